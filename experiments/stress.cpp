#include "experiments/stress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "core/timer.h"
#include "experiments/results_csv.h"
#include "experiments/stress_scenes.h"
#include "integrators/integrator.h"

namespace dp::experiments {

namespace {
bool contains(const std::string& s, const char* part) { return s.find(part) != std::string::npos; }
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
bool is_failure_counter(const std::string& name) {
  return contains(name, "fail") || contains(name, "jacobian") || contains(name, "outlier") ||
         contains(name, "diverged") || contains(name, "not_invertible");
}
}  // namespace

uint64_t StressReport::nonfinite_pixels() const {
  uint64_t n = 0;
  for (const auto& c : cases) n += c.nonfinite_pixels;
  return n;
}

int64_t StressReport::samples_dropped() const {
  int64_t n = 0;
  for (const auto& c : cases) n += c.samples_dropped;
  return n;
}

namespace {

// Integrators whose settings select another algorithm, stressed as well (name:key=value,...).
constexpr const char* kSettingVariants[] = {"mlt:mutations=path", "gdmlt:mutations=path", "beam:kernel=1d",
                                            "volpath:mnee_shapes=true,light_tracing=true"};

// Quick mode: the photon-beam and photon-plane estimators trace this many light paths per
// iteration instead of their default 20 000. Each of their paths meets ~10-100x as many
// camera segments as a photon point does, so at the defaults these four took ~190 of the
// ~240 s of `--quick` (session 23); the full run keeps the defaults.
constexpr const char* kQuickPhotonIntegrators[] = {"beam", "gbeam", "plane", "gplane"};
constexpr const char* kQuickPhotons = "2000";

// "name" or "name:key=value,key=value" (the settings of a variant).
std::unique_ptr<integrators::Integrator> make_variant(const std::string& spec, integrators::Settings& settings,
                                                      bool quick) {
  const size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  if (quick && !settings.has("photons"))
    for (const char* n : kQuickPhotonIntegrators)
      if (name == n) settings.set("photons", kQuickPhotons, "stress --quick");
  if (colon == std::string::npos) return integrators::make_integrator(spec, settings);
  size_t at = colon + 1;
  while (at < spec.size()) {
    const size_t end = std::min(spec.find(',', at), spec.size());
    const std::string kv = spec.substr(at, end - at);
    const size_t eq = kv.find('=');
    if (eq == std::string::npos) throw ValueError("stress variant '" + spec + "': expected key=value, got '" + kv + "'", "--integrators");
    settings.set(kv.substr(0, eq), kv.substr(eq + 1));
    at = end + 1;
  }
  return integrators::make_integrator(name, settings);
}

}  // namespace

StressReport run_stress(const StressOptions& options) {
  std::vector<std::string> names = options.integrators.empty() ? integrators::integrator_names() : options.integrators;
  if (options.integrators.empty())
    for (const char* variant : kSettingVariants) names.push_back(variant);
  const int variants = options.variants > 0 ? options.variants : (options.quick ? 2 : 4);
  const int resolution = options.quick ? 32 : 64;
  const int spp = options.quick ? 4 : 16;
  if (!options.image_dir.empty()) std::filesystem::create_directories(options.image_dir);
  StressReport report;
  for (const auto& family : stress_families())
    for (const auto& name : names) {
      StressCase c;
      c.family = family;
      c.integrator = name;
      for (int v = 0; v < variants; ++v) {
        const StressScene s = make_stress_scene(family, v, options.seed, resolution);
        integrators::Settings settings;
        auto integrator = make_variant(name, settings, options.quick);
        if (s.scene->caps().has_media && !integrator->renders_media()) {  // it would render the media as vacuum
          c.skipped = "no media support";
          break;
        }
        bool grids = false;
        for (const auto& m : s.scene->media()) grids = grids || m.heterogeneous();
        if (grids && !integrator->renders_grid_media()) {
          c.skipped = "no grid media support";
          break;
        }
        integrators::RenderOptions opt;
        opt.spp = spp;
        opt.seed = options.seed + uint64_t(v);
        opt.threads = options.threads;
        opt.max_depth = s.max_depth;
        opt.quiet = true;
        core::Timer timer;
        const integrators::RenderResult r = integrator->render(*s.scene, opt);
        c.seconds += timer.seconds();
        ++c.renders;
        if (!options.image_dir.empty()) {
          core::Image preview = r.layers.at(0).image;
          preview.zero_nonfinite();
          core::write_png((std::filesystem::path(options.image_dir) /
                           (family + "-" + std::to_string(v) + "-" + name + ".png")).string(), preview);
        }
        for (const auto& [k, value] : r.stats.counters()) {
          if (ends_with(k, "nan_dropped")) c.samples_dropped += value;
          else if (is_failure_counter(k) && value != 0) c.failures[k] += value;
          else if (contains(k, "max")) c.maxima[k] = std::max(c.maxima[k], value);
        }
        for (const auto& layer : r.layers) {
          const std::string lname = layer.name.empty() ? "RGB" : layer.name;
          const size_t bad = layer.image.count_nonfinite();
          if (bad > 0) {
            c.nonfinite_pixels += bad;
            if (!contains(c.nonfinite_layers, lname.c_str())) c.nonfinite_layers += (c.nonfinite_layers.empty() ? "" : " ") + lname;
            log::error("stress: ", family, "#", v, " ", name, ": ", bad, " non-finite pixels in layer ", lname);
          }
          for (const Rgb& px : layer.image.pixels())
            for (int ch = 0; ch < 3; ++ch)
              if (std::isfinite(px[ch]) && std::abs(double(px[ch])) > c.max_value) {
                c.max_value = std::abs(double(px[ch]));
                c.max_layer = lname;
              }
        }
      }
      report.cases.push_back(std::move(c));
    }
  return report;
}

std::string format_stress_report(const StressReport& report) {
  std::string out;
  char buf[512];
  std::snprintf(buf, sizeof(buf), "%-15s %-18s %7s %14s %14s %12s %-10s %8s\n", "scene", "integrator", "renders",
                "nan_dropped", "nonfinite_px", "max_value", "(layer)", "seconds");
  out += buf;
  for (const auto& c : report.cases) {
    std::snprintf(buf, sizeof(buf), "%-15s %-18s %7d %14lld %14llu %12.4g %-10s %8.2f%s\n", c.family.c_str(),
                  c.integrator.c_str(), c.renders, static_cast<long long>(c.samples_dropped),
                  static_cast<unsigned long long>(c.nonfinite_pixels), c.max_value,
                  c.max_layer.empty() ? "-" : c.max_layer.c_str(), c.seconds,
                  c.nonfinite_pixels ? ("  <- non-finite in: " + c.nonfinite_layers).c_str()
                  : c.skipped.empty() ? ""
                                      : ("  (skipped: " + c.skipped + ")").c_str());
    out += buf;
  }
  std::string fails;
  for (const auto& c : report.cases) {
    for (const auto& [k, v] : c.failures) {
      std::snprintf(buf, sizeof(buf), "  %-15s %-10s %-40s %lld\n", c.family.c_str(), c.integrator.c_str(), k.c_str(),
                    static_cast<long long>(v));
      fails += buf;
    }
    for (const auto& [k, v] : c.maxima) {
      std::snprintf(buf, sizeof(buf), "  %-15s %-10s %-40s %lld (max)\n", c.family.c_str(), c.integrator.c_str(),
                    k.c_str(), static_cast<long long>(v));
      fails += buf;
    }
  }
  out += fails.empty() ? "failure/outlier counters: none reported\n" : "failure/outlier counters by cause:\n" + fails;
  std::snprintf(buf, sizeof(buf), "total: %lld samples dropped as NaN/Inf, %llu non-finite pixels in image buffers\n",
                static_cast<long long>(report.samples_dropped()), static_cast<unsigned long long>(report.nonfinite_pixels()));
  out += buf;
  return out;
}

std::string stress_csv(const StressReport& report) {
  std::string out = "family,integrator,renders,samples_dropped,nonfinite_pixels,max_value,max_layer,seconds\n";
  char buf[256];
  for (const auto& c : report.cases) {
    std::snprintf(buf, sizeof(buf), ",%d,%lld,%llu,%.9g,", c.renders, static_cast<long long>(c.samples_dropped),
                  static_cast<unsigned long long>(c.nonfinite_pixels), c.max_value);
    out += csv_field(c.family) + "," + csv_field(c.integrator) + buf + csv_field(c.max_layer);
    std::snprintf(buf, sizeof(buf), ",%.4f\n", c.seconds);
    out += buf;
  }
  return out;
}

}  // namespace dp::experiments
