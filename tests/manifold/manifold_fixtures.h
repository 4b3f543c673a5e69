// Scenes and chain builders for the manifold tests (built in code through the Scene API).
#pragma once

#include <map>
#include <memory>
#include <optional>

#include "manifold/constraints.h"
#include "manifold/local_geometry.h"
#include "manifold/walk.h"
#include "scene/bsdf/bsdfs.h"
#include "scene/scene.h"

namespace dp::test_mf {

using namespace dp::manifold;

struct Material {
  Interaction type = Interaction::reflection;
  double eta = 1;
};

// A scene under construction plus the interaction of each specular shape.
struct Builder {
  std::unique_ptr<scene::Scene> scene = std::make_unique<scene::Scene>();
  std::map<int, Material> specular;  // shape index -> interaction
  int diffuse = -1, mirror = -1, glass = -1;

  Builder() {
    diffuse = scene->add_bsdf(scene::make_diffuse(scene::constant_texture(Rgb::Constant(0.5f))));
    mirror = scene->add_bsdf(scene::make_mirror(scene::constant_texture(Rgb::Ones())));
    glass = scene->add_bsdf(scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx));
  }
  int add(scene::ShapePtr s, std::optional<Material> m) {
    s->material = !m ? diffuse : (m->type == Interaction::reflection ? mirror : glass);
    const int id = scene->add_shape(std::move(s));
    if (m) specular[id] = *m;
    return id;
  }
  // Quad a b c d (normal = (b - a) x (c - a)).
  int quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, std::optional<Material> m) {
    auto mesh = std::make_unique<scene::TriangleMesh>();
    mesh->positions = {a, b, c, d};
    mesh->triangles = {{0, 1, 2}, {0, 2, 3}};
    mesh->finalize();
    return add(std::move(mesh), m);
  }
  int sphere(const Vec3& c, float r, std::optional<Material> m, bool flip = false) {
    auto s = std::make_unique<scene::Sphere>(c, r);
    s->flip_normals = flip;
    return add(std::move(s), m);
  }
  std::unique_ptr<scene::Scene> commit() {
    scene::CameraDesc cam;
    cam.position = Vec3(0, 0, 10);
    cam.look_at = Vec3(0, 0, 0);
    cam.width = cam.height = 8;
    scene->set_camera(cam);
    scene->commit();
    return std::move(scene);
  }
};

// Traces from x0 along dir; every hit on a specular shape becomes an interior vertex
// (target from `target_of`, default ideal specular) until `max_specular` of them; the
// next hit must be a diffuse shape, which becomes the end. nullopt if that fails.
template <class TargetFn>
std::optional<Chain> trace_chain(const scene::Scene& scene, const std::map<int, Material>& specular,
                                 const ChainVertex& x0, const Vec3d& dir0, int max_specular, TargetFn target_of) {
  Chain c;
  c.v.push_back(x0);
  Vec3d origin = x0.p(), dir = dir0.normalized();
  Vec3d ng = x0.has_surface ? x0.f.ng : Vec3d::Zero();
  for (int k = 0; k <= max_specular; ++k) {
    const auto hit = trace(scene, origin, dir, ng);
    if (!hit) return std::nullopt;
    ChainVertex v;
    if (!local_frame(*scene.shapes()[size_t(hit->shape)], hit->prim, hit->p, v.f)) return std::nullopt;
    v.shape = hit->shape;
    v.prim = hit->prim;
    const auto it = specular.find(hit->shape);
    if (k == max_specular) {
      if (it != specular.end()) return std::nullopt;
      c.v.push_back(v);
      return c;
    }
    if (it == specular.end()) return std::nullopt;
    v.type = it->second.type;
    v.eta = it->second.eta;
    v.target = target_of(k);
    Vec3d out;
    if (scatter(v, -dir, out) != WalkStatus::ok) return std::nullopt;
    c.v.push_back(v);
    origin = v.p();
    dir = out;
    ng = v.f.ng;
  }
  return std::nullopt;
}

inline std::optional<Chain> trace_chain(const scene::Scene& scene, const std::map<int, Material>& specular,
                                        const ChainVertex& x0, const Vec3d& dir0, int max_specular) {
  return trace_chain(scene, specular, x0, dir0, max_specular, [](int) { return Vec2d(0, 0); });
}

inline double rel(const Vec3d& a, const Vec3d& b, double scale) { return (a - b).norm() / scale; }

}  // namespace dp::test_mf
