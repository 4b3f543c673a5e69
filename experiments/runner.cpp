#include "experiments/runner.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/json.h"
#include "core/log.h"
#include "core/timer.h"
#include "experiments/integrator_setup.h"
#include "experiments/launcher.h"
#include "experiments/plot.h"
#include "experiments/report.h"
#include "experiments/results_csv.h"
#include "experiments/scoring.h"
#include "manifold/mesh_normals.h"
#include "scene/loaders/loader.h"

namespace dp::experiments {

namespace fs = std::filesystem;

namespace {

struct Marker {  // contents of a point's .done file
  std::string key, layer;
  double wall_time = 0;
  int64_t spp = 0;
};

std::optional<Marker> read_marker(const std::string& path) {
  std::ifstream f(path);
  if (!f) return std::nullopt;
  Marker m;
  std::string word;
  bool has_key = false, has_time = false, has_spp = false;
  while (f >> word) {
    if (word == "key") has_key = bool(f >> m.key);
    else if (word == "wall_time") has_time = bool(f >> m.wall_time);
    else if (word == "spp") has_spp = bool(f >> m.spp);
    else if (word == "layer") {
      std::getline(f, m.layer);
      if (!m.layer.empty() && m.layer[0] == ' ') m.layer.erase(0, 1);
    }
  }
  if (!has_key || !has_time || !has_spp) return std::nullopt;
  return m;
}

void write_marker(const std::string& path, const Marker& m) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.17g", m.wall_time);
  core::write_file_atomically(path, "key " + m.key + "\nwall_time " + buf + "\nspp " + std::to_string(m.spp) +
                                        "\nlayer " + m.layer + "\n");
}

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw IoError("cannot read", path);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Seconds per budget unit (per second of budget, or per spp), per run, for the ETA.
class EtaModel {
 public:
  EtaModel(size_t runs, BudgetKind kind) : m_seconds(runs, 0.0), m_units(runs, 0.0), m_kind(kind) {}
  void add(size_t run, double budget, double seconds) {
    m_seconds[run] += seconds;
    m_units[run] += budget;
  }
  // Estimated seconds for a point; < 0 when nothing is known yet.
  double estimate(size_t run, double budget) const {
    if (m_units[run] > 0) return budget * m_seconds[run] / m_units[run];
    double s = 0, u = 0;
    for (size_t i = 0; i < m_units.size(); ++i) s += m_seconds[i], u += m_units[i];
    if (u > 0) return budget * s / u;
    return m_kind == BudgetKind::time ? budget : -1.0;
  }

 private:
  std::vector<double> m_seconds, m_units;
  BudgetKind m_kind;
};

}  // namespace

