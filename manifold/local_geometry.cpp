#include "manifold/local_geometry.h"

#include <cmath>

namespace dp::manifold {

namespace {

Vec3d d3(const Vec3& v) { return v.cast<double>(); }

// Derivative of the normalized vector n = r / |r| given dr: (dr - n (n.dr)) / |r|.
Vec3d d_normalized(const Vec3d& n, double len, const Vec3d& dr) { return (dr - n * n.dot(dr)) / len; }

bool mesh_frame(const scene::TriangleMesh& m, int prim, const Vec3d& p, LocalFrame& f) {
  if (prim < 0 || size_t(prim) >= m.triangles.size()) return false;
  const auto& tri = m.triangles[size_t(prim)];
  const Vec3d v0 = d3(m.positions[tri[0]]), v1 = d3(m.positions[tri[1]]), v2 = d3(m.positions[tri[2]]);
  const Vec3d e1 = v1 - v0, e2 = v2 - v0;
  const Vec3d cr = e1.cross(e2);
  const double area2 = cr.norm();
  if (!(area2 > 0.0) || !std::isfinite(area2)) return false;
  f.ng = cr / area2;
  // Project onto the triangle's plane and find barycentrics from the Gram system.
  const Vec3d q = p - f.ng * f.ng.dot(p - v0);
  const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2);
  const double gdet = g11 * g22 - g12 * g12;
  if (!(gdet > 0.0)) return false;
  const Vec3d r = q - v0;
  const double r1 = e1.dot(r), r2 = e2.dot(r);
  const double b1 = (g22 * r1 - g12 * r2) / gdet, b2 = (g11 * r2 - g12 * r1) / gdet;
  f.p = q;

  // dp/du as in scene/shapes/triangle_mesh.cpp (pbrt-v3 Sec. 3.6.2), or e1 without uvs.
  Vec3d dpdu = e1;
  if (!m.uvs.empty()) {
    const Vec2d uv0 = m.uvs[tri[0]].cast<double>(), uv1 = m.uvs[tri[1]].cast<double>(),
                uv2 = m.uvs[tri[2]].cast<double>();
    const Vec2d duv1 = uv1 - uv0, duv2 = uv2 - uv0;
    const double det = duv1.x() * duv2.y() - duv1.y() * duv2.x();
    // The scene falls back to an arbitrary frame around ng for degenerate uvs.
    dpdu = std::abs(det) > 1e-12 ? Vec3d((duv2.y() * e1 - duv1.y() * e2) / det)
                                 : d3(Frame::from_normal(f.ng.cast<float>()).s);
  }
  const double lu = dpdu.norm();
  if (!(lu > 0.0)) return false;
  f.T1 = dpdu / lu;
  f.T2 = f.ng.cross(f.T1);
  f.dT1_1.setZero();
  f.dT1_2.setZero();  // dp/du is constant over a triangle

