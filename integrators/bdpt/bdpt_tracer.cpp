#include "integrators/bdpt/bdpt_tracer.h"

#include "pathspace/bidir_connect.h"

namespace dp::integrators {

namespace {
bool has_grid_media(const scene::Scene& scene) {
  for (const auto& m : scene.media())
    if (m.heterogeneous()) return true;
  return false;
}
}  // namespace

BdptTracer::BdptTracer(const scene::Scene& scene, const BdptSettings& settings, int max_depth)
    : m_scene(scene), m_settings(settings), m_max_depth(max_depth), m_has_grid(has_grid_media(scene)) {}

bool BdptTracer::sample(const Vec2& raster, core::Rng& rng, BdptScratch& sc, Rgb& L, std::vector<Splat>& splats,
                        BdptCounters& counters) const {
  // Grid media: delta tracking in the walks, ratio tracking on connections (bidir_media.h);
  // null in scenes without grid media, which run no grid code.
  pathspace::GridTracking grid_tracking{&rng};
  grid_tracking.ratio_tracking = m_settings.mis.fault != pathspace::BidirFault::connection_without_ratio_tracking;
  pathspace::GridTracking* grid = m_has_grid ? &grid_tracking : nullptr;
  pathspace::SubpathParams cam_params{m_max_depth + 1, m_settings.rr_depth};
  pathspace::SubpathParams light_params{m_max_depth, m_settings.rr_depth};
  cam_params.grid = light_params.grid = grid;
  pathspace::camera_subpath(m_scene, raster, cam_params, rng, sc.camera);
  pathspace::light_subpath(m_scene, light_params, rng, sc.light);
  counters.camera_vertices += int64_t(sc.camera.size());
  counters.light_vertices += int64_t(sc.light.size());
  if (m_scene.caps().has_media) {
    for (const auto* path : {&sc.camera, &sc.light})
      for (const auto& v : *path) counters.medium_vertices += v.kind == pathspace::BidirKind::medium;
  } else {
    ++counters.media_skipped;
  }
  const int nc = int(sc.camera.size()), nl = int(sc.light.size());
  const int width = m_scene.camera().width();
  Rgb sum = Rgb::Zero();
  bool finite = true;
  sc.pending.clear();
  for (int t = 1; t <= nc; ++t)
    for (int s = 0; s <= nl; ++s) {
      if (s + t < 2 || s + t - 1 > m_max_depth) continue;
      if (m_settings.only_s >= 0 && (s != m_settings.only_s || t != m_settings.only_t)) continue;
      pathspace::Connection c;
      const bool ok =
          pathspace::connect(m_scene, sc.light.data(), s, sc.camera.data(), t, m_settings.mis, c, true, nullptr, grid);
      counters.connections += c.tested;
      counters.occluded += c.occluded;
      if (!ok) continue;
      const Rgb v = c.value * c.weight;
      finite = finite && is_finite(v);
      if (t == 1) {
        const float shift = m_settings.mis.fault == pathspace::BidirFault::splat_pixel_rounded ? 0.5f : 0.0f;
        const int px = std::min(int(c.raster.x() + shift), width - 1);
        const int py = std::min(int(c.raster.y() + shift), m_scene.camera().height() - 1);
        sc.pending.push_back(Splat{py * width + px, v});
      } else {
        sum += v;
      }
    }
  counters.grid_flights += grid_tracking.flights;
  counters.ratio_tracking += grid_tracking.ratio_estimates;
  if (!finite) return false;  // counted and dropped by the caller, never splatted
  L += sum;
  counters.splats += int64_t(sc.pending.size());
  splats.insert(splats.end(), sc.pending.begin(), sc.pending.end());
  return true;
}

}  // namespace dp::integrators
