// The scene: geometry, materials, emitters, media, camera and the acceleration
// structure. Built by a front end (YAML loader, Mitsuba importer, or code) through the
// add_* methods, then commit() builds the Embree BVH. After commit the scene is
// immutable and safe to query from many threads.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scene/bsdf/bsdf.h"
#include "scene/camera.h"
#include "scene/emitters/emitter.h"
#include "scene/media/medium.h"
#include "scene/shapes/shape.h"
#include "scene/surface.h"

namespace dp::scene {

// Capability flags so integrators can skip machinery a scene does not need.
struct Caps {
  bool has_specular = false;      // some material has a delta lobe
  bool has_glossy = false;        // some material has a glossy (microfacet/phong) lobe
  bool has_media = false;
  bool has_textures = false;
  bool has_delta_lights = false;  // point, spot or directional
  bool has_env = false;           // environment emitter
};

struct IntegratorDefaults {  // the scene file's optional `integrator:` block
  std::string type = "path";
  int max_depth = 8;
  int spp = 0;  // 0 = not set by the scene
  // Every other key of the block, verbatim, for the integrator's own settings.
  std::map<std::string, std::string> settings;
};

class EmbreeAccel;

class Scene {
 public:
  Scene();
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // --- construction (before commit) ---
  int add_bsdf(BsdfPtr bsdf, const std::string& name = {});
  int add_medium(HomogeneousMedium medium);
  // Adds a shape; if `emission` is non-zero an AreaEmitter is attached to it.
  int add_shape(ShapePtr shape, const Rgb& emission = Rgb::Zero());
  int add_emitter(EmitterPtr emitter);  // point/spot/directional/environment
  void set_camera(const CameraDesc& desc);
  void set_camera_medium(int medium) { m_camera_medium = medium; }
  void set_integrator_defaults(const IntegratorDefaults& d) { m_integrator = d; }
  void set_source(const std::string& path) { m_source = path; }
  // Builds the BVH and light-selection tables; computes caps and bounds.
  void commit();

  // --- queries (after commit) ---
  std::optional<SurfaceHit> intersect(const Ray& ray) const;
  // The same query filling `hit` in place (false on a miss, `hit` then unspecified):
  // hot loops avoid building and copying the optional's ~150-byte SurfaceHit.
  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  bool occluded(const Ray& ray) const;
  // True if the open segment between a and b is blocked (endpoints excluded by epsilon).
  bool occluded(const Vec3& a, const Vec3& b) const;
  // The one rule for continuing a path from a surface vertex (PT, volpath, G-PT and
  // every shift, BDPT/VCM subpaths; issue 18): the ray starts AT the vertex, with
  // tmin = the scene's ray epsilon scaled by the point's magnitude (as occluded(a, b)
  // and Mitsuba's mint), not at an origin pushed along the normal. With a pushed origin
  // the next vertex is not on the sampled direction from the vertex, so the stored
  // direction, the cosines and the geometry of consecutive vertices disagree by
  // O(eps / (d cos)) relative (1e-4..1e-3 for ordinary bounces, up to 20% at grazing
  // ones, measured in the G-PT furnace), which breaks the exact cancellations a shift
  // relies on; and PT and G-PT would sample different paths from the same numbers.
  Ray continue_ray(const SurfacePoint& sp, const Vec3& d) const {
    Ray r;
    r.o = sp.p;
    r.d = d;
    r.tmin = epsilon_at(sp.p);
    r.tmax = kInfinity;
    return r;
  }
  // The next vertex after `from` along d (false: the ray leaves the scene). `out` may be
  // `from` itself (the hot loops trace in place). A ray leaving a planar mesh cannot hit
  // that plane again: hits of the same mesh within tmin of the origin triangle's plane
  // (self-hits at grazing angles, where the rounding of p over cos exceeds tmin) are
  // skipped.
  bool trace_from(const SurfaceHit& from, const Vec3& d, SurfaceHit& out) const;
  std::optional<SurfaceHit> trace_from(const SurfaceHit& from, const Vec3& d) const {
    SurfaceHit h;
    if (!trace_from(from, d, h)) return std::nullopt;
    return h;
  }
  // Ray leaving surface point sp in direction d, origin offset along ng to avoid
  // self-intersection: shadow rays toward infinitely distant emitters. Paths continue
  // with continue_ray/trace_from. (Inline, as spawn_segment: called once or twice per path vertex,
  // and a Ray returned from an out-of-line call is reloaded through memory.)
  Ray spawn_ray(const SurfacePoint& sp, const Vec3& d) const {
    Ray r;
    r.o = offset_origin(sp.p, sp.ng, d);
    r.d = d;
    r.tmin = 0.0f;
    r.tmax = kInfinity;
    return r;
  }
  // Segment from sp toward target, shortened by epsilon at both ends.
  Ray spawn_segment(const SurfacePoint& sp, const Vec3& target) const {
    const Vec3 d0 = target - sp.p;
    Ray r;
    r.o = offset_origin(sp.p, sp.ng, d0);
    const Vec3 d = target - r.o;
    const float len = d.norm();
    r.d = d / len;
    r.tmin = 0.0f;
    r.tmax = std::max(0.0f, len - 2.0f * epsilon_at(target));
    return r;
  }

