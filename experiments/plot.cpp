#include "experiments/plot.h"

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "core/atomic_write.h"
#include "core/log.h"

#ifndef DP_EXPERIMENTS_SOURCE_DIR
#error "DP_EXPERIMENTS_SOURCE_DIR must name the experiments/ source folder"
#endif

namespace dp::experiments {

std::string plot_script_path() {
  if (const char* env = std::getenv("DP_PLOT_SCRIPT"); env && *env) return env;
  return std::string(DP_EXPERIMENTS_SOURCE_DIR) + "/plot_convergence.py";
}

std::string shell_quote(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string find_python() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("DP_PYTHON"); env && *env) candidates.emplace_back(env);
  candidates.emplace_back("python3");
  candidates.emplace_back("/usr/bin/python3");  // Debian's, when PATH has another python3 first
  for (const auto& c : candidates)
    if (std::system((shell_quote(c) + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) == 0) return c;
  return {};
}

std::string make_convergence_plot(const std::string& csv, const std::string& out_prefix, const std::string& title) {
  const std::string script = plot_script_path();
  if (!std::filesystem::exists(script)) {
    log::warn("no convergence plot: plot script ", script, " not found (set DP_PLOT_SCRIPT)");
    return {};
  }
  const std::string python = find_python();
  if (python.empty()) {
    log::warn("no convergence plot: no python3 with matplotlib found (Debian: python3-matplotlib; or set DP_PYTHON)");
    return {};
  }
  // The script writes PREFIX.tmp-<pid>.png/.svg, renamed into place once it succeeded:
  // a plot killed half-way never leaves a truncated PREFIX.png.
  const std::string png = out_prefix + ".png", svg = out_prefix + ".svg";
  const std::string tmp = core::temp_path(out_prefix);
  std::error_code ec;
  std::filesystem::remove(png, ec);
  const std::string cmd = shell_quote(python) + " " + shell_quote(script) + " " + shell_quote(csv) + " --out " +
                          shell_quote(tmp) + " --title " + shell_quote(title);
  const bool ok = std::system(cmd.c_str()) == 0 && std::filesystem::exists(tmp + ".png");
  if (ok) std::filesystem::rename(tmp + ".png", png, ec);
  if (ok && !ec && std::filesystem::exists(tmp + ".svg")) std::filesystem::rename(tmp + ".svg", svg, ec);
  std::filesystem::remove(tmp + ".png", ec);
  std::filesystem::remove(tmp + ".svg", ec);
  if (!ok || !std::filesystem::exists(png)) {
    log::warn("no convergence plot: '", cmd, "' failed");
    return {};
  }
  return png;
}

}  // namespace dp::experiments
