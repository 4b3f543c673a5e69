// Helpers for the geometry/emitter tests: small meshes, an independent ray-triangle
// intersection (Möller-Trumbore in double; Embree is not used so the tests check the
// scene layer alone) and a Monte Carlo mean with its standard error.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <optional>

#include "core/rng.h"
#include "scene/emitters/emitter.h"
#include "scene/shapes/shape.h"

namespace dp::test {

inline std::unique_ptr<scene::TriangleMesh> make_mesh(std::vector<Vec3> positions,
                                                      std::vector<std::array<uint32_t, 3>> tris) {
  auto m = std::make_unique<scene::TriangleMesh>();
  m->positions = std::move(positions);
  m->triangles = std::move(tris);
  m->finalize();
  return m;
}

// Quad v0..v3 (planar, in order) as triangles (0,1,2), (0,2,3).
inline std::unique_ptr<scene::TriangleMesh> make_quad(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& v3) {
  return make_mesh({v0, v1, v2, v3}, {{0, 1, 2}, {0, 2, 3}});
}

struct TestHit {
  double t;
  Vec3 p, ng;
};

// Nearest hit of the ray (o, d) with a triangle mesh, t > 0.
inline std::optional<TestHit> intersect_mesh(const scene::TriangleMesh& m, const Vec3& o, const Vec3& d) {
  std::optional<TestHit> best;
  const Vec3d od = o.cast<double>(), dd = d.cast<double>();
  for (const auto& tri : m.triangles) {
    const Vec3d v0 = m.positions[tri[0]].cast<double>(), v1 = m.positions[tri[1]].cast<double>(),
                v2 = m.positions[tri[2]].cast<double>();
    const Vec3d e1 = v1 - v0, e2 = v2 - v0, pv = dd.cross(e2);
    const double det = e1.dot(pv);
    if (std::abs(det) < 1e-300) continue;
    const Vec3d tv = od - v0;
    const double b1 = tv.dot(pv) / det;
    if (b1 < 0 || b1 > 1) continue;
    const Vec3d qv = tv.cross(e1);
    const double b2 = dd.dot(qv) / det;
    if (b2 < 0 || b1 + b2 > 1) continue;
    const double t = e2.dot(qv) / det;
    if (t <= 0 || (best && t >= best->t)) continue;
    best = TestHit{t, (od + t * dd).cast<float>(), e1.cross(e2).normalized().cast<float>()};
  }
  return best;
}

// Solid-angle pdf of an area emitter's sample_direct at direction w, found by tracing
// the emitter's shape (the way an integrator computes it after a BSDF-sampled hit).
inline double area_pdf_along(const scene::AreaEmitter& e, const Vec3& ref, const Vec3& w) {
  const scene::Shape* s = e.shape();
  if (const auto* mesh = dynamic_cast<const scene::TriangleMesh*>(s)) {
    const auto h = intersect_mesh(*mesh, ref, w);
    return h ? double(e.pdf_direct(ref, h->p, h->ng, w)) : 0.0;
  }
  const auto* sphere = dynamic_cast<const scene::Sphere*>(s);
  Ray r;
  r.o = ref;
  r.d = w;
  float t;
  if (!sphere->intersect(r, t)) return 0.0;
  scene::SurfacePoint sp;
  sphere->fill_surface(0, Vec2(0, 0), r, t, sp);
  return double(e.pdf_direct(ref, sp.p, sp.ng, w));
}

struct MeanEstimate {
  double mean = 0, std_error = 0;
};

// Mean and standard error of f(rng) over n samples (Welford).
template <class F>
MeanEstimate mc_mean(F&& f, int n, uint64_t seed) {
  core::Rng rng(seed, 0);
  double mean = 0, m2 = 0;
  for (int i = 1; i <= n; ++i) {
    const double x = f(rng);
    const double delta = x - mean;
    mean += delta / i;
    m2 += delta * (x - mean);
  }
  return {mean, std::sqrt(m2 / (double(n) - 1.0) / n)};
}

}  // namespace dp::test
