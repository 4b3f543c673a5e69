#include "pathspace/path_builder.h"

#include <cmath>

#include "pathspace/scatter.h"

namespace dp::pathspace {

void PathBuilder::build(int px, int py, SampleStream& stream, Path& path) const {
  const Vec2 u = stream.next2();
  build_from_raster(Vec2(float(px) + u.x(), float(py) + u.y()), stream, path);
}

void PathBuilder::sample_light(Vertex& v, LightSample& ls, float u_light, const Vec2& u) const {
  float pmf = 0;
  const scene::Emitter* emitter = m_scene.sample_emitter(u_light, pmf);
  ls = LightSample();
  ls.u = u;
  if (!emitter) return;
  const scene::DirectSample ds = emitter->sample_direct(v.hit.p, u);
  ls.valid = true;
  ls.emitter = emitter;
  ls.p = ds.p;
  ls.n = ds.n;
  ls.w = ds.wi;
  ls.dist = ds.dist;
  ls.delta = ds.delta;
  ls.infinite = emitter->is_infinite();
  ls.radiance = ds.radiance;
  ls.pdf = double(pmf) * double(ds.pdf);
  ls.connectable = is_connectable(m_scene, emitter, m_opt.shift_threshold);
  ls.wo = v.hit.shading.to_local(ds.wi);
  if (!(ds.pdf > 0.0f) || !consistent_side(v.hit, ds.wi, ls.wo.z())) {
    ls.pdf = 0;  // the sample failed: nothing to evaluate (contributes 0)
    return;
  }
  const auto ctx = radiance_context(v.hit);
  float p = 0.0f;
  ls.f_cos = v.hit.bsdf->eval_pdf(ctx, v.wi, ls.wo, p) * abs_cos_theta(ls.wo);
  ls.bsdf_pdf = ds.delta ? 0.0 : double(p);
  // Visibility matters for the MIS weight of shifted paths (the BSDF strategy cannot
  // produce an occluded light point) even when this sample's value is zero.
  if ((is_black(ls.f_cos) || is_black(ls.radiance)) && !(ls.bsdf_pdf > 0.0)) return;
  ls.visible = std::isfinite(ds.dist) ? !m_scene.occluded(m_scene.spawn_segment(v.hit, ds.p))
                                      : !m_scene.occluded(m_scene.spawn_ray(v.hit, ds.wi));
}

void PathBuilder::build_from_raster(const Vec2& raster, SampleStream& stream, Path& path) const {
  path.clear();
  path.raster = raster;
  const auto& cam = m_scene.camera();
  Vertex& cv = path.append(Vertex());
  cv.kind = VertexKind::camera;
  cv.hit.p = cam.position();
  cv.hit.ng = cam.forward();
  cv.hit.shading = Frame::from_normal(cam.forward());
  Ray ray = cam.generate_ray(raster);
  int from = -1;  // index of the vertex the current ray leaves (-1: the camera)
  cv.wo_world = ray.d;
  cv.pdf = 1;  // W_e / p of the raster sample cancel (box filter): unit ratio
  cv.lobe = scene::kDiffuseReflection;  // marks "continued"
  cv.connectable = false;
  Rgb beta = Rgb::Ones();
  for (int depth = 1; depth <= m_opt.max_depth; ++depth) {
    const auto hit = from >= 0 ? m_scene.trace_from(path[from].hit, ray.d) : m_scene.intersect(ray);
    if (!hit) {
      Vertex& ev = path.append(Vertex());
      ev.kind = VertexKind::environment;
      ev.wo_world = ray.d;
      ev.hit.p = ray.o;
      ev.connectable = true;
      ev.emission = emitted(m_scene, ev, -ray.d);
      break;
    }
    Vertex& v = path.append(Vertex());
    const int k = path.size() - 1;
    v.kind = VertexKind::surface;
    v.hit = *hit;
    v.connectable = is_connectable(hit->bsdf, m_opt.shift_threshold);
    v.emission = emitted(m_scene, v, -ray.d);
    if (depth == m_opt.max_depth || !hit->bsdf) break;
    v.wi = hit->shading.to_local(-ray.d);
    if (!consistent_side(*hit, -ray.d, v.wi.z())) break;
    const float u_light = stream.next();
    const Vec2 u_nee = stream.next2();
    if (m_opt.nee && !hit->bsdf->is_purely_delta()) sample_light(v, path.nee[size_t(k)], u_light, u_nee);
    const float u_lobe = stream.next();
    const Vec2 u_bsdf = stream.next2();
    const float u_rr = stream.next();
    const auto bs = hit->bsdf->sample(radiance_context(*hit), v.wi, u_lobe, u_bsdf);
    if (!bs || is_black(bs->weight)) break;
    const Vec3 wo = hit->shading.to_world(bs->wo);
    if (!consistent_side(*hit, wo, bs->wo.z())) break;
    beta *= bs->weight;
    float q = 1.0f;
    if (depth >= m_opt.rr_depth) {
      q = std::min(0.95f, max_component(beta));
      if (!(u_rr < q)) break;  // terminated: the vertex did not continue
      beta /= q;
    }
    v.lobe = bs->lobe;
    v.u_lobe = u_lobe;
    v.eta = bs->eta;
    v.wo = bs->wo;
    v.wo_world = wo;
    v.pdf = double(bs->pdf);
    v.f_cos = bs->weight * bs->pdf;
    v.rr = q;
    ray = m_scene.continue_ray(*hit, wo);
    from = k;
  }
}

}  // namespace dp::pathspace
