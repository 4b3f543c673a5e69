// Diffuse area emitter attached to a shape: constant radiance from the front side
// (the side the geometric normal points to), nothing from the back.
//
// Direct sampling, two strategies:
//  * Meshes, and spheres seen from inside or from their surface: a point uniform by
//    area (Shape::sample_area), converted to solid angle at the reference point:
//      pdf_omega = pdf_area * |p - ref|^2 / cos(theta_l),  cos(theta_l) = n . (ref - p) / |ref - p|
//    (pbrt-v3 Sec. 14.2.2; dω = cos θ dA / r²). Samples on a back-facing part of the
//    emitter carry zero radiance and pdf 0 (failed samples, matching pdf_direct = 0).
//  * Spheres seen from outside: uniform in the cone of directions subtended by the
//    sphere (pbrt-v3 Sec. 14.2.2, "Sampling Spheres"), pdf_omega = 1 / (2π (1 - cos θmax)),
//    sin² θmax = r² / d_c². Area sampling wastes the far half of the sphere and its
//    estimator variance blows up for nearby receivers (d²/cos grows without bound at the
//    silhouette); the cone has neither problem. The hit is the first intersection of the
//    sampled direction with the sphere, so it always faces ref (outward normals); an
//    inward-facing (flip_normals) sphere is invisible from outside: pdf 0.
// In every case `pdf_area` is the area density of the returned point.
#include "core/error.h"
#include "core/warp.h"
#include "scene/emitters/emitter.h"
#include "scene/shapes/shape.h"

