#include "integrators/media_photons/photon_plane.h"

#include <algorithm>
#include <cmath>

#include "integrators/media_photons/photon_tracer.h"  // grown_bounds_clip
#include "scene/media/free_flight.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

namespace {
// A plane with every field but the grid's (record_plane, record_plane_grid).
MediumPlane new_plane(const Vec3& a0, const Vec3& w0, const Vec3& w1, float t0_begin, float t0_end, float t1_end,
                      float p_scatter, float q, const Rgb& beta, int depth_b, int medium, size_t index) {
  MediumPlane pl;
  pl.a0 = a0;
  pl.w0 = w0;
  pl.w1 = w1;
  pl.t0_begin = t0_begin;
  pl.t0_end = t0_end;
  pl.t1_end = t1_end;
  pl.p_scatter = p_scatter;
  pl.q = q;
  pl.beta = beta;
  pl.depth = int16_t(depth_b);
  pl.medium = int16_t(medium);
  pl.index = uint32_t(index);
  return pl;
}
}  // namespace

float free_flight_distance(const scene::HomogeneousMedium& med, float u_channel, float u) {
  const int c = std::min(int(u_channel * 3.0f), 2);  // as sample_free_flight
  const float st = med.sigma_t()[c];
  return st > 0.0f ? -std::log1p(-u) / st : kInfinity;
}

void record_plane(const scene::Scene& scene, const scene::HomogeneousMedium& med, const Vec3& a0, const Vec3& w0,
                  float t_surf, const Vec3& w1, const Rgb& beta_a0, float q, int depth_b, int medium, float u_channel,
                  float u, std::vector<MediumPlane>& planes, PlaneTraceCounters& counters) {
  if (is_black(med.sigma_s) || is_black(beta_a0)) return;  // nothing scatters
  const float p_scatter = 1.0f - scene::free_flight_pass_probability(med, t_surf);
  if (!is_finite(beta_a0) || !a0.allFinite() || !w0.allFinite() || !w1.allFinite() || !(p_scatter > 0.0f) ||
      !(q > 0.0f) || std::isnan(t_surf)) {
    ++counters.dropped;
    return;
  }
  float c0 = 0.0f, c1 = 0.0f;
  grown_bounds_clip(scene, a0, w0, c0, c1);
  const float t0b = std::max(c0, 0.0f), t0e = std::min(c1, t_surf);
  bool clipped = t0b > 0.0f || t0e < t_surf;
  if (!(t0e > t0b) || !std::isfinite(t0e)) {
    ++counters.dropped;
    return;
  }
  // t1 up to which a0 + t0 w0 + t1 w1 (t0 in [t0b, t0e]) can still lie in the grown box:
  // per axis, lo <= x + t1 w1[a] <= hi for x in the range of a0[a] + t0 w0[a].
  const Bounds3& b = scene.bounds();
  const float grow = std::max(b.diagonal(), 1.0f);
  float t1_box = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (w1[a] == 0.0f) continue;
    const float x0 = a0[a] + t0b * w0[a], x1 = a0[a] + t0e * w0[a];
    const float t =
        w1[a] > 0.0f ? (b.hi[a] + grow - std::min(x0, x1)) / w1[a] : (b.lo[a] - grow - std::max(x0, x1)) / w1[a];
    t1_box = std::min(t1_box, t);
  }
  const float d = free_flight_distance(med, u_channel, u);
  if (t1_box < d) clipped = true;
  const float t1e = std::min(d, t1_box);
  if (!(t1e > 0.0f) || !std::isfinite(t1e)) {
    ++counters.dropped;
    return;
  }
  if (clipped) ++counters.clipped;
  planes.push_back(new_plane(a0, w0, w1, t0b, t0e, t1e, p_scatter, q, beta_a0, depth_b, medium, planes.size()));
  ++counters.stored;
}

void record_plane_grid(const scene::HomogeneousMedium& med, const Vec3& a0, const Vec3& w0, float t_surf,
                       const Rgb& beta_a0, int depth_b, int medium, core::Rng& rng, std::vector<MediumPlane>& planes,
                       PlaneTraceCounters& counters) {
  if (is_black(med.sigma_s) || is_black(beta_a0)) return;  // nothing scatters
  if (!is_finite(beta_a0) || !a0.allFinite() || !w0.allFinite() || std::isnan(t_surf)) {
    ++counters.dropped;
    return;
  }
  const scene::DensityGrid& g = *med.density;
  const float dmax = g.max_value, mu = med.sigma_t()[0] * dmax;
  float tb = 0.0f, te = 0.0f;
  if (!(mu > 0.0f) || !g.clip(a0, w0, t_surf, tb, te) || !(te > tb)) return;  // no density on the segment
  // Kept with the majorant's probability of a collision inside the box (closed form).
  const float p_rec = -std::expm1(-mu * (te - tb));
  if (!(rng.uniform() < p_rec)) return;
  const Vec3 w1 = scene::HenyeyGreenstein(med.phase).sample(w0, rng.uniform2());  // rho / p = 1
  auto step = [&](float t) { return t - std::log1p(-rng.uniform()) / mu; };
  // Along w0: the ratio-tracking profile (as scene::TransmittanceProfile), cut where it is 0.
  thread_local std::vector<float> t0s, v0s, t1s;
  t0s.clear();
  v0s.clear();
  t1s.clear();
  float tr = 1.0f;
  for (float t = step(tb); t < te; t = step(t)) {
    tr *= std::max(0.0f, 1.0f - g.lookup(a0 + t * w0) / dmax);
    t0s.push_back(t);
    v0s.push_back(tr);
    if (!(tr > 0.0f)) {
      te = t;
      break;
    }
  }
  // Along w1: up to where a0 + t0 w0 + t1 w1 (t0 in [tb, te]) may still be in the box
  // (per axis), tentative collisions kept with probability c; the first one dropped ends it.
  float t1_box = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (w1[a] == 0.0f) continue;
    const float x0 = a0[a] + tb * w0[a], x1 = a0[a] + te * w0[a];
    const float t = w1[a] > 0.0f ? (g.hi[a] - std::min(x0, x1)) / w1[a] : (g.lo[a] - std::max(x0, x1)) / w1[a];
    t1_box = std::min(t1_box, t);
  }
  if (!(t1_box > 0.0f) || !std::isfinite(t1_box) || !(te > tb)) {
    ++counters.dropped;
    return;
  }
  const float c = std::clamp(1.0f - g.min_value / dmax, 0.0f, 1.0f);
  float t1e = t1_box;
  for (float t = step(0.0f); t < t1_box; t = step(t)) {
    if (c < 1.0f && !(rng.uniform() < c)) {
      t1e = t;
      break;
    }
    t1s.push_back(t);
  }
  MediumPlane pl = new_plane(a0, w0, w1, tb, te, t1e, p_rec, 1.0f, beta_a0, depth_b, medium, planes.size());
  pl.grid_n0 = uint32_t(t0s.size());
  pl.grid_c = c;
  pl.grid.reserve(2 * t0s.size() + t1s.size());
  pl.grid.insert(pl.grid.end(), t0s.begin(), t0s.end());
  pl.grid.insert(pl.grid.end(), v0s.begin(), v0s.end());
  pl.grid.insert(pl.grid.end(), t1s.begin(), t1s.end());
  planes.push_back(std::move(pl));
  ++counters.stored;
  ++counters.grid;
}

}  // namespace dp::integrators