  f.n = f.ng;
  f.dn1.setZero();
  f.dn2.setZero();
  if (m.smooth && !m.normals.empty()) {
    const Vec3d n0 = d3(m.normals[tri[0]]), n1 = d3(m.normals[tri[1]]), n2 = d3(m.normals[tri[2]]);
    const double b0 = 1.0 - b1 - b2;
    const Vec3d n_raw = b0 * n0 + b1 * n1 + b2 * n2;
    const double len = n_raw.norm();
    if (!(len > 0.0) || !std::isfinite(len)) return false;
    f.n = n_raw / len;
    // Barycentric rate along a tangent T: (db1, db2) = Gram^-1 (e1.T, e2.T).
    auto along = [&](const Vec3d& T) {
      const double s1 = e1.dot(T), s2 = e2.dot(T);
      const double db1 = (g22 * s1 - g12 * s2) / gdet, db2 = (g11 * s2 - g12 * s1) / gdet;
      return d_normalized(f.n, len, (n1 - n0) * db1 + (n2 - n0) * db2);
    };
    f.dn1 = along(f.T1);
    f.dn2 = along(f.T2);
  }
  return true;
}

bool sphere_frame(const scene::Sphere& sph, const Vec3d& p, LocalFrame& f) {
  const Vec3d c = d3(sph.center());
  const double r = double(sph.radius());
  Vec3d local = p - c;
  const double len = local.norm();
  if (!(len > 0.0)) return false;
  local *= r / len;
  f.p = c + local;
  const double sigma = sph.flip_normals ? -1.0 : 1.0;
  f.ng = sigma * local / r;
  f.n = f.ng;
  // dp/du = 2 pi (-y, x, 0): T1 = a / |a| (scene/shapes/sphere.cpp parameterization).
  const Vec3d a(-local.y(), local.x(), 0.0);
  const double la = a.norm();
  if (!(la > 1e-9 * r)) return false;  // pole
  f.T1 = a / la;
  f.T2 = f.ng.cross(f.T1);
  auto dT1 = [&](const Vec3d& T) {
    const Vec3d da(-T.y(), T.x(), 0.0);
    return Vec3d((da - f.T1 * f.T1.dot(da)) / la);
  };
  f.dT1_1 = dT1(f.T1);
  f.dT1_2 = dT1(f.T2);
  f.dn1 = sigma * f.T1 / r;
  f.dn2 = sigma * f.T2 / r;
  return true;
}

}  // namespace

bool finish_frame(LocalFrame& f) {
  const Vec3d s_raw = f.T1 - f.n * f.n.dot(f.T1);
  const double ls = s_raw.norm();
  if (!(ls > 1e-9)) return false;
  f.s = s_raw / ls;
  f.t = f.n.cross(f.s);
  auto frame_derivs = [&](const Vec3d& dT, const Vec3d& dn, Vec3d& ds, Vec3d& dt) {
    const Vec3d ds_raw = dT - dn * f.n.dot(f.T1) - f.n * (dn.dot(f.T1) + f.n.dot(dT));
    ds = d_normalized(f.s, ls, ds_raw);
    dt = dn.cross(f.s) + f.n.cross(ds);
  };
  frame_derivs(f.dT1_1, f.dn1, f.ds1, f.dt1);
  frame_derivs(f.dT1_2, f.dn2, f.ds2, f.dt2);
  return f.s.allFinite() && f.ds1.allFinite() && f.ds2.allFinite();
}

bool local_frame(const scene::Shape& shape, int prim, const Vec3d& p, LocalFrame& out) {
  bool ok = false;
  if (shape.kind() == scene::ShapeKind::mesh)
    ok = mesh_frame(static_cast<const scene::TriangleMesh&>(shape), prim, p, out);
  else
    ok = sphere_frame(static_cast<const scene::Sphere&>(shape), p, out);
  return ok && finish_frame(out);
}

std::optional<ChainVertex> make_vertex(const scene::Scene& scene, const scene::SurfaceHit& hit, Interaction type,
                                       double eta) {
  if (hit.shape < 0 || size_t(hit.shape) >= scene.shapes().size()) return std::nullopt;
  ChainVertex v;
  if (!local_frame(*scene.shapes()[size_t(hit.shape)], hit.prim, d3(hit.p), v.f)) return std::nullopt;
  v.type = type;
  v.eta = eta;
  v.shape = hit.shape;
  v.prim = hit.prim;
  return v;
}

ChainVertex make_vertex(const scene::SurfacePoint& sp, Interaction type, double eta) {
  ChainVertex v;
  v.f.p = d3(sp.p);
  v.f.ng = d3(sp.ng).normalized();
  v.f.n = d3(sp.shading.n).normalized();
  v.f.T1 = (d3(sp.dpdu) - v.f.ng * v.f.ng.dot(d3(sp.dpdu))).normalized();
  v.f.T2 = v.f.ng.cross(v.f.T1);
  // dndu, dndv are along dp/du, dp/dv: express them along the orthonormal tangents.
  const Vec3d du = d3(sp.dpdu), dv = d3(sp.dpdv);
  const double a11 = du.dot(v.f.T1), a21 = dv.dot(v.f.T1), a22 = dv.dot(v.f.T2);
  if (std::abs(a11) > 0 && std::abs(a22) > 0) {
    v.f.dn1 = d3(sp.dndu) / a11;
    v.f.dn2 = (d3(sp.dndv) - a21 * v.f.dn1) / a22;
  }
  if (!finish_frame(v.f)) v.has_surface = false;
  v.type = type;
  v.eta = eta;
  return v;
}

