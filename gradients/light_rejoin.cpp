#include "gradients/light_rejoin.h"

#include <cmath>

#include "gradients/bidir_helpers.h"
#include "pathspace/bidir_light.h"
#include "pathspace/bidir_subpath.h"

namespace dp::gradients {

using namespace bidir;

bool rejoin_light_subpath(const scene::Scene& scene, const BidirVertex* light, int end, const BidirVertex& target,
                          const BidirShiftOptions& options, LightRejoin& out) {
  out.light.clear();
  out.throughput = Rgb::Zero();
  out.area_ratio = out.direction_ratio = 1.0;
  out.specular_chain = out.walked = false;
  out.e = -1;
  auto fail = [&](ShiftStatus st) {
    out.status = st;
    return false;
  };
  if (end < 1) return fail(ShiftStatus::not_invertible);
  const BidirVertex& x_end = light[end];
  // z = light[e]: the vertex T rejoins (e = end - 1), or the end of a specular chain.
  int e = end - 1;
  const bool chain = light[e].kind != BidirKind::light && light[e].delta;
  if (chain) {
    while (e >= 1 && chain_interior(light[e])) --e;
    if (!options.walk_chains || e == end - 1 || !chain_end(light[e]) || light[e].delta) {
      out.specular_chain = true;
      return fail(ShiftStatus::not_invertible);
    }
    thread_local std::vector<const BidirVertex*> xs;  // camera order: light[end] .. light[e]
    xs.clear();
    for (int j = end; j >= e; --j) xs.push_back(&light[j]);
    out.walked = true;
    const ShiftStatus st = walk_bidir_chain(scene, xs, target, scene::TransportMode::importance, options.walk, out.chain);
    if (st != ShiftStatus::ok) return fail(st);
  } else if (blocked(scene, target, light[e])) {
    return fail(ShiftStatus::occluded);
  }
  out.e = e;
  const BidirVertex& z = light[e];
  out.light.assign(light, light + (e + 1));
  Rgb dirac = Rgb::Ones();  // the walked chain's Dirac factors over the base's densities
  if (chain)
    for (int j = e + 1; j <= end - 1; ++j) {  // light order: from z toward T
      const ChainStep& st = out.chain.steps[size_t(end - 1 - j)];
      const BidirVertex& x = light[j];
      BidirVertex v = surface_vertex(st.hit, x, Vec3::Zero());
      v.beta = Rgb::Zero();
      v.pdf_out = st.pdf;
      v.weight_out = st.weight / x.rr_out;
      pathspace::append_vertex(scene, out.light, v, scene::TransportMode::importance);
      dirac *= st.weight * (st.pdf / (x.pdf_out * x.rr_out));
    }
  BidirVertex t = target;
  t.beta = Rgb::Zero();
  t.delta = false;  // the offset light subpath ends at T
  pathspace::append_vertex(scene, out.light, t, scene::TransportMode::importance);
  const BidirVertex& y = out.light.back();  // wi re-derived: toward its light-side neighbour
  const BidirVertex& z_next = out.light[size_t(e + 1)];
  const Vec3 w_z = z.infinite() ? Vec3(-z.sp.ng) : Vec3((z_next.sp.p - z.sp.p).normalized());
  const Vec3 w_z_base = z.infinite() ? Vec3(-z.sp.ng) : Vec3((light[e + 1].sp.p - z.sp.p).normalized());
  const Rgb fz = z.kind == BidirKind::light ? pathspace::light_emit_cos(z, w_z)
                                            : scatter(z, z.wi, w_z, scene::TransportMode::importance);
  if (is_black(fz)) return fail(ShiftStatus::zero_contribution);
  auto conv = [&](const BidirVertex& v) {  // area factor at v of a direction leaving z
    if (z.infinite()) return std::abs(double(v.sp.ng.dot(z.sp.ng)));
    const Vec3 d = z.sp.p - v.sp.p;
    const double d2 = double(d.squaredNorm());
    return std::abs(double(v.sp.ng.dot(d))) / (std::sqrt(d2) * d2);
  };
  out.area_ratio = chain ? reported_manifold_jacobian(out.chain.start_density, options.fault) : conv(y) / conv(x_end);
  if (!(out.area_ratio > 0.0) || !std::isfinite(out.area_ratio)) return fail(ShiftStatus::zero_contribution);
  auto pdf_dir = [&](const Vec3& w) {
    return double(z.kind == BidirKind::light ? pathspace::light_pdf_dir(z, w)
                                             : pathspace::bsdf_pdf(z, z.wi, w, scene::TransportMode::importance));
  };
  out.direction_ratio = pdf_dir(w_z) / pdf_dir(w_z_base);
  out.throughput = z.beta * fz * dirac * float(out.area_ratio / (double(z.pdf_out) * double(z.rr_out)));
  out.status = ShiftStatus::ok;
  return true;
}

}  // namespace dp::gradients
