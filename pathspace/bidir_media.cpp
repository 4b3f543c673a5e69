#include "pathspace/bidir_media.h"

#include "scene/media/free_flight.h"
#include "scene/media/medium_interface.h"
#include "scene/media/phase_function.h"

namespace dp::pathspace {

namespace {
const scene::HomogeneousMedium& medium_of(const scene::Scene& scene, int m) { return scene.media()[size_t(m)]; }
}  // namespace

float end_factor(const scene::Scene& scene, int medium, float len, bool at_medium_vertex) {
  if (medium < 0) return 1.0f;
  const scene::HomogeneousMedium& m = medium_of(scene, medium);
  return at_medium_vertex ? scene::free_flight_pdf(m, len) : scene::free_flight_pass_probability(m, len);
}

int medium_toward(const scene::Scene& scene, const BidirVertex& v, const Vec3& w) {
  if (v.kind == BidirKind::camera) return scene.camera_medium();
  if (v.kind == BidirKind::medium || !v.on_surface()) return v.medium;
  if (v.interior < 0 && v.exterior < 0) return v.medium;
  return v.sp.ng.dot(w) < 0.0f ? v.interior : (v.exterior >= 0 ? v.exterior : scene.camera_medium());
}

void FlightChain::pass(const scene::Scene& scene, int medium, float len) {
  const float p = end_factor(scene, medium, len, false);
  if (m_n == 0) {
    m_first_medium = medium;
    m_first_len = len;
  } else {
    m_pass_after_first *= p;
  }
  m_pass_all *= p;
  ++m_n;
}

void FlightChain::finish(const scene::Scene& scene, int medium, float len, bool a_medium, bool b_medium) {
  to_b = m_pass_all * end_factor(scene, medium, len, b_medium);
  if (m_n == 0) to_a = end_factor(scene, medium, len, a_medium);
  else to_a = m_pass_after_first * end_factor(scene, medium, len, false) *
              end_factor(scene, m_first_medium, m_first_len, a_medium);
}

EdgeMedia trace_edge(const scene::Scene& scene, const BidirVertex& a, const BidirVertex& b) {
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
      if (m >= 0) e.tr *= scene::transmittance(medium_of(scene, m), len);
      chain.finish(scene, m, len, a.kind == BidirKind::medium, b.kind == BidirKind::medium);
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
    if (m >= 0) e.tr *= scene::transmittance(medium_of(scene, m), len);
    chain.pass(scene, m, len);
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
