// Experiment file parsing: the full schema, relative paths, and every error class with
// the experiment file and the line of the offending node.
#include <catch2/catch.hpp>

#include "core/error.h"
#include "experiments/config.h"

using namespace dp;
using namespace dp::experiments;

namespace {
const char* kPath = "/data/exp/cbox.yaml";

const char* kFull = R"(name: cbox-gpt-vs-pt
scene: ../scenes/cornell.yaml
reference: {file: ref.exr}
budget: {time: [5, 10, 20.5]}
seeds: 3
runs:
  - {name: PT, integrator: path}
  - {name: G-PT L1, integrator: gpt, reconstruction: l1}
  - {name: G-PT L2, integrator: gpt, reconstruction: l2, settings: {alpha: 0.2, nee: true}}
metrics: [relmse, mse, {metric: relmse, discard: 10}]
crops: [[1, 2, 30, 40], [5, 6, 7, 8]]
output: results/cbox-gpt-vs-pt
)";

// Parses `text` and requires an error of type E at `line` whose message contains `part`.
template <typename E>
void expect_error(const std::string& text, int line, const std::string& part) {
  try {
    parse_experiment_string(text, kPath);
  } catch (const E& e) {
    INFO(e.what());
    CHECK(e.file() == kPath);
    CHECK(e.line() == line);
    CHECK(e.message().find(part) != std::string::npos);
    CHECK(std::string(e.what()).rfind(std::string(kPath) + ":" + std::to_string(line) + ": ", 0) == 0);
    return;
  } catch (const std::exception& e) {
    FAIL("wrong exception type: " << e.what());
  }
  FAIL("no error for:\n" << text);
}

const char* kHead = "name: x\nscene: s.yaml\nreference: {integrator: path, spp: 64}\nbudget: {spp: [1, 4]}\n";
}  // namespace

TEST_CASE("experiment config: the full schema", "[unit]") {
  const ExperimentConfig c = parse_experiment_string(kFull, kPath);
  CHECK(c.name == "cbox-gpt-vs-pt");
  CHECK(c.scene == "/data/scenes/cornell.yaml");
  CHECK(c.reference.file == "/data/exp/ref.exr");
  CHECK(c.reference.integrator.empty());
  CHECK(c.budget_kind == BudgetKind::time);
  CHECK(c.budgets == std::vector<double>{5, 10, 20.5});
  CHECK(c.seeds == 3);
  REQUIRE(c.runs.size() == 3);
  CHECK(c.runs[0].slug == "pt");
  CHECK(c.runs[1].name == "G-PT L1");
  CHECK(c.runs[1].slug == "g-pt-l1");
  CHECK(c.runs[1].reconstruction == "l1");
  CHECK(c.runs[2].line == 9);
  REQUIRE(c.runs[2].settings.size() == 2);
  CHECK(c.runs[2].settings[0] == std::pair<std::string, std::string>("alpha", "0.2"));
  CHECK(c.runs[2].settings[1] == std::pair<std::string, std::string>("nee", "true"));
  REQUIRE(c.metrics.size() == 3);
  CHECK(c.metrics[0].column() == "relmse");
  CHECK(c.metrics[1].column() == "mse");
  CHECK(c.metrics[2].column() == "relmse_discard10");
  CHECK(c.metrics[2].discard == 10);
  REQUIRE(c.crops.size() == 2);
  CHECK((c.crops[0].x == 1 && c.crops[0].y == 2 && c.crops[0].w == 30 && c.crops[0].h == 40));
  CHECK(c.output == "/data/exp/results/cbox-gpt-vs-pt");
  CHECK(c.budget_text(20.5) == "20.5 s");
  CHECK(c.budget_label(5) == "t5s");
}

TEST_CASE("experiment config: defaults and rendered references", "[unit]") {
  const ExperimentConfig c = parse_experiment_string(std::string(kHead) + "runs: [{name: PT, integrator: path}]\n", kPath);
  CHECK(c.reference.integrator == "path");
  CHECK(c.reference.spp == 64);
  CHECK(c.budget_kind == BudgetKind::spp);
  CHECK(c.budget_label(4) == "spp4");
  CHECK(c.seeds == 1);
  REQUIRE(c.metrics.size() == 1);
  CHECK(c.metrics[0].name == "relmse");
  CHECK(c.output == "/data/exp/results/x");
  CHECK(c.crops.empty());
}