ChainVertex make_point(const Vec3d& p) {
  ChainVertex v;
  v.f.p = p;
  v.has_surface = false;
  return v;
}

ChainVertex make_plane_end(const Vec3d& p, const Vec3d& normal) {
  ChainVertex v;
  v.f.p = p;
  v.f.ng = v.f.n = normal.normalized();
  const Vec3d a = std::abs(v.f.n.x()) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
  v.f.T1 = (a - v.f.n * v.f.n.dot(a)).normalized();
  v.f.T2 = v.f.n.cross(v.f.T1);
  v.f.s = v.f.T1;
  v.f.t = v.f.T2;  // n x s; every derivative stays 0 (a plane)
  v.has_surface = false;
  return v;
}

std::optional<TraceHit> trace(const scene::Scene& scene, const Vec3d& origin, const Vec3d& dir,
                              const Vec3d& ng_origin) {
  Ray ray;
  ray.o = origin.cast<float>();
  ray.d = dir.cast<float>().normalized();
  Vec3d o = origin;
  if (ng_origin.squaredNorm() > 0) {
    const double side = dir.dot(ng_origin) >= 0 ? 1.0 : -1.0;
    // The scene's one offset rule (Scene::epsilon_at). An earlier rule scaled it by the
    // scene's extent as well (~1 unit in a 556-unit Cornell box), so Embree hit other
    // points than the exact ray and the refinement below fell back to them.
    const double eps = double(scene::Scene::epsilon_at(origin.cast<float>()));
    o = origin + side * eps * ng_origin;
    ray.o = o.cast<float>();
  }
  ray.tmin = 0;
  ray.tmax = kInfinity;
  const auto hit = scene.intersect(ray);
  if (!hit) return std::nullopt;
  TraceHit out;
  out.shape = hit->shape;
  out.prim = hit->prim;
  const scene::Shape& shape = *scene.shapes()[size_t(hit->shape)];
  const double t_est = (d3(hit->p) - origin).dot(dir);
  double t = t_est;
  if (shape.kind() == scene::ShapeKind::mesh) {
    const auto& m = static_cast<const scene::TriangleMesh&>(shape);
    const auto& tri = m.triangles[size_t(hit->prim)];
    const Vec3d v0 = d3(m.positions[tri[0]]);
    const Vec3d ng = (d3(m.positions[tri[1]]) - v0).cross(d3(m.positions[tri[2]]) - v0);
    const double denom = ng.dot(dir);
    if (std::abs(denom) > 1e-300) t = ng.dot(v0 - origin) / denom;
  } else {
    const auto& sph = static_cast<const scene::Sphere&>(shape);
    const Vec3d oc = origin - d3(sph.center());
    const double r = double(sph.radius());
    const double b = oc.dot(dir);
    const Vec3d l = oc - b * dir;  // perpendicular offset (Ray Tracing Gems Ch. 7)
    const double disc = r * r - l.squaredNorm();
    if (disc >= 0) {
      const double q = -(b + std::copysign(std::sqrt(disc), b));
      const double cc = (oc.norm() - r) * (oc.norm() + r);
      const double t0 = q, t1 = q != 0.0 ? cc / q : q;
      t = std::abs(t0 - t_est) < std::abs(t1 - t_est) ? t0 : t1;
    }
  }
  if (!std::isfinite(t) || std::abs(t - t_est) > 1e-2 * (1.0 + std::abs(t_est))) t = t_est;
  out.t = t;
  out.p = origin + t * dir;
  return out;
}

}  // namespace dp::manifold