  // Light selection for next-event estimation: proportional to emitted power is not
  // robust for environment maps, so selection is uniform over emitters.
  const Emitter* sample_emitter(float u, float& pmf) const {  // inline: once per path vertex
    if (m_emitters.empty()) {
      pmf = 0.0f;
      return nullptr;
    }
    const size_t n = m_emitters.size();
    const size_t i = std::min(size_t(u * float(n)), n - 1);
    pmf = 1.0f / float(n);
    return m_emitters[i].get();
  }
  float emitter_pmf(const Emitter* e) const;

  const PerspectiveCamera& camera() const { return *m_camera; }
  const std::vector<BsdfPtr>& bsdfs() const { return m_bsdfs; }
  const std::vector<std::string>& bsdf_names() const { return m_bsdf_names; }
  const std::vector<ShapePtr>& shapes() const { return m_shapes; }
  const std::vector<EmitterPtr>& emitters() const { return m_emitters; }
  const std::vector<HomogeneousMedium>& media() const { return m_media; }
  const EnvironmentEmitter* environment() const { return m_env; }
  int camera_medium() const { return m_camera_medium; }
  const IntegratorDefaults& integrator_defaults() const { return m_integrator; }
  const Caps& caps() const { return m_caps; }
  const Bounds3& bounds() const { return m_bounds; }
  float scene_radius() const { return 0.5f * m_bounds.diagonal(); }
  const std::string& source() const { return m_source; }
  size_t triangle_count() const;
  size_t degenerate_triangles_skipped() const;
  // The one ray-offset rule: a relative epsilon times the point's magnitude (float keeps
  // ~7 digits of a coordinate, so the rounding of p grows with |p|; Mitsuba's mint uses
  // the same (1 + max|p|) form). The scene's extent does not enter: an earlier rule also
  // scaled by it, so offsets grew with extent * |p| (~3 units in the 556-unit Cornell box).
  static constexpr float kRelativeEpsilon = 1e-5f;
  static float epsilon_at(const Vec3& p) { return kRelativeEpsilon * (1.0f + p.cwiseAbs().maxCoeff()); }
  // The raw acceleration structure (benchmarks compare against bare ray loops).
  const EmbreeAccel& accel() const { return *m_accel; }

 private:
  static Vec3 offset_origin(const Vec3& p, const Vec3& ng, const Vec3& d) {
    const float scale = epsilon_at(p);
    return p + (ng.dot(d) >= 0.0f ? scale : -scale) * ng;
  }

  std::vector<BsdfPtr> m_bsdfs;
  std::vector<std::string> m_bsdf_names;
  std::vector<ShapePtr> m_shapes;
  std::vector<EmitterPtr> m_emitters;
  std::vector<HomogeneousMedium> m_media;
  std::unique_ptr<PerspectiveCamera> m_camera;
  const EnvironmentEmitter* m_env = nullptr;
  int m_camera_medium = -1;
  IntegratorDefaults m_integrator;
  Caps m_caps;
  Bounds3 m_bounds;
  std::string m_source;
  std::unique_ptr<EmbreeAccel> m_accel;
  bool m_committed = false;
};

}  // namespace dp::scene