TEST_CASE("experiment config: structure errors are ParseError with file:line", "[unit]") {
  const std::string runs = "runs: [{name: PT, integrator: path}]\n";
  expect_error<ParseError>(std::string(kHead) + runs + "colour: red\n", 6, "unknown key 'colour' in experiment");
  expect_error<ParseError>(std::string(kHead) + "runs:\n  - {name: PT, integrator: path, spp: 4}\n", 6,
                           "unknown key 'spp' in run");
  expect_error<ParseError>("name: x\nscene: s.yaml\nreference: {file: r.exr, seed: 3}\nbudget: {spp: [1]}\n" + runs, 3,
                           "unknown key 'seed' in reference");
  expect_error<ParseError>("name: x\nscene: s.yaml\nreference: {file: r.exr, integrator: path}\nbudget: {spp: [1]}\n" + runs,
                           3, "either");
  expect_error<ParseError>("name: x\nscene: s.yaml\nreference: {file: r.exr}\nbudget: {spp: [1], time: [2]}\n" + runs, 4,
                           "exactly one");
  expect_error<ParseError>("name: x\nscene: s.yaml\nreference: {file: r.exr}\nbudget: {spp: [1.5]}\n" + runs, 4,
                           "expected an integer");
  expect_error<ParseError>("name: x\nreference: {file: r.exr}\nbudget: {spp: [1]}\n" + runs, 1,
                           "missing required key 'scene'");
  expect_error<ParseError>(std::string(kHead) + "runs:\n  - {integrator: path}\n", 6, "missing required key 'name'");
  expect_error<ParseError>(std::string(kHead) + "runs: []\n", 5, "'runs' is empty");
  expect_error<ParseError>(std::string(kHead) + "runs:\n  - {name: PT, integrator: path, settings: {a: [1, 2]}}\n", 6,
                           "expected a single value");
  expect_error<ParseError>(std::string(kHead) + runs + "crops: [[1, 2, 3]]\n", 6, "[x, y, w, h]");
  expect_error<ParseError>(std::string(kHead) + runs + "metrics: [{metric: mse, worst: 3}]\n", 6, "unknown key 'worst'");
  expect_error<ParseError>(std::string(kHead) + runs + "seeds: [1]\n", 6, "expected an integer");
  expect_error<ParseError>(std::string(kHead) + runs + "name: y\n", 6, "duplicate key 'name'");
  expect_error<ParseError>(std::string(kHead) + "runs: [{name: PT, integrator: path}\n", 6, "");  // YAML syntax
}

TEST_CASE("experiment config: value errors are ValueError with file:line", "[unit]") {
  const std::string runs = "runs: [{name: PT, integrator: path}]\n";
  expect_error<ValueError>("name: x\nscene: s.yaml\nreference: {file: r.exr}\nbudget: {time: [5, -1]}\n" + runs, 4,
                           "must be > 0");
  expect_error<ValueError>("name: x\nscene: s.yaml\nreference: {file: r.exr}\nbudget: {time: [.inf]}\n" + runs, 4,
                           "not a finite number");
  expect_error<ValueError>("name: x\nscene: s.yaml\nreference: {file: r.exr}\nbudget:\n  spp: [4, 4]\n" + runs, 5,
                           "listed twice");
  expect_error<ValueError>("name: x\nscene: s.yaml\nreference: {integrator: path, spp: 0}\nbudget: {spp: [1]}\n" + runs, 3,
                           "'spp' must be");
  expect_error<ValueError>(std::string(kHead) + runs + "seeds: 0\n", 6, "'seeds' must be");
  expect_error<ValueError>(std::string(kHead) + runs + "metrics: [relmse, psnr]\n", 6, "unknown metric 'psnr'");
  expect_error<ValueError>(std::string(kHead) + runs + "metrics: [{metric: mse, discard: -1}]\n", 6, "'discard'");
  expect_error<ValueError>(std::string(kHead) + runs + "crops: [[0, 0, 0, 5]]\n", 6, "width and height");
  expect_error<ValueError>(std::string(kHead) + runs + "metrics: [{metric: mse, crop: -2}]\n", 6, "'crop' must be");
  expect_error<ValueError>(std::string(kHead) + runs + "crops: [[0, 0, 5, 5]]\nmetrics: [relmse, {metric: mse, crop: 1}]\n",
                           7, "metric crop 1 does not exist");
  expect_error<ValueError>(std::string(kHead) + "runs:\n  - {name: G-PT, integrator: gpt, reconstruction: l3}\n", 6,
                           "l1 or l2");
  expect_error<ValueError>(std::string(kHead) + "runs:\n  - {name: PT a, integrator: path}\n  - {name: pt-A, integrator: path}\n",
                           7, "collides");
}

TEST_CASE("experiment config: a missing file is an IoError naming it", "[unit]") {
  try {
    parse_experiment("/nonexistent/dir/exp.yaml");
    FAIL("no error");
  } catch (const IoError& e) {
    CHECK(e.file() == "/nonexistent/dir/exp.yaml");
  }
}

TEST_CASE("experiment config: slugs", "[unit]") {
  CHECK(slugify("G-PT L1") == "g-pt-l1");
  CHECK(slugify("  PT, no NEE! ") == "pt-no-nee");
  CHECK(slugify("%%") == "");
}