std::string format_duration(double seconds) {
  char buf[32];
  const long s = long(seconds + 0.5);
  if (seconds < 10) std::snprintf(buf, sizeof(buf), "%.2fs", seconds);
  else if (s < 60) std::snprintf(buf, sizeof(buf), "%lds", s);
  else if (s < 3600) std::snprintf(buf, sizeof(buf), "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(buf, sizeof(buf), "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  return buf;
}

std::string point_stem(const ExperimentConfig& config, size_t run, size_t budget, int seed) {
  return (fs::path(config.output) / "runs" / config.runs.at(run).slug /
          (config.budget_label(config.budgets.at(budget)) + "-seed" + std::to_string(seed)))
      .string();
}

ExperimentResult run_experiment(const ExperimentConfig& config, const RunnerOptions& options) {
  ExperimentResult out;
  out.output_dir = config.output;
  const auto scene = scene::load_scene(config.scene, {manifold::normal_estimation_hook()});
  if (options.scene_loaded) options.scene_loaded();
  const int max_depth = scene->integrator_defaults().max_depth;
  const auto& cam = scene->camera();
  for (const auto& c : config.crops)
    if (c.x + c.w > cam.width() || c.y + c.h > cam.height())
      throw ValueError("crop [" + std::to_string(c.x) + ", " + std::to_string(c.y) + ", " + std::to_string(c.w) + ", " +
                           std::to_string(c.h) + "] is outside the " + std::to_string(cam.width()) + "x" +
                           std::to_string(cam.height()) + " image",
                       config.file, c.line);

  // Create every run's integrator first: a bad setting fails now, not after hours.
  std::vector<PreparedIntegrator> prepared;
  std::vector<std::vector<std::pair<std::string, std::string>>> run_settings;  // for a launcher's --set
  for (const auto& r : config.runs) {
    auto settings = r.settings;
    if (!r.reconstruction.empty()) settings.emplace_back("reconstruction", r.reconstruction);
    run_settings.push_back(settings);
    prepared.push_back(prepare_integrator(*scene, r.integrator, settings, config.file, r.line));
  }

  fs::create_directories(config.output);
  const fs::path parent = fs::path(config.output).parent_path();
  const std::string cache_dir = ((parent.empty() ? fs::path(".") : parent) / "reference-cache").string();
  const Reference ref = obtain_reference(config, *scene, options.render, cache_dir);
  out.reference_path = ref.path;

  const std::string scene_hash = hex64(fnv1a(read_file(config.scene)));
  const size_t total = config.runs.size() * config.budgets.size() * size_t(config.seeds);
  EtaModel eta(config.runs.size(), config.budget_kind);
  std::vector<PointResult> points;
  size_t index = 0;
  core::Timer wall;

  const auto key_of = [&](size_t run, size_t budget, int seed) {
    std::string k = "v1|" + scene_hash + "|" + config.runs[run].integrator + "|" + prepared[run].settings_text + "|" +
                    config.budget_label(config.budgets[budget]) + "|" + std::to_string(seed) + "|" +
                    std::to_string(max_depth);
    if (!config.launcher.empty())  // (only then: keys of existing experiments stay valid)
      for (const auto& w : config.launcher) k += "|" + w;
    return hex64(fnv1a(k));
  };

  for (int seed = 0; seed < config.seeds; ++seed)
    for (size_t b = 0; b < config.budgets.size(); ++b)
      for (size_t r = 0; r < config.runs.size(); ++r) {
        ++index;
        const Run& run = config.runs[r];
        const double budget = config.budgets[b];
        const std::string stem = point_stem(config, r, b, seed);
        PointResult p;
        p.run = r;
        p.budget = b;
        p.seed = seed;
        p.exr_path = stem + ".exr";
        const std::string key = key_of(r, b, seed);
        std::vector<core::NamedLayer> layers;

        const auto marker = read_marker(stem + ".done");
        if (marker && marker->key == key && fs::exists(p.exr_path)) {
          p.skipped = true;
          p.wall_time = marker->wall_time;
          p.spp = marker->spp;
          p.layer = marker->layer;
          layers = core::read_exr_layers(p.exr_path);
          eta.add(r, budget, p.wall_time);
          ++out.skipped;
        } else {
          if (options.progress && !options.render.quiet) {
            double remaining = 0;
            bool known = true;
            // This point and every later one (same iteration order).
            size_t k = 0;
            for (int s2 = 0; s2 < config.seeds; ++s2)
              for (size_t b2 = 0; b2 < config.budgets.size(); ++b2)
                for (size_t r2 = 0; r2 < config.runs.size(); ++r2)
                  if (++k >= index) {
                    const double e = eta.estimate(r2, config.budgets[b2]);
                    if (e < 0) known = false;
                    remaining += std::max(e, 0.0);
                  }
            std::fprintf(stderr, "experiment %s: [%zu/%zu] %s | %s | seed %d | elapsed %s, ETA %s\n",
                         config.name.c_str(), index, total, run.name.c_str(), config.budget_text(budget).c_str(), seed,
                         format_duration(wall.seconds()).c_str(), known ? format_duration(remaining).c_str() : "?");
          }
          integrators::RenderOptions opt;
          opt.seed = uint64_t(seed);
          opt.threads = options.render.threads;
          opt.max_depth = max_depth;
          opt.quiet = true;
          opt.stop = options.render.stop;
          if (config.budget_kind == BudgetKind::time) opt.time_budget = budget;
          else opt.spp = int(budget);
          core::Timer timer;
          integrators::RenderResult result;
          core::Json counters = core::Json::object(), info;
          if (config.launcher.empty()) {
            result = prepared[r].integrator->render(*scene, opt);
            for (const auto& [k, v] : result.stats.counters()) counters[k] = v;
            info = result.info;
          } else {  // a separate process (launcher.h)
            LaunchedRender lr =
                launch_render(config.launcher, config.scene, run.integrator, run_settings[r], opt, stem + ".launched");
            result.layers = std::move(lr.layers);
            result.min_spp = lr.min_spp;
            result.max_spp = lr.max_spp;
            result.wall_seconds = lr.wall_seconds;
            result.partial = lr.partial;
            counters = lr.counters;
            info = lr.info;
          }
          p.wall_time = timer.seconds();
          if (result.partial || (options.render.stop && options.render.stop->load()))
            throw Error("experiment interrupted during " + run.name + " (" + config.budget_text(budget) + ", seed " +
                            std::to_string(seed) + "); run it again to resume",
                        config.file);
          p.spp = result.min_spp;
          const size_t li = scored_layer(result.layers, run.reconstruction);
          p.layer = result.layers[li].name;

          size_t nonfinite = 0;
          for (const auto& l : result.layers) nonfinite += l.image.count_nonfinite();
          fs::create_directories(fs::path(stem).parent_path());
          core::write_exr(p.exr_path, result.layers);
          core::write_png(stem + ".png", result.layers[li].image);
          core::Json side = core::Json::object();
          side["experiment"] = config.name;
          side["run"] = run.name;
          side["scene"] = config.scene;
          side["integrator"] = run.integrator;
          side["settings"] = prepared[r].settings;
          side["budget"] = budget;
          side["budget_kind"] = config.budget_kind == BudgetKind::time ? "time" : "spp";
          side["seed"] = seed;
          side["max_depth"] = max_depth;
          side["wall_time"] = p.wall_time;
          side["render_wall_seconds"] = result.wall_seconds;
          side["spp_min"] = result.min_spp;
          side["spp_max"] = result.max_spp;
          side["scored_layer"] = p.layer.empty() ? "RGB" : p.layer;
          side["nonfinite_pixels"] = uint64_t(nonfinite);
          side["counters"] = counters;
          side["info"] = info;
          core::write_file_atomically(stem + ".json", side.dump());
          write_marker(stem + ".done", Marker{key, p.layer, p.wall_time, p.spp});
          layers = std::move(result.layers);
          eta.add(r, budget, p.wall_time);
          ++out.rendered;
        }

        const core::Image* img = nullptr;
        for (const auto& l : layers)
          if (l.name == p.layer) img = &l.image;
        if (!img) throw IoError("layer '" + p.layer + "' missing; delete the point's .done file to re-render it", p.exr_path);
        if (!img->same_size(ref.image)) throw ValueError("image size differs from the reference", p.exr_path);
        for (const auto& m : config.metrics) p.metrics.push_back(evaluate_metric(m, *img, ref.image, config.crops));
        if (!p.skipped && !options.render.quiet) {
          std::string msg = "  " + run.name + ": " + format_duration(p.wall_time) + ", " + std::to_string(p.spp) + " spp";
          for (size_t m = 0; m < config.metrics.size(); ++m) {
            char buf[64];
            std::snprintf(buf, sizeof(buf), ", %s %.4g", config.metrics[m].column().c_str(), p.metrics[m]);
            msg += buf;
          }
          log::info(msg);
        }
        points.push_back(std::move(p));
      }

  std::sort(points.begin(), points.end(), [](const PointResult& a, const PointResult& b) {
    return std::tie(a.run, a.budget, a.seed) < std::tie(b.run, b.budget, b.seed);
  });
  out.points = std::move(points);
  out.csv_path = (fs::path(config.output) / "results.csv").string();
  write_results_csv(out.csv_path, config, out.points);
  if (out.skipped > 0) log::info("experiment ", config.name, ": ", out.skipped, " of ", total, " points were already done");

  if (options.plot)
    out.plot_png = make_convergence_plot(out.csv_path, (fs::path(config.output) / "convergence").string(), config.name);
  if (options.report) out.report_path = write_report(config, out, ref.image);
  return out;
}

}  // namespace dp::experiments
