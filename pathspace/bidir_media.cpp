#include "pathspace/bidir_media.h"

#include <algorithm>
#include <cmath>

#include "scene/media/free_flight.h"
#include "scene/media/grid_tracking.h"
#include "scene/media/medium_interface.h"
#include "scene/media/phase_function.h"

namespace dp::pathspace {

namespace {
const scene::HomogeneousMedium& medium_of(const scene::Scene& scene, int m) { return scene.media()[size_t(m)]; }

// The end factors of one sub-segment: P(pass), and p at a medium vertex at either end
// (homogeneous: the same p(len) at both; grid: the stand-ins of the header comment, one
// quadrature for all three). at_a / at_b are evaluated only if asked for.
using Factors = SpanFactors;
Factors factors(const scene::Scene& scene, int medium, float len, const Span& span, bool need_a, bool need_b) {
  Factors f;
  if (medium < 0) return f;
  const scene::HomogeneousMedium& m = medium_of(scene, medium);
  if (!m.heterogeneous()) {
    f.pass = scene::free_flight_pass_probability(m, len);
    if (need_a || need_b) f.at_a = f.at_b = scene::free_flight_pdf(m, len);
    return f;
  }
  f.pass = std::exp(-grid_optical_depth(m, span));
  const float st = m.sigma_t()[0];
  if (need_a) f.at_a = st * m.density->lookup(span.a) * f.pass;
  if (need_b) f.at_b = span.to_infinity ? 0.0f : st * m.density->lookup(span.b) * f.pass;
  return f;
}

// The transmittance of one sub-segment (from `o` along unit `d` for `len`, may be inf);
// `pass`: its P(pass) stand-in, the grid's deterministic value without an rng.
Rgb sub_transmittance(const scene::Scene& scene, int medium, const Vec3& o, const Vec3& d, float len, float pass,
                      GridTracking* grid) {
  const scene::HomogeneousMedium& m = medium_of(scene, medium);
  if (!m.heterogeneous()) return scene::transmittance(m, len);
  if (!grid || !grid->rng) return Rgb::Constant(pass);
  if (!grid->ratio_tracking) return Rgb::Ones();
  ++grid->ratio_estimates;
  return scene::transmittance_grid(m, o, d, len, *grid->rng);
}

// a < b in lexicographic order (the canonical direction of a finite span).
bool lex_less(const Vec3& a, const Vec3& b) {
  if (a.x() != b.x()) return a.x() < b.x();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.z() < b.z();
}
}  // namespace

float grid_optical_depth(const scene::HomogeneousMedium& m, const Span& span) {
  const scene::DensityGrid& g = *m.density;
  Vec3 o = span.a, d = span.b;
  float len = kInfinity;
  if (!span.to_infinity) {
    const bool swap = lex_less(span.b, span.a);  // tau_hat(a, b) == tau_hat(b, a) exactly
    o = swap ? span.b : span.a;
    const Vec3 e = (swap ? span.a : span.b) - o;
    len = e.norm();
    if (!(len > 0.0f)) return 0.0f;
    d = e / len;
  }
  float t0 = 0, t1 = 0;
  if (!g.clip(o, d, len, t0, t1)) return 0.0f;
  const int n = kGridSteps;
  const float dt = (t1 - t0) / float(n);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += double(g.lookup(o + (t0 + (float(i) + 0.5f) * dt) * d));
  return float(double(m.sigma_t()[0]) * double(dt) * sum);
}

float end_factor(const scene::Scene& scene, int medium, float len, const Span& span, bool at_medium_vertex,
                 bool vertex_at_a) {
  const Factors f = factors(scene, medium, len, span, at_medium_vertex && vertex_at_a, at_medium_vertex && !vertex_at_a);
  return !at_medium_vertex ? f.pass : vertex_at_a ? f.at_a : f.at_b;
}

int medium_toward(const scene::Scene& scene, const BidirVertex& v, const Vec3& w) {
  if (v.kind == BidirKind::camera) return scene.camera_medium();
  if (v.kind == BidirKind::medium || !v.on_surface()) return v.medium;
  if (v.interior < 0 && v.exterior < 0) return v.medium;
  return v.sp.ng.dot(w) < 0.0f ? v.interior : (v.exterior >= 0 ? v.exterior : scene.camera_medium());
}

float FlightChain::pass(const scene::Scene& scene, int medium, float len, const Span& span) {
  const Factors f = factors(scene, medium, len, span, m_n == 0, false);
  if (m_n == 0) {
    m_first_medium = medium;
    m_first = f;
  } else {
    m_pass_after_first *= f.pass;
  }
  m_pass_all *= f.pass;
  ++m_n;
  return f.pass;
}

float FlightChain::finish(const scene::Scene& scene, int medium, float len, const Span& span, bool a_medium,
                          bool b_medium) {
  const Factors f = factors(scene, medium, len, span, m_n == 0 && a_medium, b_medium);
  to_b = m_pass_all * (b_medium ? f.at_b : f.pass);
  if (m_n == 0) to_a = a_medium ? f.at_a : f.pass;
  else to_a = m_pass_after_first * f.pass * (m_first_medium >= 0 && a_medium ? m_first.at_a : m_first.pass);
  return f.pass;
}

EdgeMedia trace_edge(const scene::Scene& scene, const BidirVertex& a, const BidirVertex& b, GridTracking* grid) {
  EdgeMedia e;
  const bool to_infinity = b.infinite();
  const Vec3 target = b.sp.p;
  const Vec3 dir = to_infinity ? Vec3(b.sp.ng) : Vec3((target - a.sp.p).normalized());
  int m = medium_toward(scene, a, dir);
  Ray r;
  if (a.on_surface() && !to_infinity) {
    r = scene.spawn_segment(a.sp, target);
  } else if (a.on_surface()) {
    r = scene.spawn_ray(a.sp, dir);
  } else {
    r.o = a.sp.p;
    r.d = dir;
    r.tmin = scene::Scene::epsilon_at(a.sp.p);
    r.tmax = to_infinity ? kInfinity : (target - a.sp.p).norm() - scene::Scene::epsilon_at(target);
    if (!(r.tmax > r.tmin)) r.tmax = r.tmin;
  }
  FlightChain chain;
  Vec3 at = a.sp.p;
  scene::SurfaceHit h;
  for (;;) {
    if (!scene.intersect(r, h)) {
      const float len = to_infinity ? kInfinity : (target - at).norm();
      const Span span = to_infinity ? Span::ray(at, dir) : Span::between(at, target);
      const float pass = chain.finish(scene, m, len, span, a.kind == BidirKind::medium, b.kind == BidirKind::medium);
      if (m >= 0) e.tr *= sub_transmittance(scene, m, at, dir, len, pass, grid);
      e.to_b = chain.to_b;
      e.to_a = chain.to_a;
      e.b_medium = m;
      return e;
    }
    if (!scene::is_index_matched(h) || e.crossings >= kMaxEdgeCrossings) {
      e.blocked = true;
      e.tr = Rgb::Zero();
      return e;
    }
    const float len = (h.p - at).norm();
    const float pass = chain.pass(scene, m, len, Span::between(at, h.p));
    if (m >= 0) e.tr *= sub_transmittance(scene, m, at, dir, len, pass, grid);
    ++e.crossings;
    at = h.p;
    m = scene::medium_toward(h, dir, m, scene.camera_medium());
    r = to_infinity ? scene.spawn_ray(h, dir) : scene.spawn_segment(h, target);
  }
}

float scatter_pdf(const scene::Scene& scene, const BidirVertex& v, const Vec3& from, const Vec3& to,
                  scene::TransportMode mode) {
  if (v.kind == BidirKind::medium) return phase_value(scene, v, from, to);
  return bsdf_pdf(v, from, to, mode);
}

float phase_value(const scene::Scene& scene, const BidirVertex& v, const Vec3& from, const Vec3& to) {
  return scene::HenyeyGreenstein(medium_of(scene, v.medium).phase).eval(-from, to);
}

}  // namespace dp::pathspace
