// G-PT vs PT at equal wall time (Kettunen et al. 2015, Sec. 7 protocol): for each scene a
// long PT reference, then G-PT with a time budget and PT with G-PT's total wall time
// (rendering + both Poisson solves), relMSE (core/metrics.h: mean over pixels and
// channels of (X - R)^2 / (R^2 + 1e-3)) of PT, G-PT primal, G-PT L1 and G-PT L2 against
// the reference, and the time per sample of each (overhead ratio = G-PT / PT, rendering
// only). The resolution is reduced through the scene's camera (a YAML variant in memory).
// Usage: bench_gpt SCENE.yaml... [--res N] [--ref-seconds S] [--seconds S] [--threads T]
//                  [--shifts reconnection,manifold[:always]] [--region X0 Y0 X1 Y1] [--diagnose N] [--seed S]
//                  [--seeds N] [--gradvar RUNS SPP]
// (--seed offsets the seeds of the equal-time runs, --seeds N repeats them for seeds
// seed .. seed+N-1 against one reference; every shift row of a scene uses the
// same G-PT seed, so its base paths are the same and the rows differ by the shift.)
// Prints one CSV row per scene and G-PT shift (`--set shift=...`; each row has its own
// equal-time PT run; reference noise is included in every relMSE; the reference has
// ref-seconds / seconds times the samples of the equal-time runs). --region (fractions of
// the image, e.g. the caustic under the glass sphere of cornell_specular.yaml: 0.5 0.78
// 0.9 0.97) adds the relMSE of PT, L1 and L2 over that window. G-PT's shift counters
// (failures by cause, steps per strategy, manifold walks) go to stderr.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/metrics.h"
#include "core/rng.h"
#include "gradients/manifold_shift.h"
#include "pathspace/path_builder.h"
#include "integrators/integrator.h"
#include "manifold/mesh_normals.h"
#include "scene/loaders/loader.h"

using namespace dp;

namespace {
const core::Image& layer(const integrators::RenderResult& r, const std::string& name) {
  for (const auto& l : r.layers)
    if (l.name == name) return l.image;
  return r.layers[0].image;
}

// A --shifts item: a shift name, optionally ":" and the manifold walk strategy
// (manifold:always, manifold:fallback; gradients/manifold_shift.h).
void set_shift(integrators::Settings& settings, const std::string& item) {
  const auto colon = item.find(':');
  settings.set("shift", item.substr(0, colon));
  if (colon != std::string::npos) settings.set("manifold_walk", item.substr(colon + 1));
}

integrators::RenderResult render(const scene::Scene& s, const std::string& name, double seconds, int threads,
                                 uint64_t seed, const std::string& shift = "") {
  integrators::Settings settings;
  if (!shift.empty()) set_shift(settings, shift);
  auto in = integrators::make_integrator(name, settings);
  integrators::RenderOptions opt;
  opt.time_budget = seconds;
  opt.threads = threads;
  opt.seed = seed;
  opt.quiet = true;
  opt.max_depth = s.integrator_defaults().max_depth;
  return in->render(s, opt);
}

// relMSE (core/metrics.h definition) over the window [x0, x1) x [y0, y1) (fractions).
double region_relmse(const core::Image& x, const core::Image& r, const double* win) {
  const int w = r.width(), h = r.height();
  const int x0 = int(win[0] * w), y0 = int(win[1] * h), x1 = int(win[2] * w), y1 = int(win[3] * h);
  double sum = 0;
  int64_t n = 0;
  for (int y = y0; y < y1; ++y)
    for (int px = x0; px < x1; ++px)
      for (int c = 0; c < 3; ++c) {
        const double a = double(x(px, y)[c]), b = double(r(px, y)[c]);
        if (!std::isfinite(a)) continue;
        sum += (a - b) * (a - b) / (b * b + core::kRelMseEpsilon);
        ++n;
      }
  return n > 0 ? sum / double(n) : 0.0;
}

std::unique_ptr<scene::Scene> load_at_resolution(const std::string& path, int res) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text =
      std::regex_replace(ss.str(), std::regex(R"(resolution:\s*\[[^\]]*\])"),
                         "resolution: [" + std::to_string(res) + ", " + std::to_string(res) + "]");
  return scene::load_scene_yaml_string(text, path, {manifold::normal_estimation_hook()});
}

