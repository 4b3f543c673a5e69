#include "integrators/gpt/gpt_media_tracer.h"

#include <string>

#include "gradients/volume_path_shift.h"
#include "integrators/gpt/gpt_splat.h"
#include "pathspace/classify.h"
#include "pathspace/scatter.h"

namespace dp::integrators {

using gradients::PairTerm;

const char* to_string(MediaShiftFail f) {
  switch (f) {
    case MediaShiftFail::none: return "none";
    case MediaShiftFail::not_connectable: return "not_connectable";
    case MediaShiftFail::surface_before_distance: return "surface_before_distance";
    case MediaShiftFail::other_medium: return "other_medium";
    case MediaShiftFail::miss: return "miss";
    case MediaShiftFail::side_mismatch: return "side_mismatch";
    case MediaShiftFail::occluded: return "occluded";
    case MediaShiftFail::zero_contribution: return "zero_contribution";
  }
  return "?";
}

void GptMediaCounters::flush(core::Stats& stats) const {
  stats.add("gpt.samples", samples);
  stats.add("gpt.nan_dropped", nan_dropped);
  stats.add("gpt.media.samples", samples);
  stats.add("gpt.media.medium_vertices", walk.medium_vertices);
  stats.add("gpt.media.surface_vertices", walk.surface_vertices);
  stats.add("gpt.media.null_crossings", walk.null_crossings);
  stats.add("gpt.media.fail.null_limit", walk.null_limit);
  stats.add("gpt.media.rr_terminated", walk.rr_terminated);
  stats.add("gpt.media.shift.attempted", shifts);
  stats.add("gpt.media.shift.outside_image", shifts_outside);
  stats.add("gpt.media.shift.distance_copy", distance_copies);
  stats.add("gpt.media.shift.primary_surface", primary_surfaces);
  stats.add("gpt.media.shift.reconnect_medium", reconnect_medium);
  stats.add("gpt.media.shift.reconnect_surface", reconnect_surface);
  stats.add("gpt.media.shift.reconnect_escape", reconnect_escape);
  stats.add("gpt.media.shift.nee_reconnect", nee_reconnect);
  stats.add("gpt.media.shift.nee_fail", nee_fail);
  for (int i = 1; i < kMediaShiftFailCount; ++i)
    stats.add(std::string("gpt.media.shift.fail.") + to_string(MediaShiftFail(i)), fail[size_t(i)]);
}

GptMediaTracer::GptMediaTracer(const scene::Scene& scene, const GptSettings& settings, int max_depth)
    : m_scene(scene),
      m_settings(settings),
      m_walk{max_depth, settings.rr_depth, settings.nee, settings.shift_threshold} {}

double GptMediaTracer::light_density(const Vec3& from, const MediaVertex& light) const {
  if (light.escaped) {
    const scene::EnvironmentEmitter* env = m_scene.environment();
    return env ? double(m_scene.emitter_pmf(env)) * double(env->pdf_direct(from, {}, {}, light.d_in)) : 0.0;
  }
  if (light.medium || !light.hit.emitter) return 0.0;
  const Vec3 w = (light.p - from).normalized();
  return double(m_scene.emitter_pmf(light.hit.emitter)) *
         double(light.hit.emitter->pdf_direct(from, light.p, light.hit.ng, w));
}

// NEE at x1': the base's light point (delta lights: the same sample u, i.e. the same
// point or direction; lights at infinity: the same direction), Jacobian of the light
// direction at x1' (area lights: the reconnection factor at a surface end).
bool GptMediaTracer::shift_light(const MediaVertex& b1, const MediaVertex& o1, const MediaLightSample& bl,
                                 MediaLightSample& ol, double& J) const {
  ol = bl;
  J = 1.0;
  const double pmf = double(m_scene.emitter_pmf(bl.emitter));
  if (bl.delta) {
    const scene::DirectSample ds = bl.emitter->sample_direct(o1.p, bl.u);
    ol.p = ds.p;
    ol.w = ds.wi;
    ol.dist = ds.dist;
    ol.radiance = ds.radiance;
    ol.pdf = pmf * double(ds.pdf);
  } else if (bl.infinite) {
    ol.pdf = pmf * double(bl.emitter->pdf_direct(o1.p, {}, {}, bl.w));
  } else {
    const Vec3 e = bl.p - o1.p;
    ol.dist = e.norm();
    if (!(ol.dist > 0.0f)) return false;
    ol.w = e / ol.dist;
    scene::SurfacePoint sp;
    sp.p = bl.p;
    sp.ng = bl.n;
    ol.radiance = bl.emitter->eval(sp, -ol.w);
    ol.pdf = pmf * double(bl.emitter->pdf_direct(o1.p, bl.p, bl.n, ol.w));
    J = gradients::volume_reconnection_jacobian(b1.p, o1.p, bl.p, &bl.n, m_settings.faults.volume);
    if (!(J > 0.0)) return false;
  }
  media_eval_light(m_scene, o1, o1.d_in, ol);
  if (m_settings.faults.media == MediaShiftFault::offset_edge_without_transmittance) [[unlikely]]
    ol.edge.tr = Rgb::Ones();
  return true;
}

void GptMediaTracer::shift(const MediaPath& base, int dx, int dy, MediaOffset& o, GptMediaCounters& c) const {
  o.alive = 0;
  o.has_x3 = false;
  o.nee1 = false;
  const std::vector<MediaVertex>& b = base.v;
  const int n = int(b.size());
  if (n < 2 || b[1].escaped || (!b[1].continued && !b[1].nee.valid)) return;  // only the direct term
  ++c.shifts;
  auto fail = [&](MediaShiftFail f) { ++c.fail[size_t(f)]; };
  const MediaVertex& x1 = b[1];
  MediaVertex& X = o.x1;
  X = MediaVertex();
  const Ray r = m_scene.camera().generate_ray(base.raster + Vec2(float(dx), float(dy)));
  scene::SurfaceHit hit;
  if (x1.medium) {
    // Distance copy t' = t (Gruson et al. 2018, Sec. 4.1 and Sec. 6).
    const float t = (x1.p - base.primary.o).norm();
    const MediaEdge e = trace_primary(m_scene, r, t, hit);
    if (e.blocked) return fail(MediaShiftFail::surface_before_distance);
    if (e.end_medium != x1.medium_index) return fail(MediaShiftFail::other_medium);
    X.medium = true;
    X.medium_index = e.end_medium;
    X.p = gradients::copy_medium_distance_t(r.o, r.d, t);
    const Rgb sigma_s = m_scene.media()[size_t(X.medium_index)].sigma_s;
    o.obc[1] = (e.tr * sigma_s).cast<double>() / x1.ff_in;
    o.cr[1] = e.ff / x1.ff_in;
    ++c.distance_copies;
  } else {
    if (!x1.connectable || x1.delta_lobe) return fail(MediaShiftFail::not_connectable);
    const MediaEdge e = trace_primary(m_scene, r, -1.0f, hit);
    if (e.blocked) return fail(MediaShiftFail::miss);
    if (!hit.bsdf || !pathspace::is_connectable(hit.bsdf, m_settings.shift_threshold))
      return fail(MediaShiftFail::not_connectable);
    if (!pathspace::consistent_side(hit, -r.d, hit.shading.to_local(-r.d).z()))
      return fail(MediaShiftFail::zero_contribution);
    X.hit = hit;
    X.p = hit.p;
    X.medium_index = e.end_medium;
    o.obc[1] = e.tr.cast<double>() / x1.ff_in;
    o.cr[1] = e.ff / x1.ff_in;
    ++c.primary_surfaces;
  }
  X.d_in = r.d;
  X.connectable = true;
  o.alive = 2;
  if (x1.nee.valid) {
    o.nee1 = shift_light(x1, X, x1.nee, o.light1, o.J_light1);
    if (o.nee1) ++c.nee_reconnect;
    else ++c.nee_fail;  // the light sample only (zero distance or Jacobian); x1' stays
  }
  if (n < 3 || !x1.continued) return;

  // Reconnection x1' -> x2 (Kettunen 2015, Sec. 5.2, with the volume measure at x2).
  const MediaVertex& x2 = b[2];
  if (x1.delta_lobe || !x2.connectable || (x2.continued && x2.delta_lobe)) return fail(MediaShiftFail::not_connectable);
  Vec3 w = x2.d_in;
  float len = kInfinity;
  double J = 1.0;
  if (!x2.escaped) {
    gradients::volume_reconnection_edge_t(X.p, x2.p, w, len);
    J = gradients::volume_reconnection_jacobian(x1.p, X.p, x2.p, x2.medium ? nullptr : &x2.hit.ng,
                                                m_settings.faults.volume);
    if (!(J > 0.0) || !(len > 0.0f)) return fail(MediaShiftFail::zero_contribution);
  }
  Rgb f1;
  float p1;
  if (!media_scatter_eval(m_scene, X, X.d_in, w, f1, p1)) return fail(MediaShiftFail::zero_contribution);
  if (!x2.escaped && !x2.medium) {
    if ((x2.hit.ng.dot(w) > 0.0f) != (x2.hit.ng.dot(x2.d_in) > 0.0f)) return fail(MediaShiftFail::side_mismatch);
    if (!pathspace::consistent_side(x2.hit, -w, x2.hit.shading.to_local(-w).z()))
      return fail(MediaShiftFail::zero_contribution);
  }
  const MediaEdge e = trace_media_edge(m_scene, media_edge_start(X), w, len, media_medium_toward(m_scene, X, w),
                                       x2.medium);
  if (e.blocked) return fail(MediaShiftFail::occluded);
  if (e.end_medium != x2.medium_index) return fail(MediaShiftFail::other_medium);
  Rgb ew = m_settings.faults.media == MediaShiftFault::offset_edge_without_transmittance ? Rgb::Ones() : e.tr;
  if (x2.medium) ew *= m_scene.media()[size_t(x2.medium_index)].sigma_s;
  o.J = J;
  o.d2 = w;
  o.obc[2] = o.obc[1] * (f1.cast<double>() * (J / x1.pdf)) * ew.cast<double>() / (x2.ff_in * double(x1.rr));
  o.cr[2] = o.cr[1] * double(p1) * J * e.ff / (x1.pdf * x2.ff_in);
  o.emission2 = Rgb::Zero();
  if (x2.escaped) o.emission2 = x2.emission;
  else if (!x2.medium && x2.hit.emitter) o.emission2 = x2.hit.emitter->eval(x2.hit, -w);
  o.alive = 3;
  if (x2.escaped) ++c.reconnect_escape;
  else if (x2.medium) ++c.reconnect_medium;
  else ++c.reconnect_surface;
  // x2 with its new incoming direction: its light sample and its continuation.
  if (x2.nee.valid) {
    Rgb f;
    float p;
    media_scatter_eval(m_scene, x2, w, x2.nee.w, f, p);
    o.f2_light = f;
    o.spdf2_light = x2.nee.delta ? 0.0 : double(p);
  }
  if (x2.continued && n > 3) {
    Rgb f2;
    float p2;
    media_scatter_eval(m_scene, x2, w, x2.wo, f2, p2);
    o.obc[3] = o.obc[2] * (f2.cast<double>() / x2.pdf) * b[3].edge_w.cast<double>() / double(x2.rr);
    o.cr[3] = o.cr[2] * double(p2) / x2.pdf;
    o.has_x3 = true;
  }
}

namespace {

// The light's value times the shadow edge's transmittance (0 when blocked).
Rgbd gpt_media_light_value(const MediaLightSample& ls, const Rgb& f) {
  if (ls.edge.blocked) return Rgbd::Zero();
  return (f * ls.edge.tr * ls.radiance).cast<double>();
}
// The density of reaching the light point by BSDF / phase sampling plus free flight.
double gpt_media_other(const MediaLightSample& ls, double scatter_pdf) {
  return ls.delta || ls.edge.blocked ? 0.0 : scatter_pdf * ls.edge.ff;
}

}  // namespace

void GptMediaTracer::terms(const MediaPath& base, const MediaOffset* o, std::vector<PairTerm>& out) const {
  out.clear();
  const std::vector<MediaVertex>& b = base.v;
  const int n = int(b.size());
  const bool nee = m_settings.nee;
  const int alive = o ? o->alive : 0;
  Rgbd ob = Rgbd::Zero();  // obc[k] for k >= 3
  for (int k = 1; k < n; ++k) {
    const MediaVertex& v = b[k];
    if (k == 3 && alive >= 3 && o->has_x3) ob = o->obc[3];
    else if (k > 3) ob = ob * (b[k - 1].weight.cast<double>() * v.edge_w.cast<double>()) / double(b[k - 1].rr);
    const bool shared = alive >= 3 && (k < 3 || o->has_x3);  // the offset has this prefix
    if (v.nee.valid) {
      const MediaLightSample& L = v.nee;
      PairTerm t;
      t.segments = k + 1;
      t.nee = true;
      t.fb = v.beta.cast<double>() * gpt_media_light_value(L, L.f) / L.pdf;
      t.b_other = gpt_media_other(L, L.scatter_pdf) / L.pdf;
      t.base_visible = !L.edge.blocked;
      if (k == 1 && alive >= 2 && o->nee1) {
        const MediaLightSample& M = o->light1;
        const double J = o->J_light1;
        t.fo = o->obc[1] * gpt_media_light_value(M, M.f) * (J / L.pdf);
        t.c = o->cr[1] * M.pdf * J / L.pdf;
        t.d = o->cr[1] * gpt_media_other(M, M.scatter_pdf) * J / L.pdf;
        t.jacobian = J;
        t.has_offset = true;
        t.offset_visible = !M.edge.blocked;
      } else if (k == 2 && alive >= 3) {
        t.fo = o->obc[2] * gpt_media_light_value(L, o->f2_light) / L.pdf;
        t.c = o->cr[2];
        t.d = o->cr[2] * gpt_media_other(L, o->spdf2_light) / L.pdf;
        t.jacobian = o->J;
        t.has_offset = true;
        t.offset_visible = t.base_visible;
      } else if (k >= 3 && shared) {
        t.fo = ob * gpt_media_light_value(L, L.f) / L.pdf;
        t.c = o->cr[3];
        t.d = o->cr[3] * t.b_other;
        t.jacobian = o->J;
        t.has_offset = true;
        t.offset_visible = t.base_visible;
      }
      if ((t.fb != 0.0).any() || (t.fo != 0.0).any()) out.push_back(t);
    }
    if (k < 2) continue;
    // The BSDF / phase path ending at x_k (it emits).
    const bool offset_emits = k == 2 && alive >= 3 && !is_black(o->emission2);
    if (is_black(v.emission) && !offset_emits) continue;
    const MediaVertex& p = b[k - 1];
    const double self = p.pdf * v.ff_in;
    const bool mis = nee && !p.delta_lobe;
    PairTerm t;
    t.segments = k;
    t.fb = v.beta.cast<double>() * v.emission.cast<double>();
    t.b_other = mis ? light_density(p.p, v) / self : 0.0;
    if (k == 2 && alive >= 3) {
      t.fo = o->obc[2] * o->emission2.cast<double>();
      t.c = o->cr[2];
      t.d = mis ? o->cr[1] * light_density(o->x1.p, v) * o->J / (p.pdf * v.ff_in) : 0.0;
      t.has_offset = true;
    } else if (k == 3 && alive >= 3 && o->has_x3) {
      t.fo = ob * v.emission.cast<double>();
      t.c = o->cr[3];
      t.d = mis ? o->cr[2] * light_density(p.p, v) / self : 0.0;
      t.has_offset = true;
    } else if (k > 3 && shared) {
      t.fo = ob * v.emission.cast<double>();
      t.c = o->cr[3];
      t.d = o->cr[3] * t.b_other;
      t.has_offset = true;
    }
    t.jacobian = t.has_offset ? o->J : 1.0;
    if ((t.fb != 0.0).any() || (t.fo != 0.0).any()) out.push_back(t);
  }
}

void GptMediaTracer::sample(int px, int py, pathspace::SampleStream& stream, gradients::GradientBuffers& buf,
                            GptMediaCounters& counters) const {
  thread_local MediaPath base;
  thread_local MediaOffset offset;
  thread_local std::vector<PairTerm> pair;
  ++counters.samples;
  build_media_path(m_scene, m_walk, px, py, stream, base, counters.walk);
  const int w = buf.width(), h = buf.height();
  if (base.v.size() >= 2) {
    const Rgb direct = base.v[1].beta * base.v[1].emission;
    if (is_finite(direct)) buf.add_direct(px, py, direct.cast<double>());
    else ++counters.nan_dropped;
  }
  for (int nb = 0; nb < 4; ++nb) {
    const int qx = px + kGptDx[nb], qy = py + kGptDy[nb];
    const bool inside = qx >= 0 && qy >= 0 && qx < w && qy < h;
    if (inside) shift(base, kGptDx[nb], kGptDy[nb], offset, counters);
    else ++counters.shifts_outside;
    terms(base, inside ? &offset : nullptr, pair);
    if (!splat_gpt_pair(pair, px, py, nb, inside, m_settings.faults.mis, buf)) ++counters.nan_dropped;
  }
  buf.add_samples(px, py, 1);
}

}  // namespace dp::integrators
