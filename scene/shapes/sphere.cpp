// Analytic sphere: intersection in double, surface geometry, uniform area sampling.
//
// Parameterization (Mitsuba's sphere, in world axes around the center):
//   phi = atan2(y, x) in [0, 2pi), theta = acos(z / r);  uv = (phi / 2pi, theta / pi)
//   dp/du = 2pi (-y, x, 0),  dp/dv = pi (z cos phi, z sin phi, -r sin theta)
// (x, y, z relative to the center). The outward normal is (p - c) / r, so
// dn/du = dp/du / r and dn/dv = dp/dv / r; with flip_normals the normal is -(p - c) / r
// and both derivatives change sign.
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/warp.h"
#include "scene/shapes/shape.h"

namespace dp::scene {

namespace {

struct SphereCoords {
  Vec2 uv;
  Vec3 dpdu, dpdv;
};

SphereCoords sphere_coords(const Vec3d& local, double r) {
  double phi = std::atan2(local.y(), local.x());
  if (phi < 0) phi += 2 * kPiD;
  const double cos_theta = std::clamp(local.z() / r, -1.0, 1.0);
  const double theta = std::acos(cos_theta);
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  SphereCoords c;
  c.uv = Vec2(float(phi / (2 * kPiD)), float(theta / kPiD));
  c.dpdu = Vec3(float(-2 * kPiD * local.y()), float(2 * kPiD * local.x()), 0.0f);
  c.dpdv = Vec3(float(kPiD * local.z() * std::cos(phi)), float(kPiD * local.z() * std::sin(phi)),
                float(-kPiD * r * sin_theta));
  return c;
}

}  // namespace

Bounds3 Sphere::bounds() const {
  Bounds3 b;
  b.expand(m_center - Vec3::Constant(m_radius));
  b.expand(m_center + Vec3::Constant(m_radius));
  return b;
}

bool Sphere::intersect(const Ray& ray, float& t_out) const {
  const Vec3d o = ray.o.cast<double>(), d = ray.d.cast<double>(), c = m_center.cast<double>();
  const double r = double(m_radius);
  const Vec3d oc = o - c;
  const double a = d.squaredNorm();
  if (!(a > 0.0)) return false;
  const double b = oc.dot(d);  // half of the usual b
  // Discriminant from the perpendicular distance of the center to the line, which
  // avoids the cancellation in b^2 - a (|oc|^2 - r^2) for distant origins
  // (Haines et al., Ray Tracing Gems, Ch. 7, Eq. 10).
  const Vec3d l = oc - (b / a) * d;
  const double disc = a * (r * r - l.squaredNorm());
  if (disc < 0.0) return false;
  // Stable quadratic roots (Press et al.): q = -(b + sign(b) sqrt(disc)).
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  const double cc = (oc.norm() - r) * (oc.norm() + r);
  double t0, t1;
  if (q == 0.0) {
    t0 = t1 = -b / a;
  } else {
    t0 = q / a;
    t1 = cc / q;
  }
  if (t0 > t1) std::swap(t0, t1);
  const double tmin = double(ray.tmin), tmax = double(ray.tmax);
  for (double t : {t0, t1}) {
    if (t > tmin && t < tmax) {
      const float tf = float(t);
      if (!(tf > ray.tmin) || !(tf < ray.tmax)) continue;  // rounded onto the bound
      t_out = tf;
      return true;
    }
  }
  return false;
}

void Sphere::fill_surface(int prim, const Vec2& b, const Ray& ray, float t, SurfacePoint& out) const {
  (void)prim;
  (void)b;
  // Re-project the hit onto the sphere (in double) to remove the error along the ray.
  const Vec3d c = m_center.cast<double>();
  Vec3d local = ray.at(t).cast<double>() - c;
  const double len = local.norm();
  const double r = double(m_radius);
  local = len > 0 ? Vec3d(local * (r / len)) : Vec3d(0, 0, r);
  out.p = (c + local).cast<float>();
  const Vec3 n_out = (local / r).cast<float>().normalized();
  const float sign = flip_normals ? -1.0f : 1.0f;
  out.ng = sign * n_out;
  const SphereCoords sc = sphere_coords(local, r);
  out.uv = sc.uv;
  out.dpdu = sc.dpdu;
  out.dpdv = sc.dpdv;
  out.dndu = sign * sc.dpdu / m_radius;
  out.dndv = sign * sc.dpdv / m_radius;
  // At the poles dp/du vanishes; from_normal_tangent then picks an arbitrary tangent.
  out.shading = Frame::from_normal_tangent(out.ng, out.dpdu);
}

PositionSample Sphere::sample_area(const Vec2& u) const {
  const Vec3 dir = core::warp::square_to_uniform_sphere(u);
  PositionSample s;
  s.p = m_center + m_radius * dir;
  s.n = flip_normals ? Vec3(-dir) : dir;
  s.uv = sphere_coords(Vec3d(dir.cast<double>() * double(m_radius)), double(m_radius)).uv;
  s.pdf_area = 1.0f / area();
  return s;
}

}  // namespace dp::scene