// --diagnose N: where the gradients of a scene come from. N base walks (G-PT's sampling)
// in random pixels, each shifted one pixel right by the reconnection and the manifold
// shift. Every BSDF path that reaches an emitter at x_k (k >= 2) is classed as
//   caustic:  a connectable vertex before a specular chain ending at the emitter (L S+ D..);
//   specular: only non-connectable vertices between camera and emitter (seen in a mirror);
//   other.
// Per class and shift: the share of failed shifts (by cause), offsets that exist but
// carry no light (the offset missed the emitter), and the squared gradient of the path
// (luminance), unweighted (f(Tx)|T'| - f(x))^2 / p^2 and with the two-direction symmetric
// MIS weight w = 1 / (1 + r^2), r = p_j(Tx)|T'| / p_i(x) (gradients/mis.h without the NEE
// terms: exact for caustic and specular paths, whose last scattering vertex has no NEE).
// The shares of the total say which paths make the gradient variance.
void diagnose(const scene::Scene& s, const std::string& path_name, int n) {
  pathspace::WalkOptions wo;
  wo.max_depth = s.integrator_defaults().max_depth;
  const pathspace::PathBuilder builder(s, wo);
  const gradients::ReconnectionShiftOptions ro{wo.shift_threshold, true};
  const gradients::ReconnectionShift rs(s, ro);
  gradients::ManifoldShiftOptions mo;
  mo.reconnection = ro;
  const gradients::ManifoldShift ms(s, mo);
  const gradients::Shift* shifts[2] = {&rs, &ms};
  struct Acc {
    int64_t paths = 0, dark = 0;
    int64_t fail[gradients::kShiftStatusCount] = {};
    double sq = 0, base_sq = 0, wsq = 0;
    std::vector<double> log_ratio;  // |log10 r| of offsets that carry light
  };
  Acc acc[2][3];
  core::Rng rng(99, 1);
  pathspace::IndependentStream stream(rng);
  pathspace::Path x;
  gradients::ShiftResult r;
  const int w = s.camera().width(), h = s.camera().height();
  auto lum = [](const Rgbd& c) { return (c[0] + c[1] + c[2]) / 3.0; };
  for (int i = 0; i < n; ++i) {
    builder.build(int(rng.uniform_double() * (w - 1)), int(rng.uniform_double() * h), stream, x);
    for (int t = 0; t < 2; ++t) {
      shifts[t]->shift(x, Vec2(1, 0), r);
      Rgbd beta = Rgbd::Ones(), beta_o = Rgbd::Ones();
      double ratio = 1.0;
      for (int k = 2; k < x.size(); ++k) {
        beta *= x[k - 1].f_cos.cast<double>() / (x[k - 1].pdf * double(x[k - 1].rr));
        const bool alive = k < r.alive;
        if (alive) {
          beta_o *= r.path[k - 1].f_cos.cast<double>() * r.jacobian[size_t(k - 1)] / (x[k - 1].pdf * double(x[k - 1].rr));
          ratio *= r.path[k - 1].pdf * r.jacobian[size_t(k - 1)] / x[k - 1].pdf;
        }
        if (is_black(x[k].emission)) continue;
        int cls = 2;
        if (!x[k - 1].connectable) {
          int j = k - 1;
          while (j >= 1 && !x[j].connectable) --j;
          cls = j >= 1 ? 0 : 1;
        }
        const double fb = lum(beta * x[k].emission.cast<double>());
        const double fo = alive ? lum(beta_o * r.path[k].emission.cast<double>()) : 0.0;
        Acc& a = acc[t][cls];
        ++a.paths;
        if (!alive) ++a.fail[size_t(r.status)];
        else if (!(fo > 0.0)) ++a.dark;
        a.sq += (fo - fb) * (fo - fb);
        const double wgt = alive ? 1.0 / (1.0 + ratio * ratio) : 1.0;
        if (alive && fo > 0.0 && ratio > 0.0) a.log_ratio.push_back(std::abs(std::log10(ratio)));
        a.wsq += wgt * wgt * (fo - fb) * (fo - fb);
        a.base_sq += fb * fb;
      }
    }
  }
  static const char* kClass[3] = {"caustic", "specular", "other"};
  for (int t = 0; t < 2; ++t) {
    double total = 0, wtotal = 0;
    for (const Acc& a : acc[t]) total += a.sq, wtotal += a.wsq;
    for (int c = 0; c < 3; ++c) {
      const Acc& a = acc[t][c];
      if (a.paths == 0) continue;
      std::fprintf(stderr, "diagnose,%s,%s,%s,paths %lld", path_name.c_str(), shifts[t]->name().c_str(), kClass[c],
                   (long long)a.paths);
      for (int f = 1; f < gradients::kShiftStatusCount; ++f)
        std::fprintf(stderr, ",fail_%s %.1f%%", gradients::to_string(gradients::ShiftStatus(f)),
                     100.0 * double(a.fail[f]) / double(a.paths));
      std::fprintf(stderr,
                   ",dark offset %.1f%%,sq grad share %.1f%%,sq grad / sq base %.3f,MIS-weighted: share %.1f%% sq grad / "
                   "sq base %.3f\n",
                   100.0 * double(a.dark) / double(a.paths), 100.0 * a.sq / total, a.sq / a.base_sq,
                   100.0 * a.wsq / wtotal, a.wsq / a.base_sq);
      std::vector<double> lr = a.log_ratio;
      std::sort(lr.begin(), lr.end());
      auto q = [&](double f) { return lr.empty() ? 0.0 : lr[std::min(lr.size() - 1, size_t(f * double(lr.size())))]; };
      std::fprintf(stderr, "diagnose,%s,%s,%s,lit offsets %zu,|log10 r| median %.3f p90 %.3f p99 %.3f\n",
                   path_name.c_str(), shifts[t]->name().c_str(), kClass[c], lr.size(), q(0.5), q(0.9), q(0.99));
    }
  }
}

