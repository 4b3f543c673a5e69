#include "scene/scene.h"

#include "core/error.h"
#include "scene/embree_accel.h"

namespace dp::scene {

Scene::Scene() = default;
Scene::~Scene() = default;

int Scene::add_bsdf(BsdfPtr bsdf, const std::string& name) {
  DP_CHECK(!m_committed, "scene already committed");
  DP_CHECK(bsdf != nullptr, "null bsdf");
  m_bsdfs.push_back(std::move(bsdf));
  m_bsdf_names.push_back(name);
  return int(m_bsdfs.size()) - 1;
}

int Scene::add_medium(HomogeneousMedium medium) {
  DP_CHECK(!m_committed, "scene already committed");
  m_media.push_back(std::move(medium));
  return int(m_media.size()) - 1;
}

int Scene::add_shape(ShapePtr shape, const Rgb& emission) {
  DP_CHECK(!m_committed, "scene already committed");
  DP_CHECK(shape != nullptr, "null shape");
  const int index = int(m_shapes.size());
  if ((emission > 0.0f).any()) {
    m_emitters.push_back(std::make_unique<AreaEmitter>(shape.get(), emission));
    shape->emitter = int(m_emitters.size()) - 1;
  }
  m_shapes.push_back(std::move(shape));
  return index;
}

int Scene::add_emitter(EmitterPtr emitter) {
  DP_CHECK(!m_committed, "scene already committed");
  DP_CHECK(emitter->kind() != EmitterKind::area, "area emitters are added with add_shape");
  if (emitter->kind() == EmitterKind::environment) {
    if (m_env) throw ValueError("a scene can have only one environment emitter", m_source);
    m_env = static_cast<const EnvironmentEmitter*>(emitter.get());
  }
  m_emitters.push_back(std::move(emitter));
  return int(m_emitters.size()) - 1;
}

void Scene::set_camera(const CameraDesc& desc) { m_camera = std::make_unique<PerspectiveCamera>(desc); }

void Scene::commit() {
  DP_CHECK(!m_committed, "scene already committed");
  if (!m_camera) throw ValueError("the scene has no camera", m_source);
  m_bounds = Bounds3();
  for (const auto& s : m_shapes) m_bounds.expand(s->bounds());
  if (!m_bounds.valid()) {
    m_bounds.expand(m_camera->position());
    m_bounds.expand(m_camera->position() + m_camera->forward());
  }
  for (auto& e : m_emitters) e->prepare(m_bounds);

  m_caps = Caps();
  for (const auto& b : m_bsdfs) {
    m_caps.has_specular |= b->has_delta();
    m_caps.has_glossy |= b->has_glossy();
    m_caps.has_textures |= b->has_texture();
  }
  m_caps.has_media = !m_media.empty();
  for (const auto& e : m_emitters) {
    m_caps.has_delta_lights |= e->is_delta();
    m_caps.has_env |= e->kind() == EmitterKind::environment;
  }
  for (const auto& s : m_shapes) {
    DP_CHECK(s->material < int(m_bsdfs.size()), "shape material index out of range");
    DP_CHECK(s->emitter < int(m_emitters.size()), "shape emitter index out of range");
  }
  m_accel = std::make_unique<EmbreeAccel>(m_shapes);
  m_committed = true;
}

std::optional<SurfaceHit> Scene::intersect(const Ray& ray) const {
  std::optional<SurfaceHit> hit(std::in_place);
  if (!intersect(ray, *hit)) hit.reset();
  return hit;
}

bool Scene::intersect(const Ray& ray, SurfaceHit& hit) const {
  RawHit raw;
  if (!m_accel->intersect(ray, raw)) return false;
  const Shape& shape = *m_shapes[size_t(raw.shape)];
  shape.fill_surface(raw.prim, raw.b, ray, raw.t, hit);
  hit.t = raw.t;
  hit.shape = raw.shape;
  hit.prim = raw.prim;
  hit.bsdf = shape.material >= 0 ? m_bsdfs[size_t(shape.material)].get() : nullptr;
  hit.emitter = shape.emitter >= 0 ? m_emitters[size_t(shape.emitter)].get() : nullptr;
  hit.interior_medium = shape.interior_medium;
  hit.exterior_medium = shape.exterior_medium;
  return true;
}

bool Scene::occluded(const Ray& ray) const { return m_accel->occluded(ray); }

bool Scene::trace_from(const SurfaceHit& from, const Vec3& d, SurfaceHit& out) const {
  const Vec3 p = from.p, ng = from.ng;  // copies: `out` may alias `from`
  const int shape = from.shape;
  Ray r = continue_ray(from, d);
  const bool planar = shape >= 0 && m_shapes[size_t(shape)]->kind() == ShapeKind::mesh;
  for (int attempt = 0; attempt < 4; ++attempt) {
    if (!intersect(r, out)) return false;
    // A hit of the same mesh lying in the origin triangle's own plane (that triangle or a
    // coplanar neighbour) is the ray re-finding its origin surface: skip past it.
    if (!planar || out.shape != shape || std::abs(ng.dot(out.p - p)) > r.tmin) return true;
    r.tmin = std::max(2.0f * r.tmin, 1.0001f * (out.p - p).norm());
  }
  return false;
}

bool Scene::occluded(const Vec3& a, const Vec3& b) const {
  const Vec3 d = b - a;
  const float len = d.norm();
  if (!(len > 0.0f)) return false;
  Ray r;
  r.d = d / len;
  const float ea = epsilon_at(a), eb = epsilon_at(b);
  r.o = a;
  r.tmin = ea;
  r.tmax = len - eb;
  if (r.tmax <= r.tmin) return false;
  return m_accel->occluded(r);
}

float Scene::emitter_pmf(const Emitter* e) const {
  return (e && !m_emitters.empty()) ? 1.0f / float(m_emitters.size()) : 0.0f;
}

size_t Scene::triangle_count() const {
  size_t n = 0;
  for (const auto& s : m_shapes)
    if (const auto* m = dynamic_cast<const TriangleMesh*>(s.get())) n += m->triangles.size();
  return n;
}

size_t Scene::degenerate_triangles_skipped() const {
  size_t n = 0;
  for (const auto& s : m_shapes)
    if (const auto* m = dynamic_cast<const TriangleMesh*>(s.get())) n += m->degenerate_skipped;
  return n;
}

}  // namespace dp::scene
