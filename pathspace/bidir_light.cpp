#include "pathspace/bidir_light.h"

#include "core/error.h"
#include "core/warp.h"
#include "scene/shape.h"

namespace dp::pathspace {

namespace {
const char* kind_name(scene::EmitterKind k) {
  switch (k) {
    case scene::EmitterKind::area: return "area";
    case scene::EmitterKind::point: return "point";
    case scene::EmitterKind::spot: return "spot";
    case scene::EmitterKind::directional: return "directional";
    case scene::EmitterKind::environment: return "environment";
  }
  return "unknown";
}
}  // namespace

void check_bidir_emitters(const scene::Scene& scene, const std::string& integrator) {
  for (const auto& e : scene.emitters()) {
    const scene::EmitterKind k = e->kind();
    if (k == scene::EmitterKind::area || k == scene::EmitterKind::point || k == scene::EmitterKind::spot) continue;
    throw ValueError("integrator '" + integrator + "' does not support " + kind_name(k) +
                     " emitters yet (only area, point and spot lights can start light subpaths)");
  }
}

float light_pdf_pos(const scene::Scene& scene, const BidirVertex& v) {
  const scene::Emitter* e = v.emitter;
  if (!e) return 0.0f;
  const float pmf = scene.emitter_pmf(e);
  if (e->kind() != scene::EmitterKind::area) return pmf;  // delta position: discrete
  const float area = static_cast<const scene::AreaEmitter*>(e)->shape()->area();
  return area > 0.0f ? pmf / area : 0.0f;
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
  if (v.emitter->kind() == scene::EmitterKind::spot) return static_cast<const scene::SpotEmitter*>(v.emitter)->intensity(w);
  if (v.emitter->kind() != scene::EmitterKind::area) return v.emitter->power() * kInv4Pi;  // intensity
  const float c = v.sp.ng.dot(w);
  if (!(c > 0.0f)) return Rgb::Zero();
  return v.emitter->eval(v.sp, w) * c;
}

}  // namespace dp::pathspace