namespace dp::scene {

namespace {

// Cone subtended by a sphere seen from outside; `valid` is false for ref inside or on
// the sphere (then area sampling is used).
struct SphereCone {
  bool valid = false;
  double dist_center = 0, one_minus_cos_max = 0, cos_max = 1;
  Vec3 axis{0, 0, 1};
};

SphereCone sphere_cone(const Sphere& s, const Vec3& ref) {
  SphereCone c;
  const Vec3d to_center = (s.center() - ref).cast<double>();
  const double dc2 = to_center.squaredNorm(), r2 = sqr(double(s.radius()));
  if (!(dc2 > r2 * (1.0 + 1e-6))) return c;
  c.valid = true;
  c.dist_center = std::sqrt(dc2);
  c.axis = (to_center / c.dist_center).cast<float>();
  const double sin2_max = r2 / dc2;
  c.cos_max = std::sqrt(std::max(0.0, 1.0 - sin2_max));
  c.one_minus_cos_max = sin2_max / (1.0 + c.cos_max);  // no cancellation for small spheres
  return c;
}

float cone_pdf(const SphereCone& c) { return float(1.0 / (2.0 * kPiD * c.one_minus_cos_max)); }

}  // namespace

AreaEmitter::AreaEmitter(const Shape* shape, const Rgb& radiance) : m_shape(shape), m_radiance(radiance) {
  if (shape->kind() == ShapeKind::mesh) m_mesh = static_cast<const TriangleMesh*>(shape);
}

DirectSample AreaEmitter::sample_direct(const Vec3& ref, const Vec2& u) const {
  DirectSample s;
  if (!m_mesh && m_shape->kind() == ShapeKind::sphere) {
    const auto& sphere = static_cast<const Sphere&>(*m_shape);
    const SphereCone cone = sphere_cone(sphere, ref);
    if (cone.valid) {
      // Uniform cos(theta) in [cos_max, 1], written as 1 - u (1 - cos_max) for accuracy.
      const double cos_t = 1.0 - double(u.x()) * cone.one_minus_cos_max;
      const double sin2_t = std::max(0.0, (1.0 - cos_t) * (1.0 + cos_t));
      const double phi = 2.0 * kPiD * double(u.y());
      const double sin_t = std::sqrt(sin2_t);
      const Frame f = Frame::from_normal(cone.axis);
      const Vec3d w = (f.to_world(Vec3(float(sin_t * std::cos(phi)), float(sin_t * std::sin(phi)), float(cos_t))))
                          .cast<double>()
                          .normalized();
      // First intersection along w: t = d_c cos - sqrt(r² - d_c² sin²) (clamped at the
      // silhouette, where rounding can make the root slightly imaginary).
      const double r = double(sphere.radius());
      const double t = cone.dist_center * cos_t - std::sqrt(std::max(0.0, r * r - sqr(cone.dist_center) * sin2_t));
      const Vec3d c = sphere.center().cast<double>();
      const Vec3d p_local = ref.cast<double>() + t * w - c;
      const Vec3d n = p_local.normalized();
      s.p = (c + r * n).cast<float>();
      s.n = sphere.flip_normals ? Vec3(-n.cast<float>()) : Vec3(n.cast<float>());
      s.wi = w.cast<float>();
      s.dist = float(t);
      if (sphere.flip_normals) return s;  // inward normals: the near side is a back side
      s.pdf = cone_pdf(cone);
      const double cos_l = std::max(0.0, -n.dot(w));
      s.pdf_area = float(double(s.pdf) * cos_l / (t * t));
      s.radiance = m_radiance;
      return s;
    }
  }
  const PositionSample ps = m_mesh && m_mesh->area() > 0.0f ? m_mesh->sample_area_inline(u) : m_shape->sample_area(u);
  s.p = ps.p;
  s.n = ps.n;
  s.pdf_area = ps.pdf_area;
  const Vec3 d = ps.p - ref;
  const float dist2 = d.squaredNorm();
  if (!(dist2 > 0.0f)) return s;  // ref on the emitter: no direction
  // pdf = pdf_area dist^2 / cos_l with cos_l = -n.d / dist, written as
  // pdf_area dist^3 / (-n.d) so that it does not wait for the normalized direction.
  const float n_dot = -ps.n.dot(d);
  s.dist = std::sqrt(dist2);
  s.wi = d / s.dist;
  if (!(n_dot > 0.0f)) return s;  // ref sees the back side
  s.pdf = ps.pdf_area * dist2 * s.dist / n_dot;
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
  if (!(cos_l > 0.0f)) return 0.0f;  // back side
  if (m_shape->kind() == ShapeKind::sphere) {
    const auto& sphere = static_cast<const Sphere&>(*m_shape);
    const SphereCone cone = sphere_cone(sphere, ref);
    if (cone.valid) return sphere.flip_normals ? 0.0f : cone_pdf(cone);
  }
  const float pdf = dist2 / (cos_l * m_shape->area());
  return std::isfinite(pdf) ? pdf : 0.0f;
}

float AreaEmitter::pdf_area_direct(const Vec3& ref, const Vec3& p, const Vec3& n) const {
  if (m_shape->kind() == ShapeKind::sphere) {
    const auto& sphere = static_cast<const Sphere&>(*m_shape);
    const SphereCone cone = sphere_cone(sphere, ref);
    if (cone.valid) {  // cone sampling reaches only the near side's points
      if (sphere.flip_normals) return 0.0f;
      const Vec3 d = p - ref;
      const float dist2 = d.squaredNorm();
      const float cos_l = -n.dot(d) / std::sqrt(dist2);
      if (!(dist2 > 0.0f) || !(cos_l > 0.0f)) return 0.0f;
      const float pdf = cone_pdf(cone) * cos_l / dist2;
      return std::isfinite(pdf) ? pdf : 0.0f;
    }
  }
  const float area = m_shape->area();  // uniform by area, independent of ref
  return area > 0.0f ? 1.0f / area : 0.0f;
}

Rgb AreaEmitter::eval(const SurfacePoint& sp, const Vec3& w) const {
  return sp.ng.dot(w) > 0.0f ? m_radiance : Rgb::Zero();
}

// Lambertian emitter, one side: Phi = L * A * integral of cos over the hemisphere
// = pi * A * L.
Rgb AreaEmitter::power() const { return kPi * m_shape->area() * m_radiance; }

}  // namespace dp::scene
