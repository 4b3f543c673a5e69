// Emitters. Contract:
//  * sample_direct(ref, u): a point (or direction) on the emitter for next-event
//    estimation from `ref`. `pdf` is solid angle at ref (for delta emitters pdf = 1 and
//    `delta` is set); `pdf_area` is the area density of the sampled point (0 for delta
//    and infinite emitters); `radiance` is what arrives at ref along -wi, before
//    visibility: Le for area/env, intensity/d^2 for point/spot, irradiance for
//    directional (delta in direction).
//  * pdf_direct(ref, point): solid-angle density of sample_direct choosing that point
//    (area emitters) or direction (environment).
//  * pdf_area_direct(ref, p, n): area density with which sample_direct(ref) returns the
//    point p of normal n, whichever side of it ref sees (sample_direct still samples a
//    point behind the emitter, only with pdf = 0 and no radiance): what a connection that
//    reaches p other than straight from ref (MNEE's refraction chains) needs. 0 for delta
//    and infinite emitters.
//  * Area emitters emit from the front side only (the side of the geometric normal).
#pragma once

#include <memory>
#include <string>

#include "core/image.h"
#include "core/math.h"
#include "scene/surface.h"

namespace dp::core {
class Distribution2D;
}

namespace dp::scene {

class Shape;
class TriangleMesh;

struct DirectSample {
  Vec3 p{0, 0, 0};   // point on the emitter (for infinite emitters: ref + wi * far)
  Vec3 n{0, 0, 1};   // emitter normal at p (area), 0 for others
  Vec3 wi{0, 0, 1};  // unit direction from ref toward the emitter
  float dist = 0;    // distance ref -> p (infinity for env/directional)
  Rgb radiance = Rgb::Zero();
  float pdf = 0;
  float pdf_area = 0;
  bool delta = false;
};

enum class EmitterKind { area, point, spot, directional, environment };

class Emitter {
 public:
  virtual ~Emitter() = default;
  virtual EmitterKind kind() const = 0;
  virtual DirectSample sample_direct(const Vec3& ref, const Vec2& u) const = 0;
  // Area: `p`,`n` a point on the emitter; environment: `p` unused, `n` unused, `w` =
  // direction from ref toward the emitter. Delta emitters return 0.
  virtual float pdf_direct(const Vec3& ref, const Vec3& p, const Vec3& n, const Vec3& w) const = 0;
  virtual float pdf_area_direct(const Vec3& ref, const Vec3& p, const Vec3& n) const {
    (void)ref; (void)p; (void)n;
    return 0.0f;
  }
  // Radiance leaving an area emitter at surface point `sp` toward unit direction `w`.
  virtual Rgb eval(const SurfacePoint& sp, const Vec3& w) const { (void)sp; (void)w; return Rgb::Zero(); }
  // Total emitted power (W), used for light selection and statistics.
  virtual Rgb power() const = 0;
  // Called by Scene::commit() with the scene bounds (infinite emitters need the radius).
  virtual void prepare(const Bounds3& scene_bounds) { (void)scene_bounds; }
  bool is_delta() const { return kind() == EmitterKind::point || kind() == EmitterKind::spot || kind() == EmitterKind::directional; }
  bool is_infinite() const { return kind() == EmitterKind::directional || kind() == EmitterKind::environment; }
};

class AreaEmitter final : public Emitter {
 public:
  AreaEmitter(const Shape* shape, const Rgb& radiance);
  EmitterKind kind() const override { return EmitterKind::area; }
  DirectSample sample_direct(const Vec3& ref, const Vec2& u) const override;
  float pdf_direct(const Vec3& ref, const Vec3& p, const Vec3& n, const Vec3& w) const override;
  float pdf_area_direct(const Vec3& ref, const Vec3& p, const Vec3& n) const override;
  Rgb eval(const SurfacePoint& sp, const Vec3& w) const override;
  Rgb power() const override;
  const Rgb& radiance() const { return m_radiance; }
  const Shape* shape() const { return m_shape; }