// --gradvar RUNS SPP: per-pixel variance of G-PT's gradients (dx, dy) and of its
// reconstructions over RUNS independent renders of SPP samples per pixel (equal samples,
// not equal time), averaged over the --region window and over the image, per shift.
void gradient_variance(const scene::Scene& s, const std::string& path_name, const std::vector<std::string>& shifts,
                       int runs, int spp, int threads, const double* win) {
  const int w = s.camera().width(), h = s.camera().height();
  const int x0 = int(win[0] * w), y0 = int(win[1] * h), x1 = int(win[2] * w), y1 = int(win[3] * h);
  for (const auto& shift : shifts) {
    const char* names[4] = {"dx", "dy", "recon_l1", "recon_l2"};
    std::vector<std::vector<double>> sum(4, std::vector<double>(size_t(w * h), 0.0)), sq = sum;
    for (int r = 0; r < runs; ++r) {
      integrators::Settings settings;
      set_shift(settings, shift);
      auto in = integrators::make_integrator("gpt", settings);
      integrators::RenderOptions opt;
      opt.spp = spp;
      opt.threads = threads;
      opt.seed = 500 + uint64_t(r);
      opt.quiet = true;
      opt.max_depth = s.integrator_defaults().max_depth;
      const auto res = in->render(s, opt);
      for (int l = 0; l < 4; ++l) {
        const core::Image& img = layer(res, names[l]);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const double v = double(img(x, y).sum()) / 3.0;
            sum[size_t(l)][size_t(y * w + x)] += v;
            sq[size_t(l)][size_t(y * w + x)] += v * v;
          }
      }
    }
    std::fprintf(stderr, "gradvar,%s,%s,runs %d spp %d", path_name.c_str(), shift.c_str(), runs, spp);
    for (int l = 0; l < 4; ++l) {
      double vr = 0, va = 0;
      int nr = 0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const double m = sum[size_t(l)][size_t(y * w + x)] / runs;
          const double var = (sq[size_t(l)][size_t(y * w + x)] - runs * m * m) / (runs - 1);
          va += var;
          if (x >= x0 && x < x1 && y >= y0 && y < y1) vr += var, ++nr;
        }
      std::fprintf(stderr, ",%s var region %.4g image %.4g", names[l], nr ? vr / nr : 0.0, va / (w * h));
    }
    std::fprintf(stderr, "\n");
  }
}
}  // namespace

