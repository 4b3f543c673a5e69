#include "experiments/config.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "scene/loaders/yaml/yaml_values.h"

namespace dp::experiments {

namespace {
namespace yamlx = scene::yaml;
using Ctx = yamlx::Context;

std::string format_number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

ReferenceSpec parse_reference(const Ctx& ctx, const YAML::Node& node) {
  ReferenceSpec r;
  r.line = yamlx::line_of(node);
  yamlx::check_keys(ctx, node, {"file", "integrator", "spp"}, "reference");
  const bool has_file = node["file"].IsDefined();
  const bool has_render = node["integrator"].IsDefined() || node["spp"].IsDefined();
  if (has_file == has_render)
    yamlx::parse_error(ctx, node, "reference: give either {file: IMAGE} or {integrator: NAME, spp: N}");
  if (has_file) {
    r.file = yamlx::resolve_path(ctx, yamlx::get_string(ctx, node["file"], "file"));
    return r;
  }
  r.integrator = yamlx::get_string(ctx, yamlx::require(ctx, node, "integrator", "reference"), "integrator");
  const YAML::Node spp = yamlx::require(ctx, node, "spp", "reference");
  r.spp = yamlx::get_integer(ctx, spp, "spp");
  if (r.spp < 1 || r.spp > (int64_t(1) << 30)) yamlx::value_error(ctx, spp, "'spp' must be in 1 .. 2^30");
  return r;
}

void parse_budget(const Ctx& ctx, const YAML::Node& node, ExperimentConfig& c) {
  yamlx::check_keys(ctx, node, {"time", "spp"}, "budget");
  if (node.size() != 1) yamlx::parse_error(ctx, node, "budget: give exactly one of {time: [...]} or {spp: [...]}");
  const bool time = node["time"].IsDefined();
  c.budget_kind = time ? BudgetKind::time : BudgetKind::spp;
  const std::string key = time ? "time" : "spp";
  const auto items = yamlx::get_list(ctx, node[key], key, true);
  if (items.empty()) yamlx::parse_error(ctx, node[key], "budget: the list of budgets is empty");
  std::set<double> seen;
  for (const auto& n : items) {
    double v = 0;
    if (time) {
      v = yamlx::get_number(ctx, n, "time");
      if (!(v > 0)) yamlx::value_error(ctx, n, "time budgets must be > 0 seconds");
    } else {
      const long long s = yamlx::get_integer(ctx, n, "spp");
      if (s < 1 || s > (1ll << 30)) yamlx::value_error(ctx, n, "spp budgets must be in 1 .. 2^30");
      v = double(s);
    }
    if (!seen.insert(v).second) yamlx::value_error(ctx, n, "budget " + format_number(v) + " is listed twice");
    c.budgets.push_back(v);
  }
}

Run parse_run(const Ctx& ctx, const YAML::Node& node) {
  Run r;
  r.line = yamlx::line_of(node);
  yamlx::check_keys(ctx, node, {"name", "integrator", "reconstruction", "settings"}, "run");
  r.name = yamlx::get_string(ctx, yamlx::require(ctx, node, "name", "run"), "name");
  r.integrator = yamlx::get_string(ctx, yamlx::require(ctx, node, "integrator", "run"), "integrator");
  if (node["reconstruction"].IsDefined()) {
    r.reconstruction = yamlx::get_string(ctx, node["reconstruction"], "reconstruction");
    if (r.reconstruction != "l1" && r.reconstruction != "l2")
      yamlx::value_error(ctx, node["reconstruction"], "'reconstruction' must be l1 or l2, got '" + r.reconstruction + "'");
  }
  if (const YAML::Node s = node["settings"]; s.IsDefined()) {
    if (!s.IsMap()) yamlx::parse_error(ctx, s, "'settings': expected a map of integrator settings");
    for (auto it = s.begin(); it != s.end(); ++it) {
      const std::string key = yamlx::get_string(ctx, it->first, "settings key");
      if (!it->second.IsScalar()) yamlx::parse_error(ctx, it->second, "setting '" + key + "': expected a single value");
      if (key == "reconstruction" && !r.reconstruction.empty())
        yamlx::parse_error(ctx, it->first, "'reconstruction' is given both as a run key and in settings");
      for (const auto& kv : r.settings)
        if (kv.first == key) yamlx::parse_error(ctx, it->first, "duplicate setting '" + key + "'");
      r.settings.emplace_back(key, it->second.Scalar());
    }
  }
  r.slug = slugify(r.name);
  if (r.slug.empty()) yamlx::value_error(ctx, node["name"], "run name '" + r.name + "' has no letters or digits");
  return r;
}

Metric parse_metric(const Ctx& ctx, const YAML::Node& node) {
  Metric m;
  // (YAML::Node's operator= writes through to the document: pick the node by reset().)
  YAML::Node name_node;
  name_node.reset(node);
  if (node.IsMap()) {
    yamlx::check_keys(ctx, node, {"metric", "discard", "crop"}, "metric");
    name_node.reset(yamlx::require(ctx, node, "metric", "metric"));
    if (node["discard"].IsDefined()) {
      const long long d = yamlx::get_integer(ctx, node["discard"], "discard");
      if (d < 0) yamlx::value_error(ctx, node["discard"], "'discard' must be >= 0");
      m.discard = size_t(d);
    }
    if (node["crop"].IsDefined()) {
      const long long i = yamlx::get_integer(ctx, node["crop"], "crop");
      if (i < 0 || i > 1'000'000) yamlx::value_error(ctx, node["crop"], "'crop' must be an index into 'crops' (0, 1, ...)");
      m.crop = int(i);
    }
  }
  m.name = yamlx::get_string(ctx, name_node, "metric");
  if (m.name != "relmse" && m.name != "mse" && m.name != "mape")
    yamlx::value_error(ctx, name_node, "unknown metric '" + m.name + "' (available: relmse, mse, mape)");
  return m;
}

Crop parse_crop(const Ctx& ctx, const YAML::Node& node) {
  if (!node.IsSequence() || node.size() != 4) yamlx::parse_error(ctx, node, "crop: expected [x, y, w, h]");
  Crop c;
  c.line = yamlx::line_of(node);
  long long v[4];
  for (size_t i = 0; i < 4; ++i) {
    v[i] = yamlx::get_integer(ctx, node[i], "crop");
    if (v[i] < 0 || v[i] > 1'000'000) yamlx::value_error(ctx, node[i], "crop values must be in 0 .. 1000000");
  }
  c.x = int(v[0]);
  c.y = int(v[1]);
  c.w = int(v[2]);
  c.h = int(v[3]);
  if (c.w < 1 || c.h < 1) yamlx::value_error(ctx, node, "crop width and height must be >= 1");
  return c;
}

ExperimentConfig parse_root(const Ctx& ctx, const YAML::Node& root) {
  if (!root.IsDefined() || root.IsNull()) throw ParseError("empty experiment file", ctx.file, 1);
  yamlx::check_keys(ctx, root, {"name", "scene", "reference", "budget", "seeds", "runs", "metrics", "crops", "output", "launcher"},
                    "experiment");
  ExperimentConfig c;
  c.file = ctx.file;
  c.name = yamlx::get_string(ctx, yamlx::require(ctx, root, "name", "experiment"), "name");
  c.scene = yamlx::resolve_path(ctx, yamlx::get_string(ctx, yamlx::require(ctx, root, "scene", "experiment"), "scene"));
  c.reference = parse_reference(ctx, yamlx::require(ctx, root, "reference", "experiment"));
  parse_budget(ctx, yamlx::require(ctx, root, "budget", "experiment"), c);
  if (const YAML::Node s = root["seeds"]; s.IsDefined()) {
    const long long n = yamlx::get_integer(ctx, s, "seeds");
    if (n < 1 || n > 10000) yamlx::value_error(ctx, s, "'seeds' must be in 1 .. 10000");
    c.seeds = int(n);
  }
  const YAML::Node runs = yamlx::require(ctx, root, "runs", "experiment");
  const auto run_nodes = yamlx::get_list(ctx, runs, "runs");
  if (run_nodes.empty()) yamlx::parse_error(ctx, runs, "'runs' is empty");
  for (const auto& n : run_nodes) {
    Run r = parse_run(ctx, n);
    for (const auto& o : c.runs)
      if (o.slug == r.slug)
        yamlx::value_error(ctx, n["name"], "run name '" + r.name + "' collides with '" + o.name + "' (file name " + r.slug + ")");
    c.runs.push_back(std::move(r));
  }
  if (const YAML::Node m = root["metrics"]; m.IsDefined()) {
    const auto items = yamlx::get_list(ctx, m, "metrics");
    if (items.empty()) yamlx::parse_error(ctx, m, "'metrics' is empty");
    for (const auto& n : items) {
      Metric mt = parse_metric(ctx, n);
      for (const auto& o : c.metrics)
        if (o.column() == mt.column()) yamlx::value_error(ctx, n, "metric '" + mt.column() + "' is listed twice");
      c.metrics.push_back(mt);
    }
  } else {
    c.metrics.push_back(Metric{"relmse", 0});
  }
  if (const YAML::Node cr = root["crops"]; cr.IsDefined())
    for (const auto& n : yamlx::get_list(ctx, cr, "crops")) c.crops.push_back(parse_crop(ctx, n));
  if (const YAML::Node m = root["metrics"]; m.IsDefined())
    for (size_t i = 0; i < c.metrics.size(); ++i)
      if (c.metrics[i].crop >= int(c.crops.size()))
        yamlx::value_error(ctx, m[i]["crop"], "metric crop " + std::to_string(c.metrics[i].crop) + " does not exist (" +
                                                  std::to_string(c.crops.size()) + " crops listed)");
  if (const YAML::Node o = root["output"]; o.IsDefined())
    c.output = yamlx::resolve_path(ctx, yamlx::get_string(ctx, o, "output"));
  else
    c.output = yamlx::resolve_path(ctx, "results/" + slugify(c.name));
  if (const YAML::Node l = root["launcher"]; l.IsDefined()) {
    std::istringstream words(yamlx::get_string(ctx, l, "launcher"));
    for (std::string w; words >> w;) c.launcher.push_back(w);
    if (c.launcher.empty()) yamlx::value_error(ctx, l, "'launcher' is empty (e.g. mpirun -np 4)");
  }
  return c;
}

Ctx make_ctx(const std::string& path) {
  return Ctx{path, std::filesystem::path(path).parent_path()};
}

ExperimentConfig parse_node(const std::string& text, const std::string& path) {
  const Ctx ctx = make_ctx(path);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ParseError(e.msg, path, e.mark.line >= 0 ? e.mark.line + 1 : 0);
  }
  try {
    return parse_root(ctx, root);
  } catch (const YAML::Exception& e) {
    throw ParseError(e.msg, path, e.mark.line >= 0 ? e.mark.line + 1 : 0);
  }
}
}  // namespace

std::string Metric::column() const {
  std::string c = discard > 0 ? name + "_discard" + std::to_string(discard) : name;
  return crop >= 0 ? c + "_crop" + std::to_string(crop) : c;
}

std::string ExperimentConfig::budget_text(double b) const {
  return format_number(b) + (budget_kind == BudgetKind::time ? " s" : " spp");
}

std::string ExperimentConfig::budget_label(double b) const {
  return budget_kind == BudgetKind::time ? "t" + format_number(b) + "s" : "spp" + format_number(b);
}

std::string slugify(const std::string& name) {
  std::string s;
  bool dash = false;
  for (char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c)) {
      if (dash && !s.empty()) s += '-';
      s += char(std::tolower(c));
      dash = false;
    } else {
      dash = true;
    }
  }
  return s;
}

ExperimentConfig parse_experiment(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw IoError("cannot open experiment file", path);
  std::ostringstream ss;
  ss << f.rdbuf();
  return parse_node(ss.str(), path);
}

ExperimentConfig parse_experiment_string(const std::string& text, const std::string& path) {
  return parse_node(text, path);
}

}  // namespace dp::experiments
