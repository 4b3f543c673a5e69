#include "mcmc/perturb_chain.h"

#include <cmath>

#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"
#include "pathspace/scatter.h"

namespace dp::mcmc {

using pathspace::BidirKind;
using pathspace::BidirVertex;

int first_smooth_from_camera(const PathState& x) {
  int c = x.depth() - 1;
  while (c >= 0 && x.v[size_t(c)].delta) --c;
  return c;
}

ProposalStatus retrace_chain(const scene::Scene& scene, const PathState& x, std::vector<BidirVertex>& yv, int from,
                             int end, const Vec3& w, scene::TransportMode mode) {
  const int step = end > from ? 1 : -1;
  Vec3 dir = w;
  for (int i = from + step;; i += step) {
    const BidirVertex& prev = yv[size_t(i - step)];
    scene::SurfaceHit hit;
    bool found = false;
    if (prev.kind == BidirKind::surface) {
      found = pathspace::next_hit(scene, pathspace::surface_hit(prev), dir, hit);
    } else if (prev.infinite()) {
      return ProposalStatus::configuration;
    } else {
      found = scene.intersect(pathspace::anchored_ray(scene, prev.sp.p, dir), hit);
    }
    if (!found) return ProposalStatus::walk_ended;
    const BidirVertex& xv = x.v[size_t(i)];
    BidirVertex v = pathspace::surface_vertex_at(hit);
    v.wi = -dir;
    if (!hit.bsdf) return ProposalStatus::configuration;
    const Vec3 wi = hit.shading.to_local(v.wi);
    if (!pathspace::consistent_side(hit, v.wi, wi.z())) return ProposalStatus::walk_ended;
    if (i == end) {
      if (hit.bsdf->is_purely_delta()) return ProposalStatus::configuration;
      yv[size_t(i)] = v;
      return ProposalStatus::ok;
    }
    const auto bs = pathspace::sample_dirac_lobe(*hit.bsdf, scene::BsdfContext{hit.uv, mode}, wi, xv.lobe, xv.u_lobe);
    if (!bs) return ProposalStatus::configuration;
    dir = hit.shading.to_world(bs->wo);
    if (!pathspace::consistent_side(hit, dir, bs->wo.z())) return ProposalStatus::walk_ended;
    v.delta = true;
    v.lobe = xv.lobe;
    v.u_lobe = xv.u_lobe;
    yv[size_t(i)] = v;
  }
}

double dirac_chain_prob(const PathState& s, int a, int b, scene::TransportMode mode) {
  double p = 1.0;
  const bool radiance = mode == scene::TransportMode::radiance;
  for (int i = std::min(a, b) + 1; i < std::max(a, b); ++i) {
    const BidirVertex& v = s.v[size_t(i)];
    if (!v.delta || !v.bsdf) continue;
    const Vec3 wi = direction_between(v, s.v[size_t(radiance ? i + 1 : i - 1)]);
    const auto bs = pathspace::sample_dirac_lobe(*v.bsdf, scene::BsdfContext{v.sp.uv, mode}, v.sp.shading.to_local(wi),
                                                 v.lobe, v.u_lobe);
    if (!bs) return 0.0;
    p *= double(bs->pdf);
  }
  return p;
}

bool offset_raster(const scene::Scene& scene, const Vec2& raster, double r1, double r2, core::Rng& rng, Vec2& out) {
  const double r = r2 * std::exp(-std::log(r2 / r1) * rng.uniform_double());
  const double phi = 2.0 * kPiD * rng.uniform_double();
  out = Vec2(float(double(raster.x()) + r * std::cos(phi)), float(double(raster.y()) + r * std::sin(phi)));
  const auto& cam = scene.camera();
  return out.x() >= 0.0f && out.y() >= 0.0f && out.x() < float(cam.width()) && out.y() < float(cam.height());
}

Vec3 turn_direction(const Vec3& w, double cos_theta, double phi) {
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const Frame f = Frame::from_normal(w);
  return f.to_world(Vec3(float(sin_theta * std::cos(phi)), float(sin_theta * std::sin(phi)), float(cos_theta)))
      .normalized();
}

bool connection_visible(const scene::Scene& scene, const PathState& y, int s, PathSides& sides) {
  if (s == 0) return true;  // the camera walk reached the light itself
  pathspace::MisConfig unweighted;
  unweighted.unweighted = true;
  pathspace::Connection c;
  return pathspace::connect(scene, sides.light.data(), s, sides.camera.data(), y.depth() + 1 - s, unweighted, c, true);
}

}  // namespace dp::mcmc

namespace dp::mcmc {

ProposalStatus finish_proposal(const scene::Scene& scene, PathState& y, int s, PathSides& sides) {
  const bool valid = evaluate_path(scene, y, sides);
  if (y.nonfinite) return ProposalStatus::nonfinite;
  if (!valid || !(y.inv_c[size_t(s)] > 0.0)) return ProposalStatus::zero;
  return connection_visible(scene, y, s, sides) ? ProposalStatus::ok : ProposalStatus::occluded;
}

}  // namespace dp::mcmc