 private:
  const Shape* m_shape;
  const TriangleMesh* m_mesh = nullptr;  // m_shape if it is a mesh (sampled inline)
  Rgb m_radiance;
};

class PointEmitter final : public Emitter {
 public:
  PointEmitter(const Vec3& position, const Rgb& intensity) : m_position(position), m_intensity(intensity) {}
  EmitterKind kind() const override { return EmitterKind::point; }
  DirectSample sample_direct(const Vec3& ref, const Vec2& u) const override;
  float pdf_direct(const Vec3&, const Vec3&, const Vec3&, const Vec3&) const override { return 0; }
  Rgb power() const override { return 4.0f * kPi * m_intensity; }
  const Vec3& position() const { return m_position; }

 private:
  Vec3 m_position;
  Rgb m_intensity;
};

// Intensity * smoothstep falloff between the cutoff and falloff_start cone angles.
class SpotEmitter final : public Emitter {
 public:
  SpotEmitter(const Vec3& position, const Vec3& direction, const Rgb& intensity, float cutoff_deg,
              float falloff_start_deg);
  EmitterKind kind() const override { return EmitterKind::spot; }
  DirectSample sample_direct(const Vec3& ref, const Vec2& u) const override;
  float pdf_direct(const Vec3&, const Vec3&, const Vec3&, const Vec3&) const override { return 0; }
  Rgb power() const override;
  // Intensity toward unit direction w (world space, pointing away from the light).
  Rgb intensity(const Vec3& w) const;
  const Vec3& position() const { return m_position; }
  const Frame& frame() const { return m_frame; }  // n = the spot's axis
  float cos_cutoff() const { return m_cos_cutoff; }

 private:
  Vec3 m_position;
  Frame m_frame;
  Rgb m_intensity;
  float m_cos_cutoff, m_cos_falloff_start;
};

class DirectionalEmitter final : public Emitter {
 public:
  // `direction` is the direction light travels.
  DirectionalEmitter(const Vec3& direction, const Rgb& irradiance);
  void prepare(const Bounds3& scene_bounds) override;
  EmitterKind kind() const override { return EmitterKind::directional; }
  DirectSample sample_direct(const Vec3& ref, const Vec2& u) const override;
  float pdf_direct(const Vec3&, const Vec3&, const Vec3&, const Vec3&) const override { return 0; }
  Rgb power() const override;
  const Rgb& irradiance() const { return m_irradiance; }

 private:
  Vec3 m_direction;
  Rgb m_irradiance;
  float m_scene_radius = 1;
};

// Constant radiance, or a lat-long map (Mitsuba's envmap parameterization, documented
// in emitter_environment.cpp; y is up) importance-sampled by luminance * sin(theta).
class EnvironmentEmitter final : public Emitter {
 public:
  explicit EnvironmentEmitter(const Rgb& radiance);
  EnvironmentEmitter(core::Image latlong, const Mat3& to_world, float scale);
  void prepare(const Bounds3& scene_bounds) override;
  ~EnvironmentEmitter() override;
  EmitterKind kind() const override { return EmitterKind::environment; }
  DirectSample sample_direct(const Vec3& ref, const Vec2& u) const override;
  float pdf_direct(const Vec3& ref, const Vec3& p, const Vec3& n, const Vec3& w) const override;
  // Radiance arriving along -w, i.e. seen when looking in world direction w.
  Rgb eval_direction(const Vec3& w) const;
  Rgb power() const override;

 private:
  Rgb m_radiance = Rgb::Zero();
  core::Image m_map;
  Mat3 m_to_world = Mat3::Identity();
  float m_scale = 1;
  float m_scene_radius = 1;
  std::unique_ptr<core::Distribution2D> m_dist;
};

using EmitterPtr = std::unique_ptr<Emitter>;

}  // namespace dp::scene
