#include "mcmc/path_state.h"

#include <cmath>

#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_light.h"
#include "pathspace/scatter.h"

namespace dp::mcmc {

using pathspace::BidirKind;
using pathspace::BidirVertex;
using scene::TransportMode;

namespace {

// The factor a walk in `mode` multiplies its throughput by when it scatters at surface
// vertex v, arriving along wi and leaving along wo (both away from v): f |cos wo| / pdf
// of the smooth lobes, or the Dirac lobe's sample weight (f |cos| / its probability).
// 0 on a sidedness violation of either direction (as the walks and connect()). `pdf`
// receives the density of wo as the walk samples it (solid angle; a Dirac lobe's
// selection probability), 0 where the weight is 0.
Rgb step_weight(const BidirVertex& v, const Vec3& wi, const Vec3& wo, TransportMode mode, float* pdf_out = nullptr) {
  if (pdf_out) *pdf_out = 0.0f;
  if (v.kind != BidirKind::surface || !v.bsdf) return Rgb::Zero();
  const Vec3 wi_l = v.sp.shading.to_local(wi), wo_l = v.sp.shading.to_local(wo);
  if (!(v.sp.ng.dot(wi) * wi_l.z() > 0.0f) || !(v.sp.ng.dot(wo) * wo_l.z() > 0.0f)) return Rgb::Zero();
  const scene::BsdfContext ctx{v.sp.uv, mode};
  if (v.delta) {
    const auto bs = pathspace::sample_dirac_lobe(*v.bsdf, ctx, wi_l, v.lobe, v.u_lobe);
    if (bs && pdf_out) *pdf_out = bs->pdf;
    return bs ? bs->weight : Rgb::Zero();
  }
  float pdf = 0.0f;
  const Rgb f = v.bsdf->eval_pdf(ctx, wi_l, wo_l, pdf);
  if (pdf_out) *pdf_out = pdf;
  return pdf > 0.0f ? Rgb(f * (std::abs(wo_l.z()) / pdf)) : Rgb::Zero();
}

// The light walk's copy: wi toward the predecessor, beta as light_subpath() sets it.
void light_side(const scene::Scene& scene, const std::vector<BidirVertex>& v, std::vector<BidirVertex>& out) {
  out = v;
  const size_t n = out.size();
  BidirVertex& y0 = out[0];
  const float pos = pathspace::light_pdf_pos(scene, y0);
  y0.beta = pos > 0.0f ? Rgb::Constant(1.0f / pos) : Rgb::Zero();
  y0.wi = Vec3::Zero();
  if (n < 2) return;
  const Vec3 w = direction_between(y0, out[1]);
  const float r = pathspace::infinite_disk_radius(scene);
  const float pdf_ray = y0.infinite() ? 1.0f / (kPi * r * r) : pathspace::light_pdf_dir(y0, w);
  out[1].beta = pdf_ray > 0.0f ? Rgb(y0.beta * pathspace::light_emit_cos(y0, w) / pdf_ray) : Rgb::Zero();
  for (size_t i = 1; i < n; ++i) {
    out[i].wi = direction_between(out[i], out[i - 1]);
    if (i + 1 < n) out[i + 1].beta = out[i].beta * step_weight(out[i], out[i].wi, direction_between(out[i], out[i + 1]),
                                                               TransportMode::importance);
  }
}

// The camera walk's copy (x_K first): We / p = 1 at z_1 (bidir_vertex.h). Each surface
// vertex also gets what a camera walk that sampled these directions would have recorded
// (pdf_out, weight_out, rr_out = 1: no roulette in path space), as the shifts replay it
// (gradients/bidir_shift.h).
void camera_side(const std::vector<BidirVertex>& v, std::vector<BidirVertex>& out) {
  out.assign(v.rbegin(), v.rend());
  const size_t n = out.size();
  out[0].beta = Rgb::Ones();
  out[0].wi = Vec3::Zero();
  if (n < 2) return;
  out[1].beta = Rgb::Ones();
  for (size_t j = 1; j < n; ++j) {
    BidirVertex& z = out[j];
    z.wi = direction_between(z, out[j - 1]);
    z.rr_out = 1.0f;
    z.pdf_out = 0.0f;
    z.weight_out = Rgb::Zero();
    if (j + 1 < n) {
      z.weight_out = step_weight(z, z.wi, direction_between(z, out[j + 1]), TransportMode::radiance, &z.pdf_out);
      out[j + 1].beta = z.beta * z.weight_out;
    }
  }
  // The light endpoint as the camera walk finds it: an area light is a surface hit.
  BidirVertex& last = out[n - 1];
  if (last.emitter && last.emitter->kind() == scene::EmitterKind::area) last.kind = BidirKind::surface;
}

}  // namespace

Vec3 direction_between(const BidirVertex& from, const BidirVertex& to) {
  if (to.infinite()) return to.sp.ng;
  if (from.infinite()) return -from.sp.ng;
  return (to.sp.p - from.sp.p).normalized();
}

void path_sides(const scene::Scene& scene, const std::vector<BidirVertex>& v, PathSides& sides) {
  light_side(scene, v, sides.light);
  camera_side(v, sides.camera);
}

bool evaluate_path(const scene::Scene& scene, PathState& state, PathSides& sides) {
  const int K = state.depth();
  state.inv_c.assign(size_t(std::max(K + 1, 0)), 0.0);
  state.ref = -1;
  state.c_ref = Rgb::Zero();
  state.nonfinite = false;
  if (K < 1 || state.v[0].kind != BidirKind::light || state.v[size_t(K)].kind != BidirKind::camera) return false;
  const scene::PerspectiveCamera& cam = scene.camera();
  const BidirVertex& eye = state.v[size_t(K - 1)];
  const auto raster = cam.raster_of(eye.infinite() ? Vec3(cam.position() + eye.sp.ng) : eye.sp.p);
  if (!raster) return false;
  state.raster = *raster;
  path_sides(scene, state.v, sides);
  pathspace::MisConfig unweighted;
  unweighted.unweighted = true;
  for (int s = 0; s <= K; ++s) {
    const int t = K + 1 - s;
    // A connection needs smooth components at both ends; s = 0 needs the camera walk to
    // reach the light (any component before it).
    if (s >= 1 && (state.v[size_t(s - 1)].delta || state.v[size_t(s)].delta)) continue;
    if (s == 0 && state.v[0].emitter->is_delta()) continue;  // no walk hits a point, spot or directional light
    pathspace::Connection c;
    if (!pathspace::connect(scene, sides.light.data(), s, sides.camera.data(), t, unweighted, c, false)) continue;
    const double lum = luminance(c.value);
    if (!std::isfinite(lum) || !is_finite(c.value)) {
      state.nonfinite = true;
      return false;
    }
    if (!(lum > 0.0)) continue;
    state.inv_c[size_t(s)] = 1.0 / lum;
    if (state.ref < 0) {
      state.ref = s;
      state.c_ref = c.value;
    }
  }
  return state.ref >= 0;
}

void path_of_strategy(const BidirVertex* light, int s, const BidirVertex* camera, int t,
                      std::vector<BidirVertex>& out) {
  out.clear();
  for (int i = 0; i < s; ++i) out.push_back(light[i]);
  for (int j = t - 1; j >= 0; --j) out.push_back(camera[j]);
  if (s >= 1) out[size_t(s - 1)].delta = false;
  out[size_t(s)].delta = false;
  BidirVertex& x0 = out[0];
  if (s == 0 && x0.kind == BidirKind::surface) {
    x0.kind = BidirKind::light;
    x0.bsdf = nullptr;
    x0.sp.shading = Frame::from_normal(x0.sp.ng);  // emission is about the geometric normal
  }
}

}  // namespace dp::mcmc
