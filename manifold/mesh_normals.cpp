// CGAL is header-only here (Simple_cartesian<double>, no exact kernels needed).
#include "manifold/mesh_normals.h"

#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/jet_estimate_normals.h>

#include <map>
#include <tuple>
#include <utility>
#include <vector>

namespace dp::manifold {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using Mesh = CGAL::Surface_mesh<Point>;

}  // namespace

bool needs_vertex_normals(const scene::TriangleMesh& mesh, const scene::Bsdf* material) {
  if (!mesh.normals.empty() || !mesh.smooth || material == nullptr) return false;
  return material->has_delta() || material->has_glossy();
}

size_t estimate_vertex_normals(scene::TriangleMesh& mesh, const NormalEstimation& opts) {
  // Weld identical positions.
  std::map<std::tuple<float, float, float>, uint32_t> index;
  std::vector<uint32_t> weld(mesh.positions.size());
  std::vector<Point> points;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3& p = mesh.positions[i];
    const auto [it, inserted] = index.emplace(std::make_tuple(p.x(), p.y(), p.z()), uint32_t(points.size()));
    if (inserted) points.emplace_back(double(p.x()), double(p.y()), double(p.z()));
    weld[i] = it->second;
  }

  // Angle-weighted normals from CGAL PMP on the welded surface mesh. Faces that would
  // make it non-manifold are left out of the mesh and contribute through `fallback`.
  Mesh sm;
  std::vector<Mesh::Vertex_index> vids;
  vids.reserve(points.size());
  for (const Point& p : points) vids.push_back(sm.add_vertex(p));
  std::vector<Vector> fallback(points.size(), Vector(0, 0, 0));
  for (const auto& tri : mesh.triangles) {
    const uint32_t a = weld[tri[0]], b = weld[tri[1]], c = weld[tri[2]];
    if (a == b || b == c || a == c) continue;
    if (sm.add_face(vids[a], vids[b], vids[c]) == Mesh::null_face()) {
      const Vector fn = CGAL::cross_product(points[b] - points[a], points[c] - points[a]);
      for (uint32_t k : {a, b, c}) fallback[k] = fallback[k] + fn;
    }
  }
  auto vnormals = sm.add_property_map<Mesh::Vertex_index, Vector>("v:dp_normal", Vector(0, 0, 0)).first;
  CGAL::Polygon_mesh_processing::compute_vertex_normals(sm, vnormals);
  std::vector<Vector> normals(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    Vector v = vnormals[vids[k]];
    if (!(v.squared_length() > 0)) v = fallback[k];
    normals[k] = v;
  }

  if (opts.method == NormalMethod::jet_fit && points.size() > opts.jet_neighbors) {
    using PN = std::pair<Point, Vector>;
    std::vector<PN> pts(points.size());
    for (size_t k = 0; k < points.size(); ++k) pts[k] = PN(points[k], Vector(0, 0, 0));
    CGAL::jet_estimate_normals<CGAL::Sequential_tag>(
        pts, opts.jet_neighbors,
        CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PN>())
            .normal_map(CGAL::Second_of_pair_property_map<PN>()));
    for (size_t k = 0; k < points.size(); ++k) {
      Vector j = pts[k].second;
      if (!(j.squared_length() > 0) || !std::isfinite(j.x())) continue;
      if (j * normals[k] < 0) j = -j;  // orient by the winding
      normals[k] = j;
    }
  }

  mesh.normals.assign(mesh.positions.size(), Vec3(0, 0, 1));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vector& v = normals[weld[i]];
    const double len = std::sqrt(v.squared_length());
    if (len > 0 && std::isfinite(len))
      mesh.normals[i] = Vec3(float(v.x() / len), float(v.y() / len), float(v.z() / len));
  }
  return points.size();
}

scene::MeshNormalHook normal_estimation_hook(const NormalEstimation& opts) {
  return [opts](scene::TriangleMesh& mesh, const scene::Bsdf* material) {
    if (!needs_vertex_normals(mesh, material)) return false;
    estimate_vertex_normals(mesh, opts);
    return true;
  };
}

}  // namespace dp::manifold
