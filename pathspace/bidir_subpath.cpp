#include "pathspace/bidir_subpath.h"

#include <limits>

#include "core/warp.h"
#include "pathspace/bidir_light.h"
#include "pathspace/bidir_media.h"
#include "pathspace/scatter.h"
#include "scene/media/free_flight.h"
#include "scene/media/grid_tracking.h"
#include "scene/media/medium_interface.h"
#include "scene/media/phase_function.h"
#include "scene/shapes/shape.h"

namespace dp::pathspace {

namespace {

scene::TransportMode other(scene::TransportMode m) {
  return m == scene::TransportMode::radiance ? scene::TransportMode::importance : scene::TransportMode::radiance;
}

// Area density (direction density if `to` is at infinity) with which the walk leaves
// `from` (pinhole, light, scattering surface) and arrives at `to`.
float leave_pdf(const scene::Scene& scene, const BidirVertex& from, const BidirVertex& to, scene::TransportMode mode) {
  if (from.kind == BidirKind::light) return light_pdf_next(scene, from, to);
  const Vec3 w = -to.wi;
  const float pdf =
      from.kind == BidirKind::camera ? scene.camera().pdf_direction(w) : scatter_pdf(scene, from, from.wi, w, mode);
  return solid_angle_to_area(pdf, from, to);
}

// Sets the forward density of the new vertex path[n] = v and the reverse density of
// path[n - 2] (the other walk arriving at path[n - 1] from v). A Dirac lobe at
// path[n - 1] leaves both 0.
void set_densities(const scene::Scene& scene, BidirVertex* path, size_t n, BidirVertex& v,
                   scene::TransportMode mode) {
  const BidirVertex& prev = path[n - 1];
  if (prev.delta) return;
  // The free-flight factors of the edges (1 without media; bidir_media.h).
  v.pdf_fwd = leave_pdf(scene, prev, v, mode) * v.ff_fwd;
  if (n >= 2 && (prev.kind == BidirKind::surface || prev.kind == BidirKind::medium))
    path[n - 2].pdf_rev =
        solid_angle_to_area(scatter_pdf(scene, prev, -v.wi, prev.wi, other(mode)), prev, path[n - 2]) * prev.ff_rev;
}

// The camera walk escaped along `d`: the environment as a light vertex at infinity.
// ff: the free-flight factors of the escaping edge (bidir_media.h).
void add_environment_vertex(const scene::Scene& scene, const Vec3& d, const Rgb& beta, std::vector<BidirVertex>& path,
                            const FlightChain& ff) {
  BidirVertex v;
  v.kind = BidirKind::light;
  v.ff_fwd = ff.to_b;
  v.ff_rev = ff.to_a;
  v.emitter = scene.environment();
  v.sp.ng = d;
  v.sp.p = path.back().sp.p + d * (4.0f * infinite_disk_radius(scene));
  v.wi = -d;
  v.beta = beta;
  set_densities(scene, path.data(), path.size(), v, scene::TransportMode::radiance);
  path.push_back(v);
}

}  // namespace

bool next_hit(const scene::Scene& scene, const scene::SurfaceHit& from, const Vec3& w, scene::SurfaceHit& out) {
  const auto h = scene.trace_from(from, w);
  if (h) out = *h;
  return h.has_value();
}

Ray anchored_ray(const scene::Scene& scene, const Vec3& p, const Vec3& w) {
  scene::SurfaceHit at;
  at.p = p;
  return scene.continue_ray(at, w);
}

namespace {

// v.wi: the unit direction from v toward prev (exactly toward a light at infinity);
// false if they coincide.
bool point_back(const BidirVertex& prev, BidirVertex& v) {
  if (prev.infinite()) {
    v.wi = prev.sp.ng;
    return true;
  }
  const Vec3 d = prev.sp.p - v.sp.p;
  const float len = d.norm();
  if (!(len > 0.0f)) return false;
  v.wi = d / len;
  return true;
}

// Ends the edge into v with its last sub-segment (medium, len): v's free-flight factors
// (bidir_media.h), and a fresh chain for the next edge.
void close_edge(const scene::Scene& scene, FlightChain& chain, int medium, float len, const Span& span,
                bool prev_medium, BidirVertex& v) {
  chain.finish(scene, medium, len, span, prev_medium, v.kind == BidirKind::medium);
  v.ff_fwd = chain.to_b;
  v.ff_rev = chain.to_a;
  chain = FlightChain{};
}

// Continues `path` (holding its start vertex) along `ray`; `beta` is the throughput
// carried by the ray. Densities from vertex positions (bidir_vertex.h).
// `from`: the surface vertex the ray leaves (anchored at it), or null for a ray from an
// endpoint. In scenes with media each segment in a medium samples a free flight
// (scene/media/free_flight.h; a grid medium: delta tracking, grid_tracking.h) exactly as
// volpath: a scatter makes a medium vertex (its direction from the phase function, weight
// 1), a pass multiplies beta by Tr / P(pass) (grid: 1); index-matched boundaries switch
// the medium and are not vertices (bidir_media.h). The end factors of each sub-segment
// come from its endpoints (seg_start: the previous vertex or boundary crossing).
void random_walk(const scene::Scene& scene, Ray ray, Rgb beta, scene::TransportMode mode,
                 const SubpathParams& params, core::Rng& rng, std::vector<BidirVertex>& path,
                 const scene::SurfaceHit* from = nullptr) {
  constexpr int kUnknown = -2;
  const bool media = scene.caps().has_media;
  const int cam_medium = scene.camera_medium();
  scene::SurfaceHit hit;
  bool from_surface = from != nullptr;  // the ray leaves the surface vertex `hit` (anchored at it)
  if (from) hit = *from;
  // The medium of the ray; a light's is that of the near side of the first surface the
  // emitted ray meets if it is a boundary, else the camera's (as the photon tracers).
  int medium = !media ? -1 : path.back().kind == BidirKind::light ? kUnknown : medium_toward(scene, path.back(), ray.d);
  FlightChain chain;
  int crossings = 0;
  Vec3 seg_start = path.back().sp.p;
  while (int(path.size()) < params.max_vertices) {
    const bool found = from_surface ? next_hit(scene, hit, ray.d, hit) : scene.intersect(ray, hit);
    if (medium == kUnknown) {
      medium = found ? scene::medium_toward(hit, -ray.d, cam_medium, cam_medium) : cam_medium;
      path.back().medium = int16_t(medium);
      if (medium >= 0 && path.back().infinite()) break;  // Tr(inf) = 0 (bidir_media.h)
    }
    const BidirVertex& prev = path.back();
    const bool prev_medium = prev.kind == BidirKind::medium;
    if (medium >= 0) {
      const scene::HomogeneousMedium& med = scene.media()[size_t(medium)];
      scene::FreeFlightSample ff;
      if (med.heterogeneous()) {
        if (params.grid) ++params.grid->flights;
        ff = scene::sample_free_flight_grid(med, ray.o, ray.d, found ? hit.t : kInfinity, rng);
      } else {
        const float u_channel = rng.uniform(), u_distance = rng.uniform();
        ff = scene::sample_free_flight(med, found ? hit.t : kInfinity, u_channel, u_distance);
      }
      beta *= ff.weight;
      if (is_black(beta)) break;
      if (ff.scattered) {
        BidirVertex v;
        v.kind = BidirKind::medium;
        v.sp.p = ray.at(ff.t);
        v.sp.ng = Vec3::Zero();
        v.medium = int16_t(medium);
        if (!point_back(prev, v)) break;
        close_edge(scene, chain, medium, ff.t, Span::between(seg_start, v.sp.p), prev_medium, v);
        v.beta = beta;
        set_densities(scene, path.data(), path.size(), v, mode);
        path.push_back(v);
        if (int(path.size()) >= params.max_vertices) break;
        BidirVertex& cur = path.back();
        // Phase sampling is exact (weight 1); sigma_s is in the free flight's weight.
        const scene::HenyeyGreenstein phase(med.phase);
        const Vec3 wo = phase.sample(-cur.wi, rng.uniform2());
        cur.pdf_out = phase.pdf(-cur.wi, wo);
        if (params.stop_after_smooth) break;
        float q = 1.0f;
        if (int(path.size()) - 1 >= params.rr_depth) {
          q = std::min(0.95f, max_component(beta));
          if (!(rng.uniform() < q)) break;
          beta /= q;
        }
        cur.rr_out = q;
        cur.weight_out = Rgb::Constant(1.0f / q);
        ray.o = cur.sp.p;
        seg_start = cur.sp.p;
        ray.d = wo;
        ray.tmin = 0.0f;
        ray.tmax = kInfinity;
        from_surface = false;
        continue;
      }
    }
    if (!found) {
      if (mode == scene::TransportMode::radiance && scene.environment()) {
        chain.finish(scene, medium, kInfinity, Span::ray(seg_start, ray.d), prev_medium, false);
        add_environment_vertex(scene, ray.d, beta, path, chain);
      }
      break;
    }
    if (media && scene::is_index_matched(hit)) {  // not a vertex: switch media, keep the direction
      if (++crossings > kMaxEdgeCrossings) break;
      chain.pass(scene, medium, hit.t, Span::between(seg_start, hit.p));
      seg_start = hit.p;
      medium = scene::medium_toward(hit, ray.d, medium, cam_medium);
      ray = scene.continue_ray(hit, ray.d);
      from_surface = true;
      continue;
    }
    BidirVertex v = surface_vertex_at(hit);
    if (!point_back(prev, v)) break;
    if (media) {
      v.medium = int16_t(medium);
      close_edge(scene, chain, medium, hit.t, Span::between(seg_start, hit.p), prev_medium, v);
    }
    v.beta = beta;
    set_densities(scene, path.data(), path.size(), v, mode);
    path.push_back(v);
    if (int(path.size()) >= params.max_vertices || !hit.bsdf) break;
    BidirVertex& cur = path.back();
    const Vec3 wi_local = hit.shading.to_local(cur.wi);
    if (!(hit.ng.dot(cur.wi) * wi_local.z() > 0.0f)) break;  // sidedness (as the path tracer)
    const scene::BsdfContext ctx{hit.uv, mode};
    const float u_lobe = rng.uniform();
    const Vec2 u = rng.uniform2();
    const auto bs = hit.bsdf->sample(ctx, wi_local, u_lobe, u);
    if (!bs || is_black(bs->weight)) break;
    const Vec3 wo = hit.shading.to_world(bs->wo);
    if (!(hit.ng.dot(wo) * bs->wo.z() > 0.0f)) break;
    cur.delta = bs->is_delta();
    cur.lobe = bs->lobe;
    cur.u_lobe = u_lobe;
    cur.pdf_out = bs->pdf;
    if (params.stop_after_smooth && !cur.delta) break;
    beta *= bs->weight;
    float q = 1.0f;
    if (int(path.size()) - 1 >= params.rr_depth) {  // segments so far
      q = std::min(0.95f, max_component(beta));
      if (!(rng.uniform() < q)) break;
      beta /= q;
    }
    cur.rr_out = q;
    cur.weight_out = bs->weight / q;
    if (media) medium = scene::medium_toward(hit, wo, medium, cam_medium);
    ray = scene.continue_ray(hit, wo);  // ray.o: the origin of a medium vertex's distance
    seg_start = hit.p;
    from_surface = true;
  }
}

}  // namespace

namespace {
// wi, pdf_fwd of path[n] and pdf_rev of path[n - 2], from the positions.
void derive(const scene::Scene& scene, std::vector<BidirVertex>& path, size_t n, scene::TransportMode mode) {
  BidirVertex& v = path[n];
  const BidirVertex& prev = path[n - 1];
  if (prev.infinite()) v.wi = prev.sp.ng;
  else if (v.infinite()) v.wi = -v.sp.ng;
  else v.wi = (prev.sp.p - v.sp.p).normalized();
  v.pdf_fwd = v.pdf_rev = 0.0f;
  if (scene.caps().has_media) {  // the edge's free-flight factors, re-traced (bidir_media.h)
    const bool reversed = prev.infinite();
    const EdgeMedia e = reversed ? trace_edge(scene, v, prev) : trace_edge(scene, prev, v);
    v.ff_fwd = reversed ? e.to_a : e.to_b;
    v.ff_rev = reversed ? e.to_b : e.to_a;
    if (v.kind != BidirKind::medium && !reversed) v.medium = int16_t(e.b_medium);
  }
  set_densities(scene, path.data(), n, v, mode);
}
}  // namespace

void append_vertex(const scene::Scene& scene, std::vector<BidirVertex>& path, const BidirVertex& v,
                   scene::TransportMode mode) {
  path.push_back(v);
  derive(scene, path, path.size() - 1, mode);
}

void recompute_densities(const scene::Scene& scene, std::vector<BidirVertex>& path, scene::TransportMode mode) {
  if (path.empty()) return;
  BidirVertex& first = path[0];
  first.pdf_fwd = first.kind == BidirKind::camera ? 1.0f : light_pdf_pos(scene, first);
  first.pdf_rev = 0.0f;
  for (size_t n = 1; n < path.size(); ++n) derive(scene, path, n, mode);
}

void camera_subpath(const scene::Scene& scene, const Vec2& raster, const SubpathParams& params, core::Rng& rng,
                    std::vector<BidirVertex>& out) {
  out.clear();
  const scene::PerspectiveCamera& cam = scene.camera();
  BidirVertex z0;
  z0.kind = BidirKind::camera;
  z0.sp.p = cam.position();
  z0.sp.ng = cam.forward();
  z0.pdf_fwd = 1.0f;  // the pinhole position is fixed
  out.push_back(z0);
  if (params.max_vertices < 2) return;
  const Ray ray = cam.generate_ray(raster);
  out[0].pdf_out = cam.pdf_direction(ray.d);
  out[0].weight_out = Rgb::Ones();
  // We / p = 1 for a camera ray of its own pixel (bidir_vertex.h); the MIS density is
  // the whole-image direction density.
  random_walk(scene, ray, Rgb::Ones(), scene::TransportMode::radiance, params, rng, out);
}

namespace {

// Emission from a finite light point y0 (area, point, spot) along a direction drawn with
// u_dir: the ray, its solid-angle density.
bool finite_emission(const scene::Scene& scene, const BidirVertex& y0, const Vec2& u_dir, Ray& ray, float& pdf) {
  const scene::Emitter* e = y0.emitter;
  Vec3 w;
  if (e->kind() == scene::EmitterKind::area) {
    w = y0.sp.shading.to_world(core::warp::square_to_cosine_hemisphere(u_dir));
    ray = anchored_ray(scene, y0.sp.p, w);
  } else if (e->kind() == scene::EmitterKind::point || e->kind() == scene::EmitterKind::spot) {
    if (e->kind() == scene::EmitterKind::point) {
      w = core::warp::square_to_uniform_sphere(u_dir);
    } else {
      const auto* spot = static_cast<const scene::SpotEmitter*>(e);
      w = spot->frame().to_world(core::warp::square_to_uniform_cone(u_dir, spot->cos_cutoff()));
    }
    ray.o = y0.sp.p;
    ray.d = w;
    ray.tmin = 0.0f;
    ray.tmax = kInfinity;
  } else {
    return false;
  }
  pdf = light_pdf_dir(y0, w);
  return pdf > 0.0f;
}

// y_0 on the light `e` (u_pos: its position; u_dir: the direction, or for lights at
// infinity the direction toward them) and the ray leaving it with the ray's density.
bool light_endpoint(const scene::Scene& scene, const scene::Emitter* e, const Vec2& u_pos, const Vec2& u_dir,
                    BidirVertex& y0, Ray& ray, float& pdf_ray) {
  y0 = BidirVertex{};
  y0.kind = BidirKind::light;
  y0.emitter = e;
  if (e->kind() == scene::EmitterKind::area) {
    const scene::PositionSample ps = static_cast<const scene::AreaEmitter*>(e)->shape()->sample_area(u_pos);
    y0.sp.p = ps.p;
    y0.sp.ng = ps.n;
    y0.sp.shading = Frame::from_normal(ps.n);
    y0.sp.uv = ps.uv;
  } else if (e->kind() == scene::EmitterKind::point) {
    y0.sp.p = static_cast<const scene::PointEmitter*>(e)->position();
  } else if (e->kind() == scene::EmitterKind::spot) {
    y0.sp.p = static_cast<const scene::SpotEmitter*>(e)->position();
  } else {
    // At infinity (environment, directional): a direction toward the light, then a ray
    // origin on a disk of radius R across it, outside the scene (bidir_light.h).
    const scene::DirectSample ds = e->sample_direct(scene.bounds().center(), u_dir);
    if (!(ds.pdf > 0.0f)) return false;
    const float r = infinite_disk_radius(scene);
    const Vec2 disk = core::warp::square_to_uniform_disk_concentric(u_pos);
    const Frame f = Frame::from_normal(ds.wi);
    y0.sp.ng = ds.wi;
    y0.sp.p = scene.bounds().center() + r * f.to_world(Vec3(disk.x(), disk.y(), 1.0f));
    ray.o = y0.sp.p;
    ray.d = -ds.wi;
    ray.tmin = 0.0f;
    ray.tmax = kInfinity;
    pdf_ray = 1.0f / (kPi * r * r);  // a planar origin
  }
  y0.pdf_fwd = light_pdf_pos(scene, y0);
  if (!(y0.pdf_fwd > 0.0f)) return false;
  y0.beta = Rgb::Constant(1.0f / y0.pdf_fwd);
  return y0.infinite() || finite_emission(scene, y0, u_dir, ray, pdf_ray);
}

// Records the ray leaving the light endpoint path[0] (density pdf_ray) and returns the
// throughput it carries.
Rgb leave_light(std::vector<BidirVertex>& path, const Ray& ray, float pdf_ray) {
  BidirVertex& y0 = path[0];
  const Rgb emit = light_emit_cos(y0, ray.d);
  y0.pdf_out = pdf_ray;
  y0.weight_out = emit / pdf_ray;
  return y0.beta * emit / pdf_ray;
}

}  // namespace

void light_subpath(const scene::Scene& scene, const SubpathParams& params, core::Rng& rng,
                   std::vector<BidirVertex>& out) {
  out.clear();
  const float u_light = rng.uniform();
  const Vec2 u_pos = rng.uniform2(), u_dir = rng.uniform2();
  float pmf = 0.0f;
  const scene::Emitter* e = scene.sample_emitter(u_light, pmf);
  if (!e || params.max_vertices < 1) return;
  BidirVertex y0;
  Ray ray;
  float pdf_ray = 0.0f;
  if (!light_endpoint(scene, e, u_pos, u_dir, y0, ray, pdf_ray)) {
    // Densities of zero (a back-facing or cut-off direction) keep the endpoint, as before.
    if (y0.pdf_fwd > 0.0f && !y0.infinite()) out.push_back(y0);
    return;
  }
  out.push_back(y0);
  if (params.max_vertices < 2) return;
  const Rgb beta = leave_light(out, ray, pdf_ray);
  if (is_black(beta)) {
    out[0].pdf_out = 0.0f;
    out[0].weight_out = Rgb::Zero();
    return;
  }
  random_walk(scene, ray, beta, scene::TransportMode::importance, params, rng, out);
}

bool emit_light_ray(const scene::Scene& scene, core::Rng& rng, Ray& ray, Rgb& beta, BidirVertex* endpoint) {
  const float u_light = rng.uniform();
  const Vec2 u_pos = rng.uniform2(), u_dir = rng.uniform2();
  float pmf = 0.0f;
  const scene::Emitter* e = scene.sample_emitter(u_light, pmf);
  if (!e) return false;
  BidirVertex y0;
  float pdf_ray = 0.0f;
  if (!light_endpoint(scene, e, u_pos, u_dir, y0, ray, pdf_ray)) return false;
  beta = y0.beta * light_emit_cos(y0, ray.d) / pdf_ray;  // as leave_light
  if (endpoint) *endpoint = y0;
  return !is_black(beta) && is_finite(beta);
}

bool extend_subpath(const scene::Scene& scene, std::vector<BidirVertex>& path, int n, scene::TransportMode mode,
                    core::Rng& rng) {
  if (n <= 0) return n == 0;
  const size_t target = path.size() + size_t(n);
  SubpathParams params;
  params.max_vertices = int(target);
  params.rr_depth = std::numeric_limits<int>::max();
  Ray ray;
  Rgb beta = Rgb::Ones();
  const scene::SurfaceHit* from = nullptr;
  scene::SurfaceHit at;
  const bool radiance = mode == scene::TransportMode::radiance;
  if (path.empty() && radiance) {
    const scene::PerspectiveCamera& cam = scene.camera();
    BidirVertex z0;
    z0.kind = BidirKind::camera;
    z0.sp.p = cam.position();
    z0.sp.ng = cam.forward();
    z0.pdf_fwd = 1.0f;
    path.push_back(z0);
    if (path.size() == target) return true;
    // The raster uniform on the whole image (the density camera pdfs use).
    const Vec2 u = rng.uniform2();
    const Vec2 raster(std::min(u.x() * float(cam.width()), std::nextafter(float(cam.width()), 0.0f)),
                      std::min(u.y() * float(cam.height()), std::nextafter(float(cam.height()), 0.0f)));
    ray = cam.generate_ray(raster);
    path[0].pdf_out = cam.pdf_direction(ray.d);
    path[0].weight_out = Rgb::Ones();
  } else if (path.empty()) {
    const float u_light = rng.uniform();
    const Vec2 u_pos = rng.uniform2(), u_dir = rng.uniform2();
    float pmf = 0.0f;
    const scene::Emitter* e = scene.sample_emitter(u_light, pmf);
    BidirVertex y0;
    float pdf_ray = 0.0f;
    if (!e || !light_endpoint(scene, e, u_pos, u_dir, y0, ray, pdf_ray)) return false;
    path.push_back(y0);
    if (path.size() == target) return true;
    beta = leave_light(path, ray, pdf_ray);
  } else if (path.back().kind == BidirKind::light) {
    // A kept finite light point emits anew.
    float pdf_ray = 0.0f;
    if (path.back().infinite() || !finite_emission(scene, path.back(), rng.uniform2(), ray, pdf_ray)) return false;
    beta = leave_light(path, ray, pdf_ray);
  } else {
    BidirVertex& v = path.back();
    if (v.kind != BidirKind::surface || !v.bsdf) return false;
    const Vec3 wi_local = v.sp.shading.to_local(v.wi);
    if (!(v.sp.ng.dot(v.wi) * wi_local.z() > 0.0f)) return false;
    const float u_lobe = rng.uniform();
    const Vec2 u = rng.uniform2();
    const auto bs = v.bsdf->sample(scene::BsdfContext{v.sp.uv, mode}, wi_local, u_lobe, u);
    if (!bs || is_black(bs->weight)) return false;
    const Vec3 wo = v.sp.shading.to_world(bs->wo);
    if (!(v.sp.ng.dot(wo) * bs->wo.z() > 0.0f)) return false;
    v.delta = bs->is_delta();
    v.lobe = bs->lobe;
    v.u_lobe = u_lobe;
    v.pdf_out = bs->pdf;
    v.rr_out = 1.0f;
    v.weight_out = bs->weight;
    at = surface_hit(v);
    from = &at;
    ray = scene.continue_ray(at, wo);
  }
  if (is_black(beta)) return false;
  random_walk(scene, ray, beta, mode, params, rng, path, from);
  return path.size() == target;
}

}  // namespace dp::pathspace
