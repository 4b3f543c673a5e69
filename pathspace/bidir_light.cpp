#include "pathspace/bidir_light.h"

#include <cmath>

#include "core/warp.h"
#include "scene/shapes/shape.h"

namespace dp::pathspace {

float light_pdf_pos(const scene::Scene& scene, const BidirVertex& v) {
  const scene::Emitter* e = v.emitter;
  if (!e) return 0.0f;
  const float pmf = scene.emitter_pmf(e);
  if (e->kind() == scene::EmitterKind::environment) return pmf * e->pdf_direct(v.sp.p, v.sp.p, v.sp.ng, v.sp.ng);
  if (e->kind() != scene::EmitterKind::area) return pmf;  // delta position or direction: discrete
  const float area = static_cast<const scene::AreaEmitter*>(e)->shape()->area();
  return area > 0.0f ? pmf / area : 0.0f;
}

float infinite_disk_radius(const scene::Scene& scene) {
  const float r = scene.scene_radius();
  return r > 0.0f && std::isfinite(r) ? r : 1.0f;
}

float light_pdf_next(const scene::Scene& scene, const BidirVertex& v, const BidirVertex& next) {
  if (!v.infinite()) return solid_angle_to_area(light_pdf_dir(v, (next.sp.p - v.sp.p).normalized()), v, next);
  const float r = infinite_disk_radius(scene);
  const float c = next.on_surface() ? std::abs(next.sp.ng.dot(v.sp.ng)) : 1.0f;
  return c / (kPi * r * r);
}

float light_pdf_dir(const BidirVertex& v, const Vec3& w) {
  if (!v.emitter) return 0.0f;
  if (v.emitter->kind() == scene::EmitterKind::spot) {
    const auto* spot = static_cast<const scene::SpotEmitter*>(v.emitter);
    return core::warp::square_to_uniform_cone_pdf(spot->frame().to_local(w), spot->cos_cutoff());
  }
  if (v.emitter->kind() != scene::EmitterKind::area) return core::warp::square_to_uniform_sphere_pdf();
  const float c = v.sp.ng.dot(w);
  return c > 0.0f ? c * kInvPi : 0.0f;  // cosine-weighted about the front side
}

Rgb light_emit_cos(const BidirVertex& v, const Vec3& w) {
  if (!v.emitter) return Rgb::Zero();
  if (v.emitter->kind() == scene::EmitterKind::environment)
    return static_cast<const scene::EnvironmentEmitter*>(v.emitter)->eval_direction(v.sp.ng);
  if (v.emitter->kind() == scene::EmitterKind::directional)
    return static_cast<const scene::DirectionalEmitter*>(v.emitter)->irradiance();
  if (v.emitter->kind() == scene::EmitterKind::spot) return static_cast<const scene::SpotEmitter*>(v.emitter)->intensity(w);
  if (v.emitter->kind() != scene::EmitterKind::area) return v.emitter->power() * kInv4Pi;  // intensity
  const float c = v.sp.ng.dot(w);
  if (!(c > 0.0f)) return Rgb::Zero();
  return v.emitter->eval(v.sp, w) * c;
}

}  // namespace dp::pathspace
