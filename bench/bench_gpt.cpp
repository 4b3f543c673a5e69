// G-PT vs PT at equal wall time (Kettunen et al. 2015, Sec. 7 protocol): for each scene a
// long PT reference, then G-PT with a time budget and PT with G-PT's total wall time
// (rendering + both Poisson solves), relMSE (core/metrics.h: mean over pixels and
// channels of (X - R)^2 / (R^2 + 1e-3)) of PT, G-PT primal, G-PT L1 and G-PT L2 against
// the reference, and the time per sample of each (overhead ratio = G-PT / PT, rendering
// only). The resolution is reduced through the scene's camera (a YAML variant in memory).
// Usage: bench_gpt SCENE.yaml... [--res N] [--ref-seconds S] [--seconds S] [--threads T]
// Prints one CSV row per scene (reference noise is included in every relMSE; the
// reference has ref-seconds / seconds times the samples of the equal-time runs).
#include <cstdio>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/metrics.h"
#include "integrators/integrator.h"
#include "scene/loader.h"

using namespace dp;

namespace {
const core::Image& layer(const integrators::RenderResult& r, const std::string& name) {
  for (const auto& l : r.layers)
    if (l.name == name) return l.image;
  return r.layers[0].image;
}

integrators::RenderResult render(const scene::Scene& s, const std::string& name, double seconds, int threads,
                                 uint64_t seed) {
  integrators::Settings settings;
  auto in = integrators::make_integrator(name, settings);
  integrators::RenderOptions opt;
  opt.time_budget = seconds;
  opt.threads = threads;
  opt.seed = seed;
  opt.quiet = true;
  opt.max_depth = s.integrator_defaults().max_depth;
  return in->render(s, opt);
}

std::unique_ptr<scene::Scene> load_at_resolution(const std::string& path, int res) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text =
      std::regex_replace(ss.str(), std::regex(R"(resolution:\s*\[[^\]]*\])"),
                         "resolution: [" + std::to_string(res) + ", " + std::to_string(res) + "]");
  return scene::load_scene_yaml_string(text, path);
}
}  // namespace

int main(int argc, char** argv) {
  int res = 128, threads = 2;
  double ref_seconds = 60, seconds = 6;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--res") && i + 1 < argc) res = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--ref-seconds") && i + 1 < argc) ref_seconds = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc) seconds = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else scenes.emplace_back(argv[i]);
  }
  std::printf("scene,resolution,threads,ref_spp,gpt_spp,gpt_wall_s,gpt_render_s,gpt_solve_s,pt_spp,pt_wall_s,"
              "pt_ms_per_spp,gpt_ms_per_spp,overhead,relmse_pt,relmse_gpt_primal,relmse_gpt_l1,relmse_gpt_l2,"
              "pt_over_l1,pt_over_l2\n");
  for (const auto& path : scenes) {
    const auto s = load_at_resolution(path, res);
    const auto ref = render(*s, "path", ref_seconds, threads, 7);
    auto gpt = render(*s, "gpt", seconds, threads, 11);
    auto number = [&](const char* key) { return std::stod(gpt.info[key].dump()); };  // core::Json writes only
    const double gpt_render = number("render_seconds");
    const double gpt_solve = number("solve_l1_seconds") + number("solve_l2_seconds");
    const auto pt = render(*s, "path", gpt.wall_seconds, threads, 13);
    const core::Image& R = ref.layers[0].image;
    const double e_pt = core::relmse(pt.layers[0].image, R);
    const double e_primal = core::relmse(layer(gpt, "primal"), R);
    const double e_l1 = core::relmse(layer(gpt, "recon_l1"), R);
    const double e_l2 = core::relmse(layer(gpt, "recon_l2"), R);
    const double pt_ms = 1e3 * pt.wall_seconds / double(pt.min_spp);
    const double gpt_ms = 1e3 * gpt_render / double(gpt.min_spp);
    std::printf("%s,%d,%d,%lld,%lld,%.2f,%.2f,%.3f,%lld,%.2f,%.2f,%.2f,%.2f,%.5g,%.5g,%.5g,%.5g,%.2f,%.2f\n",
                path.c_str(), res, threads, (long long)ref.min_spp, (long long)gpt.min_spp, gpt.wall_seconds,
                gpt_render, gpt_solve, (long long)pt.min_spp, pt.wall_seconds, pt_ms, gpt_ms, gpt_ms / pt_ms, e_pt,
                e_primal, e_l1, e_l2, e_pt / e_l1, e_pt / e_l2);
    std::fflush(stdout);
  }
  return 0;
}
