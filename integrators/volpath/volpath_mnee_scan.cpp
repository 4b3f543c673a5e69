// MNEE's scanned seeds (setting mnee_scan; volpath_mnee.h has the strategy).
//
// A ball lens has one solution S(x, y) outside its caustic and three inside; near the
// caustic's folds two of them lie close together and their generalized geometry term D
// grows without bound, so the pixels there carry much light. Fixed seed directions reach
// such a pair only when one falls into its small basin of attraction: the rest is left
// to BSDF sampling, which practically never finds a small light through glass.
//
// The scan instead follows the seed chain itself across the shape: K directions in the
// plane of x, y and the shape's centre (every solution of a ball lies in it), each
// refracted through the chain's m Dirac vertices and carried on to the
// light's tangent plane, where e(t) = (landing point - y) . a is its signed miss along the
// plane's in-light direction a. Solutions are roots of e(t):
//  * a sign change between neighbouring samples brackets one; its seed is the secant root;
//  * a local minimum of |e| without a sign change may hide a pair closer together than
//    the sampling (a fold): the parabola through the three samples gives its roots as
//    seeds when it crosses zero;
//  * where the chain breaks (the silhouette, an occluder), the last valid sample of a run
//    whose miss still shrinks toward the break seeds a walk of its own.
// From inside the shape the samples close a circle (neighbours wrap around).
// Every seed then goes through the same manifold walk and the same de-duplication as the
// fixed seeds, so S(x, y) stays a deterministic function of x and y and the MIS with
// BSDF sampling is unchanged (volpath_mnee.h, "The BSDF side").
#include <algorithm>
#include <cmath>
#include <limits>

#include "integrators/volpath/volpath_mnee_chain.h"
#include "integrators/volpath/volpath_tracer.h"

