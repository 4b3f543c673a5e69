// The experiment runner on a 32x32 Cornell box with PT: output files, CSV shape,
// resumability (a second run renders nothing and reproduces the CSV; a removed marker
// or a changed setting re-renders exactly the affected points), references from files,
// early setting errors, and the layer that is scored.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "experiments/config.h"
#include "experiments/runner.h"
#include "experiments/scoring.h"
#include "tests/experiments/temp_dir.h"

using namespace dp;
using namespace dp::experiments;
namespace fs = std::filesystem;

namespace {
std::string scene_path() { return std::string(DP_SOURCE_DIR) + "/tests/experiments/data/tiny_cornell.yaml"; }

std::string experiment_text(const std::string& reference, const std::string& extra_run_settings = "") {
  return "name: runner test\nscene: " + scene_path() + "\nreference: " + reference +
         "\nbudget: {spp: [1, 2]}\nseeds: 2\nruns:\n"
         "  - {name: PT, integrator: path}\n"
         "  - {name: \"PT, BSDF only\", integrator: path, settings: {nee: false" + extra_run_settings + "}}\n"
         "metrics: [relmse, {metric: mse, discard: 3}]\noutput: out\n";
}

RunnerOptions quiet_options() {
  log::set_level(log::Level::warn);
  RunnerOptions o;
  o.render.threads = 2;
  o.render.quiet = true;
  o.progress = false;
  o.plot = false;
  return o;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Splits one CSV line (RFC 4180 quotes).
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else out.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}
}  // namespace

TEST_CASE("runner: outputs, CSV shape and resumability", "[unit]") {
  test::ExperimentTempDir dir;
  const std::string file = dir.write("exp.yaml", experiment_text("{integrator: path, spp: 16}"));
  const ExperimentConfig config = parse_experiment(file);

  const ExperimentResult first = run_experiment(config, quiet_options());
  CHECK(first.rendered == 8);
  CHECK(first.skipped == 0);
  REQUIRE(first.points.size() == 8);
  CHECK(fs::exists(dir.path("reference-cache")));  // beside the output folder
  CHECK(fs::exists(dir.path("out/report.html")));
  CHECK(fs::exists(dir.path("out/report/reference.png")));
  CHECK(fs::exists(dir.path("out/report/pt-bsdf-only-error.png")));
  for (const auto& p : first.points) {
    CHECK(fs::exists(p.exr_path));
    CHECK(p.spp == int64_t(config.budgets[p.budget]));
    CHECK(p.wall_time > 0);
    for (double m : p.metrics) CHECK(m > 0);
  }
  CHECK(fs::exists(dir.path("out/runs/pt/spp2-seed1.png")));
  CHECK(fs::exists(dir.path("out/runs/pt/spp2-seed1.json")));

  // CSV: header, then one row per (run, budget, seed) sorted by run, budget, seed.
  const std::string csv = slurp(first.csv_path);
  std::istringstream lines(csv);
  std::string line;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(lines, line)) rows.push_back(split_csv(line));
  REQUIRE(rows.size() == 9);
  CHECK(rows[0] == std::vector<std::string>{"name", "budget", "seed", "wall_time", "spp", "relmse", "mse_discard3"});
  for (size_t i = 1; i < rows.size(); ++i) CHECK(rows[i].size() == 7);
  CHECK(rows[1][0] == "PT");
  CHECK(rows[5][0] == "PT, BSDF only");
  CHECK((rows[1][1] == "1" && rows[1][2] == "0" && rows[2][2] == "1" && rows[3][1] == "2"));
  CHECK(rows[8][4] == "2");

  // Second run: nothing rendered, identical CSV, point files untouched.
  const auto stamp = fs::last_write_time(first.points[0].exr_path);
  const ExperimentResult second = run_experiment(config, quiet_options());
  CHECK(second.rendered == 0);
  CHECK(second.skipped == 8);
  CHECK(slurp(second.csv_path) == csv);
  CHECK(fs::last_write_time(first.points[0].exr_path) == stamp);

  // A point without its marker is rendered again, and only that one.
  fs::remove(point_stem(config, 0, 1, 1) + ".done");
  const ExperimentResult third = run_experiment(config, quiet_options());
  CHECK(third.rendered == 1);
  CHECK(third.skipped == 7);

  // Changing one run's settings re-renders that run's points only.
  dir.write("exp.yaml", experiment_text("{integrator: path, spp: 16}", ", rr_depth: 3"));
  const ExperimentResult fourth = run_experiment(parse_experiment(file), quiet_options());
  CHECK(fourth.rendered == 4);
  CHECK(fourth.skipped == 4);
}

