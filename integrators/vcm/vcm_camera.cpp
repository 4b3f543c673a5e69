#include "integrators/vcm/vcm_camera.h"

#include <cmath>

#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"

namespace dp::integrators {

Rgb merge_bsdf(const pathspace::BidirVertex& z, const Vec3& wo) {
  const Vec3 wi = z.sp.shading.to_local(z.wi), w = z.sp.shading.to_local(wo);
  if (!(z.sp.ng.dot(z.wi) * wi.z() > 0.0f) || !(z.sp.ng.dot(wo) * w.z() > 0.0f)) return Rgb::Zero();
  return z.bsdf->eval(scene::BsdfContext{z.sp.uv, scene::TransportMode::radiance}, wi, w);
}

MergeKernel merge_kernel(float radius, float norm, const pathspace::VcmPrefix* cp, int t) {
  MergeKernel k;
  k.shrink = cp[t - 2].m;
  if (k.shrink == 1.0) {
    k.radius = radius;
    k.norm = norm;
  } else if (k.shrink >= 1e-20) {
    k.radius = float(double(radius) * std::sqrt(k.shrink));
    k.norm = float(double(norm) / k.shrink);
  }
  return k;
}

VcmCameraTracer::VcmCameraTracer(const scene::Scene& scene, const VcmSettings& settings, const VcmIteration& it,
                                 const LightPathStore& light, const PhotonGrid& grid)
    : m_scene(scene), m_settings(settings), m_it(it), m_light(light), m_grid(grid) {
  const double n = double(light.paths());
  m_merge_norm = n > 0 ? float(1.0 / (kPiD * double(it.radius) * double(it.radius) * n)) : 0.0f;
}

Rgb VcmCameraTracer::merge(const pathspace::BidirVertex* camera, const pathspace::VcmPrefix* cp, int t,
                           VcmCameraCounters& counters) const {
  const pathspace::BidirVertex& z = camera[t - 1];
  const bool weighted = m_settings.mode != VcmMode::ppm;
  const MergeKernel kernel = merge_kernel(m_it.radius, m_merge_norm, cp, t);
  if (!(kernel.radius > 0.0f)) return Rgb::Zero();
  Rgb sum = Rgb::Zero();
  ++counters.merge_queries;
  m_grid.query(z.sp.p, kernel.radius, [&](uint32_t k) {
    const VcmPhoton& ph = m_light.photons[k];
    if (ph.depth + t - 1 > m_it.max_depth) return;  // path depth: j light segments + t - 1 camera segments
    const Rgb f = merge_bsdf(z, ph.mis.wi);
    if (is_black(f)) return;
    ++counters.merges;
    const float w = weighted ? pathspace::vcm_merge_weight(ph.mis, camera, cp, t, m_it.mis) : 1.0f;
    sum += w * f * ph.beta;
  });
  return sum * z.beta * kernel.norm;
}

bool VcmCameraTracer::sample(const Vec2& raster, int64_t pixel, core::Rng& rng, VcmCameraScratch& sc, Rgb& L,
                             VcmCameraCounters& counters) const {
  const pathspace::SubpathParams params{m_it.max_depth + 1, m_settings.rr_depth};
  pathspace::camera_subpath(m_scene, raster, params, rng, sc.camera);
  const int nc = int(sc.camera.size());
  sc.prefixes.resize(size_t(nc));
  pathspace::vcm_prefixes(sc.camera.data(), nc, true, m_it.mis, sc.prefixes.data());
  counters.camera_vertices += nc;
  const pathspace::BidirVertex* cam = sc.camera.data();
  const pathspace::VcmPrefix* cp = sc.prefixes.data();
  const pathspace::VcmPrefix* lp = nullptr;
  int nl = 0;
  const pathspace::BidirVertex* light = m_light.path(pixel, &lp, &nl);
  const pathspace::MisConfig unweighted{.unweighted = true};
  Rgb sum = Rgb::Zero();
  bool dirac_prefix = true;  // z_1 .. z_{t-2} all scattered through Dirac lobes
  for (int t = 2; t <= nc; ++t) {
    const pathspace::BidirVertex& z = cam[t - 1];
    pathspace::Connection c;
    // s = 0: the camera walk hit a light. Without connections (vm, ppm) only paths no
    // merge can produce (Dirac lobes all the way) count, unweighted.
    if (z.emitter && (m_settings.connects() || dirac_prefix) &&
        pathspace::connect(m_scene, nullptr, 0, cam, t, unweighted, c)) {
      const float w = m_settings.connects()
                          ? pathspace::vcm_connection_weight(m_scene, nullptr, nullptr, 0, cam, cp, t, m_it.mis)
                          : 1.0f;
      sum += c.value * w;
    }
    if (m_settings.connects())
      for (int s = 1; s <= nl && s + t - 1 <= m_it.max_depth; ++s) {
        const bool ok = pathspace::connect(m_scene, light, s, cam, t, unweighted, c);
        counters.connections += c.tested;
        counters.occluded += c.occluded;
        if (!ok) continue;
        sum += c.value * pathspace::vcm_connection_weight(m_scene, light, lp, s, cam, cp, t, m_it.mis);
      }
    if (m_settings.merges() && !m_grid.empty() && t <= m_it.max_depth && pathspace::vcm_mergeable(z, false, m_it.mis.min_merge_roughness)) {
      sum += merge(cam, cp, t, counters);
      if (m_settings.mode == VcmMode::ppm && !z.delta) break;  // the path's first non-Dirac lobe: merged here
    }
    dirac_prefix = dirac_prefix && z.delta;
  }
  if (!is_finite(sum)) {
    ++counters.nan_dropped;
    return false;
  }
  L += sum;
  return true;
}

}  // namespace dp::integrators
