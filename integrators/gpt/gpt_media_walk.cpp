#include "integrators/gpt/gpt_media_walk.h"

#include <algorithm>
#include <cmath>

#include "pathspace/bidir_media.h"  // kMaxEdgeCrossings
#include "pathspace/classify.h"
#include "pathspace/scatter.h"
#include "scene/media/free_flight.h"
#include "scene/media/medium_interface.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

using pathspace::consistent_side;

bool media_scatter_eval(const scene::Scene& scene, const MediaVertex& v, const Vec3& d_in, const Vec3& wo, Rgb& f,
                        float& pdf) {
  f = Rgb::Zero();
  pdf = 0.0f;
  if (v.medium) {
    // The medium vertex's rho_p (Gruson et al. 2018, Eq. 3; sigma_s is in the edge weight).
    const float p = scene::HenyeyGreenstein(scene.media()[size_t(v.medium_index)].phase).eval(d_in, wo);
    f = Rgb::Constant(p);
    pdf = p;
    return true;
  }
  const scene::SurfaceHit& h = v.hit;
  if (!h.bsdf) return false;
  const Vec3 wi = h.shading.to_local(-d_in), wl = h.shading.to_local(wo);
  if (!consistent_side(h, -d_in, wi.z()) || !consistent_side(h, wo, wl.z())) return false;
  f = h.bsdf->eval_pdf(pathspace::radiance_context(h), wi, wl, pdf) * abs_cos_theta(wl);
  return true;
}

int media_medium_toward(const scene::Scene& scene, const MediaVertex& v, const Vec3& w) {
  if (v.medium) return v.medium_index;
  return scene::medium_toward(v.hit, w, v.medium_index, scene.camera_medium());
}

void media_eval_light(const scene::Scene& scene, const MediaVertex& v, const Vec3& d_in, MediaLightSample& ls) {
  float spdf = 0.0f;
  Rgb f;
  const bool ok = media_scatter_eval(scene, v, d_in, ls.w, f, spdf);
  ls.f = f;
  ls.scatter_pdf = ls.delta ? 0.0 : double(spdf);
  ls.edge = MediaEdge();
  // No light can arrive (wrong side, zero BSDF): the shadow edge is not traced, and the
  // path counts as blocked for both strategies (the same rule for base and offset).
  if (!ok || is_black(f)) {
    ls.edge.blocked = true;
    return;
  }
  const float len = ls.infinite ? kInfinity : ls.dist;
  ls.edge = trace_media_edge(scene, media_edge_start(v), ls.w, len, media_medium_toward(scene, v, ls.w), false);
}

namespace {

// NEE at vertex v: one light sample (as volpath's next_event_*), recorded.
void gpt_media_sample_light(const scene::Scene& scene, MediaVertex& v, pathspace::SampleStream& stream) {
  MediaLightSample& ls = v.nee;
  const float u_light = stream.next();
  const Vec2 u = stream.next2();
  float pmf = 0.0f;
  const scene::Emitter* emitter = scene.sample_emitter(u_light, pmf);
  if (!emitter) return;
  const scene::DirectSample ds = emitter->sample_direct(v.p, u);
  if (!(ds.pdf > 0.0f) || is_black(ds.radiance)) return;
  ls.valid = true;
  ls.emitter = emitter;
  ls.u = u;
  ls.p = ds.p;
  ls.n = ds.n;
  ls.w = ds.wi;
  ls.dist = ds.dist;
  ls.delta = ds.delta;
  ls.infinite = !std::isfinite(ds.dist);
  ls.radiance = ds.radiance;
  ls.pdf = double(pmf) * double(ds.pdf);
  media_eval_light(scene, v, v.d_in, ls);
}

// Russian roulette after rr_depth segments (as volpath): survival min(0.95, max beta).
bool gpt_media_survive(Rgb& beta, int depth, int rr_depth, pathspace::SampleStream& stream, float& rr,
                       GptMediaWalkCounters& c) {
  rr = 1.0f;
  if (depth < rr_depth) return true;
  const float q = std::min(0.95f, max_component(beta));
  if (!(stream.next() < q)) {
    ++c.rr_terminated;
    return false;
  }
  rr = q;
  beta /= q;
  return true;
}

}  // namespace

