#include "gradients/reconnection_shift.h"

#include <cmath>

#include "gradients/jacobians.h"
#include "gradients/shift_helpers.h"
#include "pathspace/classify.h"
#include "pathspace/scatter.h"

namespace dp::gradients {

using pathspace::LightSample;
using pathspace::Path;
using pathspace::Vertex;
using pathspace::VertexKind;

namespace {
// Shadow test of a light sample seen from surface point `hit`.
bool light_visible(const scene::Scene& scene, const scene::SurfaceHit& hit, const LightSample& ls) {
  return std::isfinite(ls.dist) ? !scene.occluded(scene.spawn_segment(hit, ls.p))
                                : !scene.occluded(scene.spawn_ray(hit, ls.w));
}
}  // namespace

void ReconnectionShift::shift(const Path& base, const Vec2& raster_offset, ShiftResult& out) const {
  run(base, base.raster + raster_offset, nullptr, out);
}

void ReconnectionShift::shift_to_primary(const Path& base, const Path& target, ShiftResult& out) const {
  run(base, target.raster, &target, out);
}

void ReconnectionShift::run(const Path& base, const Vec2& raster, const Path* target, ShiftResult& out) const {
  const int n = base.size();
  out.reset(n);
  Path& o = out.path;
  o.raster = raster;
  Vertex cam = base[0];
  cam.wo_world = target ? (*target)[0].wo_world : m_scene.camera().generate_ray(o.raster).d;
  o.append(cam);
  out.alive = 1;
  for (int k = 0; k < n; ++k) {
    if (k >= 1 && base.nee[size_t(k)].valid) shift_nee(base, k, out);
    if (k + 1 >= n) break;
    if (o.size() < k + 2) {  // a chain step (ManifoldShift) may already have made x'_{k+1}
      const ShiftStatus s = k == 0 && target ? adopt_primary(base, *target, out) : step(base, k, out);
      if (s != ShiftStatus::ok) {
        out.status = s;
        return;
      }
    }
    out.alive = k + 2;
  }
}

ShiftStatus ReconnectionShift::step(const Path& base, int k, ShiftResult& out) const {
  Path& o = out.path;
  const Vertex& b = base[k];
  const Vertex& bn = base[k + 1];
  if (k == 0) {
    out.step[0] = StepKind::primary;  // same sub-pixel offset: Jacobian 1
    return trace_next(base, 0, out);
  }
  const bool connected = out.reconnected >= 0;
  if (connected && k > out.reconnected) {  // shared vertices: identical directions, factor 1
    o[k] = b;
    o.append(bn);
    out.step[size_t(k)] = StepKind::copy;
    return ShiftStatus::ok;
  }
  Vertex& ov = o[k];
  if (ov.kind != VertexKind::surface || !ov.hit.bsdf || !wi_consistent(ov)) return ShiftStatus::zero_contribution;
  const auto ctx = pathspace::radiance_context(ov.hit);
  const scene::Bsdf& bsdf = *ov.hit.bsdf;

  if (connected) {  // k == reconnected: the base vertex, reached from the offset's direction
    Rgb f;
    double pdf;
    if (b.delta_lobe()) {
      const auto bs = pathspace::sample_dirac_lobe(bsdf, ctx, ov.wi, b.lobe, b.u_lobe);
      if (!bs || (bs->wo - b.wo).norm() > 1e-4f) return ShiftStatus::zero_contribution;
      f = bs->weight * bs->pdf;
      pdf = double(bs->pdf);
    } else {
      float p = 0.0f;
      f = bsdf.eval_pdf(ctx, ov.wi, b.wo, p) * abs_cos_theta(b.wo);
      pdf = double(p);
    }
    if (!(pdf > 0.0)) return ShiftStatus::zero_contribution;
    set_scatter(ov, b, b.wo, b.wo_world, f, pdf);
    o.append(bn);
    out.step[size_t(k)] = StepKind::copy;
    return ShiftStatus::ok;
  }

  // Reconnection (Kettunen 2015, Sec. 5.2): x_k, x'_k and x_{k+1} connectable.
  const bool reconnect_here = !b.delta_lobe() && b.connectable && ov.connectable;
  if (reconnect_here && bn.connectable) {
    Vec3 wo_w;
    double J = 1.0;
    if (bn.kind == VertexKind::environment) {
      wo_w = b.wo_world;  // same escape direction: factor 1
      if (m_scene.trace_from(ov.hit, wo_w)) return ShiftStatus::occluded;
    } else {
      if (m_scene.occluded(m_scene.spawn_segment(ov.hit, bn.p()))) return ShiftStatus::occluded;
      wo_w = (bn.p() - ov.p()).normalized();
      J = reconnection_jacobian(d3(b.p()), d3(ov.p()), d3(bn.p()), d3(bn.hit.ng));
    }
    const Vec3 wo_l = ov.hit.shading.to_local(wo_w);
    if (!pathspace::consistent_side(ov.hit, wo_w, wo_l.z())) return ShiftStatus::zero_contribution;
    float p = 0.0f;
    const Rgb f = bsdf.eval_pdf(ctx, ov.wi, wo_l, p) * abs_cos_theta(wo_l);
    const double pdf = double(p);
    if (!(pdf > 0.0) || !(J > 0.0)) return ShiftStatus::zero_contribution;
    set_scatter(ov, b, wo_l, wo_w, f, pdf);
    Vertex nv = bn;
    if (nv.kind == VertexKind::surface) nv.wi = nv.hit.shading.to_local(-wo_w);
    nv.emission = pathspace::emitted(m_scene, nv, -wo_w);
    o.append(nv);
    out.jacobian[size_t(k)] = reported_jacobian(J, m_opt.fault, false);
    out.step[size_t(k)] = StepKind::reconnect;
    out.reconnected = k + 1;
    return ShiftStatus::ok;
  }

  Vec3 wo_l;
  Rgb f;
  double pdf, J = 1.0;
  if (b.delta_lobe()) {  // Dirac lobe copy (factor 1); never between delta and smooth lobes
    const auto bs = pathspace::sample_dirac_lobe(bsdf, ctx, ov.wi, b.lobe, b.u_lobe);
    if (!bs) return ShiftStatus::zero_contribution;
    wo_l = bs->wo;
    f = bs->weight * bs->pdf;
    pdf = double(bs->pdf);
    out.step[size_t(k)] = StepKind::dirac;
  } else {
    if (!m_opt.half_vector_enabled) return ShiftStatus::not_invertible;
    const Vec3d wi = d3(b.wi), wo = d3(b.wo), wi_o = d3(ov.wi);
    Vec3d wo_o;
    if (b.wi.z() * b.wo.z() > 0.0f) {  // reflection
      const Vec3d h = reflection_half_vector(wi, wo);
      wo_o = reflect_about(wi_o, h);
      J = reflection_jacobian(wo, wo_o, h);
    } else {  // refraction: both on the same side of the interface, eta != 1
      if (b.wi.z() * ov.wi.z() <= 0.0f) return ShiftStatus::not_invertible;
      const auto h = refraction_half_vector(wi, wo, double(b.eta));
      if (!h) return ShiftStatus::not_invertible;
      const auto r = refract_about(wi_o, *h, double(b.eta));
      if (!r) return ShiftStatus::zero_contribution;  // total internal reflection
      wo_o = *r;
      J = refraction_jacobian(wi, wo, wi_o, wo_o, double(b.eta));
    }
    wo_l = wo_o.normalized().cast<float>();
    float p = 0.0f;
    f = bsdf.eval_pdf(ctx, ov.wi, wo_l, p) * abs_cos_theta(wo_l);
    pdf = double(p);
    out.step[size_t(k)] = StepKind::half_vector;
  }
  if (!(pdf > 0.0) || !(J > 0.0)) return ShiftStatus::zero_contribution;
  const Vec3 wo_w = ov.hit.shading.to_world(wo_l);
  if (!pathspace::consistent_side(ov.hit, wo_w, wo_l.z())) return ShiftStatus::zero_contribution;
  set_scatter(ov, b, wo_l, wo_w, f, pdf);
  out.jacobian[size_t(k)] = reported_jacobian(J, m_opt.fault, out.step[size_t(k)] == StepKind::half_vector);
  return trace_next(base, k, out);
}

ShiftStatus ReconnectionShift::adopt_primary(const Path& base, const Path& target, ShiftResult& out) const {
  out.step[0] = StepKind::primary;  // same sub-pixel offset: Jacobian 1
  const Vertex& bn = base[1];
  if (target.size() < 2) return ShiftStatus::miss;  // (a built walk always has x_1)
  const Vertex& t = target[1];
  // The vertex trace_next would make from the same camera ray (the walk's x_1 was traced
  // from it): position, classification, wi and emission; no scattering record yet.
  Vertex nv;
  nv.kind = t.kind;
  if (t.kind == VertexKind::environment) {
    if (bn.kind != VertexKind::environment) return ShiftStatus::miss;
    nv.wo_world = t.wo_world;
    nv.hit.p = t.hit.p;
    nv.connectable = true;
  } else {
    if (bn.kind == VertexKind::environment) return ShiftStatus::miss;
    nv.hit = t.hit;
    nv.connectable = t.connectable;
    nv.wi = t.hit.shading.to_local(-target[0].wo_world);
  }
  if (m_opt.match_classes && nv.connectable != bn.connectable) {
    out.class_mismatch = true;
    return ShiftStatus::not_invertible;
  }
  nv.emission = t.emission;
  out.path.append(nv);
  return ShiftStatus::ok;
}

ShiftStatus ReconnectionShift::trace_next(const Path& base, int k, ShiftResult& out) const {
  Path& o = out.path;
  const Vertex& b = base[k];
  const Vertex& bn = base[k + 1];
  const Vertex& ov = o[k];
  // Rays leave from the vertex itself, as the base walk's (pathspace/scatter.h).
  const Ray ray = k == 0 ? m_scene.camera().generate_ray(o.raster) : m_scene.continue_ray(ov.hit, ov.wo_world);
  // The reverse shift reconnects at k+1 iff x'_k, x_k and x'_{k+1} are connectable; the
  // forward one did not, so an offset landing on a connectable vertex is not invertible.
  const bool check_inverse = k > 0 && !b.delta_lobe() && b.connectable && ov.connectable;
  const auto hit = k == 0 ? m_scene.intersect(ray) : m_scene.trace_from(ov.hit, ov.wo_world);
  Vertex nv;
  if (!hit) {
    if (bn.kind != VertexKind::environment) return ShiftStatus::miss;
    nv.kind = VertexKind::environment;
    nv.wo_world = ray.d;
    nv.hit.p = ray.o;
    nv.connectable = true;
  } else {
    if (bn.kind == VertexKind::environment) return ShiftStatus::miss;
    nv.kind = VertexKind::surface;
    nv.hit = *hit;
    nv.connectable = pathspace::is_connectable(hit->bsdf, m_opt.threshold);
    nv.wi = hit->shading.to_local(-ray.d);
  }
  if (check_inverse && nv.connectable) return ShiftStatus::not_invertible;
  if (m_opt.match_classes && nv.connectable != bn.connectable) {
    out.class_mismatch = true;
    return ShiftStatus::not_invertible;
  }
  nv.emission = pathspace::emitted(m_scene, nv, -ray.d);
  o.append(nv);
  return ShiftStatus::ok;
}

void ReconnectionShift::shift_nee(const Path& base, int k, ShiftResult& out) const {
  Path& o = out.path;
  const LightSample& bl = base.nee[size_t(k)];
  LightSample& ol = o.nee[size_t(k)];
  ol = LightSample();
  auto fail = [&](ShiftStatus s) { out.nee_status[size_t(k)] = s; };
  if (!(bl.pdf > 0.0)) return fail(ShiftStatus::zero_contribution);  // the base sample failed
  const bool connected = out.reconnected >= 0;
  if (connected && k > out.reconnected) {
    ol = bl;
    out.nee_step[size_t(k)] = StepKind::nee_copy;
    return;
  }
  const Vertex& ov = o[k];
  const Vertex& b = base[k];
  if (ov.kind != VertexKind::surface || !ov.hit.bsdf || ov.hit.bsdf->is_purely_delta() || !wi_consistent(ov))
    return fail(ShiftStatus::zero_contribution);
  const auto ctx = pathspace::radiance_context(ov.hit);
  const scene::Bsdf& bsdf = *ov.hit.bsdf;
  auto finish = [&](double J, StepKind kind) {
    ol.wo = ov.hit.shading.to_local(ol.w);
    if (!pathspace::consistent_side(ov.hit, ol.w, ol.wo.z())) return fail(ShiftStatus::zero_contribution);
    float p = 0.0f;
    ol.f_cos = bsdf.eval_pdf(ctx, ov.wi, ol.wo, p) * abs_cos_theta(ol.wo);
    ol.bsdf_pdf = ol.delta ? 0.0 : double(p);
    ol.valid = true;
    out.nee_jacobian[size_t(k)] = reported_jacobian(J, m_opt.fault, kind == StepKind::nee_half_vector);
    out.nee_step[size_t(k)] = kind;
  };

  if (connected || (b.connectable && ov.connectable && bl.connectable)) {
    // Same light point / direction / position (area measure on the light: the shared
    // vertex does not move; in solid angle at x'_k the factor is the reconnection one).
    ol = bl;
    ol.valid = false;
    double J = 1.0;
    const float pmf = m_scene.emitter_pmf(bl.emitter);
    if (connected) {
      // k == reconnected: the very base vertex, only wi differs.
    } else if (bl.delta) {
      const scene::DirectSample ds = bl.emitter->sample_direct(ov.p(), bl.u);
      ol.p = ds.p;
      ol.w = ds.wi;
      ol.dist = ds.dist;
      ol.radiance = ds.radiance;
      ol.pdf = double(pmf) * double(ds.pdf);
    } else if (bl.infinite) {
      ol.pdf = double(pmf) * double(bl.emitter->pdf_direct(ov.p(), {}, {}, bl.w));
    } else {
      const Vec3 d = bl.p - ov.p();
      ol.dist = d.norm();
      ol.w = d / ol.dist;
      scene::SurfacePoint sp;
      sp.p = bl.p;
      sp.ng = bl.n;
      ol.radiance = bl.emitter->eval(sp, -ol.w);
      ol.pdf = double(pmf) * double(bl.emitter->pdf_direct(ov.p(), bl.p, bl.n, ol.w));
      J = reconnection_jacobian(d3(b.p()), d3(ov.p()), d3(bl.p), d3(bl.n));
    }
    // A light pdf of 0 (e.g. the back of the light) is not a failure: BSDF sampling may
    // still produce this path, so its density counts in the MIS weights.
    if (!(J > 0.0)) return fail(ShiftStatus::zero_contribution);
    finish(J, connected ? StepKind::nee_copy : StepKind::nee_reconnect);
    if (ol.valid) ol.visible = (is_black(ol.f_cos) && !(ol.bsdf_pdf > 0.0)) ? false : light_visible(m_scene, ov.hit, ol);
    return;
  }

  // Half-vector copy of the light direction (reflection only), then trace.
  if (!m_opt.half_vector_enabled) return fail(ShiftStatus::not_invertible);
  if (bl.delta) return fail(ShiftStatus::zero_contribution);  // a traced ray never hits a delta light
  if (b.wi.z() * bl.wo.z() <= 0.0f) return fail(ShiftStatus::not_invertible);
  const Vec3d h = reflection_half_vector(d3(b.wi), d3(bl.wo));
  const Vec3d wo_o = reflect_about(d3(ov.wi), h);
  const double J = reflection_jacobian(d3(bl.wo), wo_o, h);
  if (!(J > 0.0)) return fail(ShiftStatus::zero_contribution);
  ol.w = ov.hit.shading.to_world(wo_o.normalized().cast<float>());
  const auto hit = m_scene.trace_from(ov.hit, ol.w);
  ol.visible = true;
  ol.u = bl.u;
  if (hit) {
    ol.p = hit->p;
    ol.n = hit->ng;
    ol.dist = (hit->p - ov.p()).norm();
    ol.connectable = pathspace::is_connectable(hit->bsdf, m_opt.threshold);
    if (hit->emitter) {
      ol.emitter = hit->emitter;
      ol.radiance = hit->emitter->eval(*hit, -ol.w);
      ol.pdf = double(m_scene.emitter_pmf(hit->emitter)) * double(hit->emitter->pdf_direct(ov.p(), hit->p, hit->ng, ol.w));
    }
  } else {
    ol.dist = kInfinity;
    ol.infinite = true;
    ol.connectable = true;
    if (const auto* env = m_scene.environment()) {
      ol.emitter = env;
      ol.radiance = env->eval_direction(ol.w);
      ol.pdf = double(m_scene.emitter_pmf(env)) * double(env->pdf_direct(ov.p(), {}, {}, ol.w));
    }
  }
  if (b.connectable && ov.connectable && !bl.connectable && ol.connectable) return fail(ShiftStatus::not_invertible);
  finish(J, StepKind::nee_half_vector);
}

}  // namespace dp::gradients