namespace dp::integrators {

using scene::SurfaceHit;

int VolpathTracer::mnee_scan(const MneeAnchor& x, const Vec3& y, const Vec3& n_y, int m, int shape,
                             const Bounds3& b, MneeSeeds& seeds, VolpathCounters& c) const {
  seeds.count = 0;
  const int k = std::clamp(m_settings.mnee_scan, 3, kMaxMneeScan);
  const Vec3 xp = x.position();
  const Vec3 to_c = b.center() - xp;
  const float dc = to_c.norm();
  // R: half the bounds' largest extent (the ball's radius for a sphere; for a flat shape,
  // a pane or one face of a slab, its width and not its zero thickness).
  const float half = 0.5f * (b.hi - b.lo).maxCoeff();
  // From outside the sphere of radius R about the bounds' centre: directions across it,
  // parametrized by the angle t in (-pi/2, pi/2) at which a line from x would meet it
  // seen from afar (impact parameter R sin t), so sin(theta) = R sin(t) / d_c for the
  // angle theta from the direction to the centre. Uniform in t, the samples crowd toward
  // the silhouette, where the entry point (hence the miss) moves fastest. From inside:
  // theta = 2 t, the whole circle.
  const bool inside = !(dc > half);
  const Vec3 c_dir = dc > 1e-6f * std::max(1.0f, half) ? Vec3(to_c / dc) : Vec3((y - xp).normalized());
  Vec3 normal = c_dir.cross(y - xp);
  if (!(normal.squaredNorm() > 1e-12f * (y - xp).squaredNorm())) normal = Frame::from_normal(c_dir).s;
  const Vec3 u = normal.cross(c_dir).normalized();
  const Vec3 ny = n_y.normalized();
  Vec3 a = ny.cross(normal);  // in the scan plane and in the light's tangent plane
  if (!(a.squaredNorm() > 1e-12f * normal.squaredNorm())) a = u;
  a.normalize();
  auto direction = [&](float t) {
    if (inside) return Vec3(std::cos(2.0f * t) * c_dir + std::sin(2.0f * t) * u);
    const float sin_theta = half / dc * std::sin(t);
    return Vec3(std::sqrt(std::max(0.0f, 1.0f - sin_theta * sin_theta)) * c_dir + sin_theta * u);
  };

  // e(t_j) at t_j = (-1 + (2 j + 1) / k) pi / 2; NaN where the chain breaks.
  std::array<float, kMaxMneeScan> t{}, e{};
  for (int j = 0; j < k; ++j) {
    t[size_t(j)] = (-1.0f + float(2 * j + 1) / float(k)) * (0.5f * kPi);
    e[size_t(j)] = std::numeric_limits<float>::quiet_NaN();
    Ray r;
    const bool ok = follow_dirac_chain(m_scene, x, direction(t[size_t(j)]), m, 0u, shape, r,
                                       [](const SurfaceHit&, const Vec3&, const scene::BsdfSample&) { return true; });
    ++c.mnee_scan_rays;
    if (!ok) continue;
    const float dist = (y - r.o).dot(ny) / r.d.dot(ny);  // to the light's tangent plane
    if (!(dist > 0.0f) || !std::isfinite(dist)) continue;
    e[size_t(j)] = (r.o + dist * r.d - y).dot(a);
  }

  auto add = [&](float tt) {
    if (seeds.count < kMaxMneeScanSeeds) seeds.d[size_t(seeds.count++)] = direction(tt);
  };
  const float step = kPi / float(k);
  // Neighbours of sample j (-1: none); from inside the samples close a circle.
  auto next = [&](int j) { return j + 1 < k ? j + 1 : inside ? 0 : -1; };
  auto prev = [&](int j) { return j > 0 ? j - 1 : inside ? k - 1 : -1; };
  auto at = [&](int j) { return j < 0 ? std::numeric_limits<float>::quiet_NaN() : e[size_t(j)]; };
  for (int j = 0; j < k; ++j) {
    const float e0 = e[size_t(j)], e1 = at(next(j));
    if (std::isnan(e0) || std::isnan(e1)) continue;
    if ((e0 <= 0.0f) != (e1 <= 0.0f)) {  // a bracketed root: the secant's
      add(t[size_t(j)] + step * e0 / (e0 - e1));
      ++c.mnee_scan_brackets;
      continue;
    }
    const float em = at(prev(j));
    if (std::isnan(em) || (em <= 0.0f) != (e0 <= 0.0f)) continue;
    if (!(std::abs(e0) < std::abs(em) && std::abs(e0) < std::abs(e1))) continue;
    // A local minimum of |e| at t_j: the parabola e(s) = e0 + B s + A s^2 (s in steps).
    const float A = 0.5f * (e1 - 2.0f * e0 + em), B = 0.5f * (e1 - em);
    const float disc = B * B - 4.0f * A * e0;
    if (!(disc >= 0.0f) || A == 0.0f) continue;
    const float root = std::sqrt(disc);
    for (const float s : {(-B - root) / (2.0f * A), (-B + root) / (2.0f * A)})
      if (std::abs(s) <= 1.0f) add(t[size_t(j)] + s * step);
    ++c.mnee_scan_folds;
  }
  // The ends of each run of valid samples: a miss still shrinking toward the run's end may
  // have its root between the last sample and where the chain breaks (the silhouette).
  for (int j = 0; j < k; ++j) {
    const float e0 = e[size_t(j)];
    if (std::isnan(e0)) continue;
    const bool left_end = std::isnan(at(prev(j))), right_end = std::isnan(at(next(j)));
    if (left_end == right_end) continue;  // inside a run, or a run of one sample
    const float inner = at(left_end ? next(j) : prev(j));
    if ((inner <= 0.0f) == (e0 <= 0.0f) && std::abs(e0) < std::abs(inner)) {
      add(t[size_t(j)]);
      ++c.mnee_scan_edges;
    }
  }
  return seeds.count;
}

}  // namespace dp::integrators
