#include "integrators/path/path_tracer.h"

#include "pathspace/scatter.h"

namespace dp::integrators {

using scene::BsdfContext;
using scene::SurfaceHit;

using pathspace::consistent_side;

Rgb PathTracer::next_event(const SurfaceHit& hit, const Vec3& wi_local, const BsdfContext& ctx, core::Rng& rng,
                           PathCounters& counters) const {
  const float u_light = rng.uniform();
  const Vec2 u = rng.uniform2();
  float pmf;
  const scene::Emitter* emitter = m_scene.sample_emitter(u_light, pmf);
  if (!emitter) return Rgb::Zero();
  const scene::DirectSample ds = emitter->sample_direct(hit.p, u);
  if (!(ds.pdf > 0.0f) || is_black(ds.radiance)) return Rgb::Zero();
  const Vec3 wo_local = hit.shading.to_local(ds.wi);
  if (!consistent_side(hit, ds.wi, wo_local.z())) return Rgb::Zero();
  float bsdf_pdf;  // pdf of sampling wo by the BSDF, for the MIS weight
  // |cos theta_o| of the light direction at the shading point (dropped only by the tests'
  // negative control PathFault::nee_without_cosine).
  const float cos_o = m_settings.fault == PathFault::nee_without_cosine ? 1.0f : abs_cos_theta(wo_local);
  const Rgb f = hit.bsdf->eval_pdf(ctx, wi_local, wo_local, bsdf_pdf) * cos_o;
  if (is_black(f)) return Rgb::Zero();
  ++counters.shadow_rays;
  const bool blocked = std::isfinite(ds.dist) ? m_scene.occluded(m_scene.spawn_segment(hit, ds.p))
                                              : m_scene.occluded(m_scene.spawn_ray(hit, ds.wi));
  if (blocked) return Rgb::Zero();
  const float light_pdf = pmf * ds.pdf;
  const float weight = ds.delta ? 1.0f : power_heuristic(light_pdf, bsdf_pdf);
  return f * ds.radiance * (weight / light_pdf);
}

Rgb PathTracer::radiance(const Ray& primary, core::Rng& rng, PathCounters& counters) const {
  Rgb L = Rgb::Zero(), beta = Rgb::Ones();
  Ray ray = primary;
  bool prev_delta = true;  // the camera is a "delta" for MIS: directly seen lights count fully
  float prev_bsdf_pdf = 0.0f;
  Vec3 prev_p = primary.o;
  const scene::EnvironmentEmitter* env = m_scene.environment();
  scene::SurfaceHit hit_storage;  // filled in place by every intersection (no optional copy)
  const scene::SurfaceHit* const hit = &hit_storage;
  for (int depth = 1; depth <= m_max_depth; ++depth) {
    // Later segments continue from the vertex by the one rule of every integrator and
    // shift (Scene::trace_from; `ray.d` is the sampled direction).
    const bool found = depth == 1 ? m_scene.intersect(ray, hit_storage) : m_scene.trace_from(hit_storage, ray.d, hit_storage);
    ++counters.rays;
    const bool hide = depth == 1 && m_settings.hide_emitters;
    if (!found) {
      if (env && !hide) {
        const Rgb Le = env->eval_direction(ray.d);
        float w = 1.0f;
        if (!prev_delta && m_settings.nee)
          w = power_heuristic(prev_bsdf_pdf, m_scene.emitter_pmf(env) * env->pdf_direct(prev_p, {}, {}, ray.d));
        L += beta * Le * w;
      }
      break;
    }
    if (hit->emitter && !hide) {
      const Rgb Le = hit->emitter->eval(*hit, -ray.d);
      if (!is_black(Le)) {
        float w = 1.0f;
        if (!prev_delta && m_settings.nee) {
          const float light_pdf = m_scene.emitter_pmf(hit->emitter) * hit->emitter->pdf_direct(prev_p, hit->p, hit->ng, ray.d);
          w = power_heuristic(prev_bsdf_pdf, light_pdf);
        }
        L += beta * Le * w;
      }
    }
    if (depth == m_max_depth || !hit->bsdf) break;
    const Vec3 wi_local = hit->shading.to_local(-ray.d);
    if (!consistent_side(*hit, -ray.d, wi_local.z())) break;
    const BsdfContext ctx{hit->uv, scene::TransportMode::radiance};
    if (m_settings.nee && !hit->bsdf->is_purely_delta()) L += beta * next_event(*hit, wi_local, ctx, rng, counters);

    const float u_lobe = rng.uniform();
    const Vec2 u = rng.uniform2();
    const auto bs = hit->bsdf->sample(ctx, wi_local, u_lobe, u);
    if (!bs || is_black(bs->weight)) break;
    const Vec3 wo = hit->shading.to_world(bs->wo);
    if (!consistent_side(*hit, wo, bs->wo.z())) break;
    beta *= bs->weight;
    prev_delta = bs->is_delta();
    prev_bsdf_pdf = bs->pdf;
    prev_p = hit->p;
    if (depth >= m_settings.rr_depth) {
      const float q = std::min(0.95f, max_component(beta));
      if (!(rng.uniform() < q)) {
        ++counters.rr_terminated;
        break;
      }
      beta /= q;
    }
    ray.d = wo;
  }
  return L;
}

}  // namespace dp::integrators
