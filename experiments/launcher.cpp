#include "experiments/launcher.h"

#include <cstdio>
#include <filesystem>
#include <spawn.h>
#include <sys/wait.h>
#include <yaml-cpp/yaml.h>

#include "core/error.h"

extern char** environ;

namespace dp::experiments {

namespace fs = std::filesystem;

namespace {
std::string number_text(double v) {
  char b[32];
  std::snprintf(b, sizeof(b), "%.17g", v);
  return b;
}

// The child's JSON sidecar (read with yaml-cpp: JSON is YAML) back as core::Json.
core::Json to_json(const YAML::Node& n) {
  if (n.IsMap()) {
    core::Json j = core::Json::object();
    for (const auto& kv : n) j[kv.first.as<std::string>()] = to_json(kv.second);
    return j;
  }
  if (n.IsSequence()) {
    core::Json j = core::Json::array();
    for (const auto& e : n) j.push_back(to_json(e));
    return j;
  }
  if (!n.IsScalar() || n.Tag() == "tag:yaml.org,2002:null" || n.Scalar() == "null") return core::Json(nullptr);
  const std::string s = n.Scalar();
  if (n.Tag() == "!") return core::Json(s);  // a quoted JSON string
  if (s == "true" || s == "false") return core::Json(s == "true");
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  return end && *end == '\0' && !s.empty() ? core::Json(v) : core::Json(s);
}

std::string command_text(const std::vector<std::string>& argv) {
  std::string c;
  for (const auto& a : argv) c += (c.empty() ? "" : " ") + a;
  return c;
}
}  // namespace

LaunchedRender launch_render(const std::vector<std::string>& launcher, const std::string& scene,
                             const std::string& integrator,
                             const std::vector<std::pair<std::string, std::string>>& settings,
                             const integrators::RenderOptions& options, const std::string& work_dir) {
  fs::create_directories(work_dir);
  const std::string out = (fs::path(work_dir) / "point.exr").string();
  std::vector<std::string> argv = launcher;
  argv.push_back(fs::read_symlink("/proc/self/exe").string());
  argv.push_back("render");
  argv.insert(argv.end(), {scene, "--integrator", integrator, "--seed", std::to_string(options.seed), "--max-depth",
                           std::to_string(options.max_depth), "--quiet", "--out", out});
  if (options.time_budget > 0) argv.insert(argv.end(), {"--time", number_text(options.time_budget)});
  else argv.insert(argv.end(), {"--spp", std::to_string(options.spp)});
  if (options.threads > 0) argv.insert(argv.end(), {"--threads", std::to_string(options.threads)});
  for (const auto& [k, v] : settings) argv.insert(argv.end(), {"--set", k + "=" + v});

  std::vector<char*> cargv;
  for (auto& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, cargv[0], nullptr, nullptr, cargv.data(), environ) != 0)
    throw Error("launcher: cannot start '" + argv[0] + "' (" + command_text(argv) + ")");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error("launcher: '" + command_text(argv) + "' failed (" +
                (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                   : "signal " + std::to_string(WTERMSIG(status))) +
                ")");
  const std::string json = (fs::path(work_dir) / "point.json").string();
  if (!fs::exists(out) || !fs::exists(json))
    throw Error("launcher: '" + command_text(argv) + "' wrote no " + out + " (is it a deltapath render?)");
  LaunchedRender r;
  r.layers = core::read_exr_layers(out);
  const YAML::Node side = YAML::LoadFile(json);
  r.min_spp = side["spp_min"].as<int64_t>(0);
  r.max_spp = side["spp_max"].as<int64_t>(0);
  r.wall_seconds = side["wall_seconds"].as<double>(0.0);
  r.partial = side["partial"].as<bool>(false);
  if (side["counters"]) r.counters = to_json(side["counters"]);
  if (side["info"]) r.info = to_json(side["info"]);
  if (side["ranks"]) r.info["ranks"] = side["ranks"].as<int>(1);
  fs::remove_all(work_dir);  // the runner writes the point's own files
  return r;
}

}  // namespace dp::experiments