int main(int argc, char** argv) {
  int res = 128, threads = 2;
  double ref_seconds = 60, seconds = 6;
  std::vector<std::string> scenes, shifts = {"reconnection", "manifold"};
  double region[4] = {0, 0, 1, 1};
  int diagnose_paths = 0;
  uint64_t seed = 0;
  int seeds = 1;
  int gradvar_runs = 0, gradvar_spp = 0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--res") && i + 1 < argc) res = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--ref-seconds") && i + 1 < argc) ref_seconds = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc) seconds = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--shifts") && i + 1 < argc) {
      shifts.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');) shifts.push_back(item);
    } else if (!std::strcmp(argv[i], "--gradvar") && i + 2 < argc) {
      gradvar_runs = std::atoi(argv[++i]);
      gradvar_spp = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (!std::strcmp(argv[i], "--seeds") && i + 1 < argc) {
      seeds = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--diagnose") && i + 1 < argc) {
      diagnose_paths = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--region") && i + 4 < argc) {
      for (double& v : region) v = std::atof(argv[++i]);
    }
    else scenes.emplace_back(argv[i]);
  }
  if (gradvar_runs > 1) {
    for (const auto& path : scenes)
      gradient_variance(*load_at_resolution(path, res), path, shifts, gradvar_runs, gradvar_spp, threads, region);
    return 0;
  }
  if (diagnose_paths > 0) {
    for (const auto& path : scenes) diagnose(*load_at_resolution(path, res), path, diagnose_paths);
    return 0;
  }
  std::printf("scene,seed,shift,resolution,threads,ref_spp,gpt_spp,gpt_wall_s,gpt_render_s,gpt_solve_s,pt_spp,pt_wall_s,"
              "pt_ms_per_spp,gpt_ms_per_spp,overhead,relmse_pt,relmse_gpt_primal,relmse_gpt_l1,relmse_gpt_l2,"
              "pt_over_l1,pt_over_l2,region_relmse_pt,region_relmse_l1,region_relmse_l2\n");
  for (const auto& path : scenes) {
    const auto s = load_at_resolution(path, res);
    const auto ref = render(*s, "path", ref_seconds, threads, 7);
    for (uint64_t sd = seed; sd < seed + uint64_t(seeds); ++sd)
    for (const auto& shift : shifts) {
      auto gpt = render(*s, "gpt", seconds, threads, 11 + 1000 * sd, shift);
      auto number = [&](const char* key) { return std::stod(gpt.info[key].dump()); };  // core::Json writes only
      const double gpt_render = number("render_seconds");
      const double gpt_solve = number("solve_l1_seconds") + number("solve_l2_seconds");
      const auto pt = render(*s, "path", gpt.wall_seconds, threads, 13 + 1000 * sd);
      const core::Image& R = ref.layers[0].image;
      const double e_pt = core::relmse(pt.layers[0].image, R);
      const double e_primal = core::relmse(layer(gpt, "primal"), R);
      const double e_l1 = core::relmse(layer(gpt, "recon_l1"), R);
      const double e_l2 = core::relmse(layer(gpt, "recon_l2"), R);
      const double pt_ms = 1e3 * pt.wall_seconds / double(pt.min_spp);
      const double gpt_ms = 1e3 * gpt_render / double(gpt.min_spp);
      std::printf("%s,%llu,%s,%d,%d,%lld,%lld,%.2f,%.2f,%.3f,%lld,%.2f,%.2f,%.2f,%.2f,%.5g,%.5g,%.5g,%.5g,%.2f,%.2f,%.5g,%.5g,"
                  "%.5g\n",
                  path.c_str(), (unsigned long long)sd, shift.c_str(), res, threads, (long long)ref.min_spp, (long long)gpt.min_spp,
                  gpt.wall_seconds, gpt_render, gpt_solve, (long long)pt.min_spp, pt.wall_seconds, pt_ms, gpt_ms,
                  gpt_ms / pt_ms, e_pt, e_primal, e_l1, e_l2, e_pt / e_l1, e_pt / e_l2,
                  region_relmse(pt.layers[0].image, R, region), region_relmse(layer(gpt, "recon_l1"), R, region),
                  region_relmse(layer(gpt, "recon_l2"), R, region));
      std::fflush(stdout);
      for (const auto& [name, value] : gpt.stats.counters())
        if (value != 0 && (name.rfind("gpt.shift", 0) == 0 || name.rfind("gpt.step", 0) == 0 ||
                           name.rfind("gpt.manifold", 0) == 0 || name == "gpt.nan_dropped"))
          std::fprintf(stderr, "%s,%s,%s,%lld\n", path.c_str(), shift.c_str(), name.c_str(), (long long)value);
    }
  }
  return 0;
}