void build_media_path(const scene::Scene& scene, const MediaWalkOptions& opt, int px, int py,
                      pathspace::SampleStream& stream, MediaPath& path, GptMediaWalkCounters& c) {
  path.v.clear();
  const Vec2 u = stream.next2();
  path.raster = Vec2(float(px) + u.x(), float(py) + u.y());
  Ray ray = scene.camera().generate_ray(path.raster);
  path.primary = ray;
  MediaVertex cam;
  cam.p = ray.o;
  cam.medium_index = scene.camera_medium();
  cam.continued = true;
  cam.wo = ray.d;
  path.v.push_back(cam);
  Rgb beta = Rgb::Ones(), edge_w = Rgb::Ones();
  double ff = 1.0;
  int medium = scene.camera_medium(), nulls = 0;
  const scene::EnvironmentEmitter* env = scene.environment();
  scene::SurfaceHit hit;
  bool from_surface = false;
  for (int depth = 1; depth <= opt.max_depth;) {
    const bool found = from_surface ? scene.trace_from(hit, ray.d, hit) : scene.intersect(ray, hit);
    if (medium >= 0) {
      const scene::HomogeneousMedium& med = scene.media()[size_t(medium)];
      const float u_channel = stream.next(), u_distance = stream.next();
      const scene::FreeFlightSample fs =
          scene::sample_free_flight(med, found ? hit.t : kInfinity, u_channel, u_distance);
      beta *= fs.weight;
      edge_w *= fs.weight;
      ff *= double(fs.pdf);
      if (fs.scattered) {
        ++c.medium_vertices;
        MediaVertex& v = path.v.emplace_back();
        v.medium = true;
        v.medium_index = medium;
        v.p = ray.at(fs.t);
        v.d_in = ray.d;
        v.beta = beta;
        v.ff_in = ff;
        v.edge_w = edge_w;
        v.connectable = true;  // a smooth phase function
        edge_w = Rgb::Ones();
        ff = 1.0;
        if (depth == opt.max_depth || is_black(beta)) break;
        if (opt.nee) gpt_media_sample_light(scene, v, stream);
        const scene::HenyeyGreenstein phase(med.phase);
        const Vec3 wo = phase.sample(ray.d, stream.next2());
        v.continued = true;
        v.wo = wo;
        v.pdf = double(phase.pdf(ray.d, wo));
        v.f = Rgb::Constant(float(v.pdf));
        v.weight = Rgb::Ones();  // phase sampling is exact
        if (!gpt_media_survive(beta, depth, opt.rr_depth, stream, v.rr, c)) {
          v.continued = false;
          break;
        }
        ray.o = v.p;
        ray.d = wo;
        ray.tmin = 0.0f;
        ray.tmax = kInfinity;
        from_surface = false;
        ++depth;
        continue;
      }
      if (is_black(beta)) break;
    }
    if (!found) {
      if (env) {
        MediaVertex& v = path.v.emplace_back();
        v.escaped = true;
        v.medium_index = medium;
        v.p = ray.d;  // a direction
        v.d_in = ray.d;
        v.beta = beta;
        v.ff_in = ff;
        v.edge_w = edge_w;
        v.emission = env->eval_direction(ray.d);
        v.connectable = true;
      }
      break;
    }
    if (scene::is_index_matched(hit)) {  // not a vertex: switch media, keep direction and depth
      ++c.null_crossings;
      if (++nulls > pathspace::kMaxEdgeCrossings) {
        ++c.null_limit;
        break;
      }
      medium = scene::medium_toward(hit, ray.d, medium, scene.camera_medium());
      ray = scene.continue_ray(hit, ray.d);
      from_surface = true;
      continue;
    }
    MediaVertex& v = path.v.emplace_back();
    v.hit = hit;
    v.p = hit.p;
    v.d_in = ray.d;
    v.medium_index = medium;
    v.beta = beta;
    v.ff_in = ff;
    v.edge_w = edge_w;
    if (hit.emitter) v.emission = hit.emitter->eval(hit, -ray.d);
    v.connectable = pathspace::is_connectable(hit.bsdf, opt.shift_threshold);  // a pure emitter ends the path
    edge_w = Rgb::Ones();
    ff = 1.0;
    if (depth == opt.max_depth || !hit.bsdf) break;
    const Vec3 wi_local = hit.shading.to_local(-ray.d);
    if (!consistent_side(hit, -ray.d, wi_local.z())) break;
    ++c.surface_vertices;
    if (opt.nee && !hit.bsdf->is_purely_delta()) gpt_media_sample_light(scene, v, stream);
    const scene::BsdfContext ctx = pathspace::radiance_context(hit);
    const float u_lobe = stream.next();
    const Vec2 ub = stream.next2();
    const auto bs = hit.bsdf->sample(ctx, wi_local, u_lobe, ub);
    if (!bs || is_black(bs->weight)) break;
    const Vec3 wo = hit.shading.to_world(bs->wo);
    if (!consistent_side(hit, wo, bs->wo.z())) break;
    beta *= bs->weight;
    v.continued = true;
    v.wo = wo;
    v.weight = bs->weight;
    v.pdf = double(bs->pdf);
    v.delta_lobe = bs->is_delta();
    v.f = bs->weight * bs->pdf;
    medium = scene::medium_toward(hit, wo, medium, scene.camera_medium());
    if (!gpt_media_survive(beta, depth, opt.rr_depth, stream, v.rr, c)) {
      v.continued = false;
      break;
    }
    ray = scene.continue_ray(hit, wo);
    from_surface = true;
    ++depth;
  }
}

}  // namespace dp::integrators