TEST_CASE("runner: reference from a file, size checked", "[unit]") {
  test::ExperimentTempDir dir;
  core::write_exr(dir.path("ref.exr"), core::Image(32, 32, Rgb(0.2f, 0.2f, 0.2f)));
  core::write_exr(dir.path("small.exr"), core::Image(16, 16, Rgb(0.2f, 0.2f, 0.2f)));
  RunnerOptions o = quiet_options();
  o.report = false;
  const ExperimentResult r =
      run_experiment(parse_experiment(dir.write("a.yaml", experiment_text("{file: ref.exr}"))), o);
  CHECK(r.rendered == 8);
  CHECK(r.reference_path == dir.path("ref.exr"));
  CHECK_FALSE(fs::exists(dir.path("reference-cache")));

  const std::string bad = dir.write("b.yaml", experiment_text("{file: small.exr}"));
  try {
    run_experiment(parse_experiment(bad), o);
    FAIL("no error for a 16x16 reference");
  } catch (const ValueError& e) {
    CHECK(e.file() == bad);
    CHECK(e.line() == 3);
    CHECK(e.message().find("16x16") != std::string::npos);
  }
}

TEST_CASE("runner: a bad integrator setting fails before anything renders", "[unit]") {
  test::ExperimentTempDir dir;
  const std::string file = dir.write("exp.yaml", experiment_text("{integrator: path, spp: 16}", ", no_such_key: 1"));
  try {
    run_experiment(parse_experiment(file), quiet_options());
    FAIL("no error");
  } catch (const ValueError& e) {
    CHECK(e.file() == file + ":8");  // the run's line
    CHECK(e.message().find("no_such_key") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(dir.path("out/runs")));
  CHECK_FALSE(fs::exists(dir.path("reference-cache")));

  const std::string file2 = dir.write(
      "exp2.yaml", "name: x\nscene: " + scene_path() +
                       "\nreference: {integrator: path, spp: 4}\nbudget: {spp: [1]}\nruns:\n  - {name: X, integrator: nope}\n");
  try {
    run_experiment(parse_experiment(file2), quiet_options());
    FAIL("no error");
  } catch (const ValueError& e) {
    CHECK(e.file() == file2);
    CHECK(e.line() == 6);
    CHECK(e.message().find("unknown integrator 'nope'") != std::string::npos);
  }
}

TEST_CASE("runner: the scored layer follows `reconstruction`", "[unit]") {
  std::vector<core::NamedLayer> layers = {
      {"", core::Image(1, 1)}, {"recon_l1", core::Image(1, 1)}, {"recon_l2", core::Image(1, 1)}, {"dx", core::Image(1, 1)}};
  CHECK(scored_layer(layers, "") == 0);
  CHECK(scored_layer(layers, "l1") == 1);
  CHECK(scored_layer(layers, "l2") == 2);
  layers.resize(1);
  CHECK(scored_layer(layers, "l2") == 0);  // integrators without reconstructions: the final image
}

TEST_CASE("runner: duration format", "[unit]") {
  CHECK(format_duration(1.234) == "1.23s");
  CHECK(format_duration(45) == "45s");
  CHECK(format_duration(200) == "3m20s");
  CHECK(format_duration(3720) == "1h02m");
}
