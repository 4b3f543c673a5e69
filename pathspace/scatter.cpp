#include "pathspace/scatter.h"

#include <cmath>

#include "pathspace/classify.h"
#include "scene/shapes/shape.h"

namespace dp::pathspace {

std::optional<scene::BsdfSample> sample_dirac_lobe(const scene::Bsdf& bsdf, const scene::BsdfContext& ctx,
                                                   const Vec3& wi, uint32_t lobe, float u_lobe) {
  const float tries[3] = {u_lobe, 0.0f, 1.0f - 0x1p-24f};
  for (float u : tries) {
    auto s = bsdf.sample(ctx, wi, u, Vec2(0.5f, 0.5f));
    if (s && s->lobe == lobe) return s;
  }
  return std::nullopt;
}

double light_pdf(const scene::Scene& scene, const Vec3& from, const Vertex& light) {
  if (light.kind == VertexKind::environment) {
    const scene::EnvironmentEmitter* env = scene.environment();
    if (!env) return 0.0;
    return double(scene.emitter_pmf(env)) * double(env->pdf_direct(from, {}, {}, light.wo_world));
  }
  if (!light.hit.emitter) return 0.0;
  const Vec3 d = light.hit.p - from;
  const float len = d.norm();
  return double(scene.emitter_pmf(light.hit.emitter)) *
         double(light.hit.emitter->pdf_direct(from, light.hit.p, light.hit.ng, d / len));
}

Rgb emitted(const scene::Scene& scene, const Vertex& v, const Vec3& w_world) {
  if (v.kind == VertexKind::environment) {
    const scene::EnvironmentEmitter* env = scene.environment();
    return env ? env->eval_direction(-w_world) : Rgb::Zero();
  }
  if (v.kind != VertexKind::surface || !v.hit.emitter) return Rgb::Zero();
  return v.hit.emitter->eval(v.hit, w_world);
}

bool is_connectable(const scene::Scene& scene, const scene::Emitter* emitter, float threshold) {
  if (!emitter || emitter->kind() != scene::EmitterKind::area) return true;
  const auto* shape = static_cast<const scene::AreaEmitter*>(emitter)->shape();
  if (!shape || shape->material < 0) return true;
  return is_connectable(scene.bsdfs()[size_t(shape->material)].get(), threshold);
}

}  // namespace dp::pathspace
