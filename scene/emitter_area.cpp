// Diffuse area emitter attached to a shape: constant radiance from the front side
// (the side the geometric normal points to), nothing from the back.
//
// Direct sampling picks a point uniformly by area on the shape (Shape::sample_area)
// and converts the area density to solid angle at the reference point:
//   pdf_omega = pdf_area * |p - ref|^2 / cos(theta_l),  cos(theta_l) = n . (ref - p)/|ref - p|
// (pbrt-v3 Sec. 14.2.2, Eq. 5.6 change of variables dω = cos θ dA / r²). Samples that
// land on a back-facing part of the emitter (as seen from ref) carry zero radiance and
// pdf 0: they are a failed sample, consistent with pdf_direct returning 0 there.
#include "core/error.h"
#include "scene/emitter.h"
#include "scene/shape.h"

namespace dp::scene {

DirectSample AreaEmitter::sample_direct(const Vec3& ref, const Vec2& u) const {
  const PositionSample ps = m_shape->sample_area(u);
  DirectSample s;
  s.p = ps.p;
  s.n = ps.n;
  s.pdf_area = ps.pdf_area;
  const Vec3 d = ps.p - ref;
  const float dist2 = d.squaredNorm();
  if (!(dist2 > 0.0f)) return s;  // ref on the emitter: no direction
  s.dist = std::sqrt(dist2);
  s.wi = d / s.dist;
  const float cos_l = -ps.n.dot(s.wi);
  if (!(cos_l > 0.0f)) return s;  // ref sees the back side
  s.pdf = ps.pdf_area * dist2 / cos_l;
  if (!std::isfinite(s.pdf)) {
    s.pdf = 0;
    return s;
  }
  s.radiance = m_radiance;
  return s;
}

float AreaEmitter::pdf_direct(const Vec3& ref, const Vec3& p, const Vec3& n, const Vec3& w) const {
  (void)w;
  const Vec3 d = p - ref;
  const float dist2 = d.squaredNorm();
  if (!(dist2 > 0.0f)) return 0.0f;
  const float cos_l = -n.dot(d) / std::sqrt(dist2);
  if (!(cos_l > 0.0f)) return 0.0f;
  const float pdf = dist2 / (cos_l * m_shape->area());
  return std::isfinite(pdf) ? pdf : 0.0f;
}

Rgb AreaEmitter::eval(const SurfacePoint& sp, const Vec3& w) const {
  return sp.ng.dot(w) > 0.0f ? m_radiance : Rgb::Zero();
}

// Lambertian emitter, one side: Phi = L * A * integral of cos over the hemisphere
// = pi * A * L.
Rgb AreaEmitter::power() const { return kPi * m_shape->area() * m_radiance; }

}  // namespace dp::scene
