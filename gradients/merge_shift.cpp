#include "gradients/merge_shift.h"

#include "gradients/bidir_helpers.h"

namespace dp::gradients {

using namespace bidir;

bool shift_merge(const scene::Scene& scene, const BidirVertex* light, int j, const std::vector<BidirVertex>& camera,
                 const CameraSubpathShift& shift, const BidirShiftOptions& options, MergeShift& out) {
  out.value = Rgb::Zero();
  const int b = shift.b;
  if (j < 1 || b < 1 || shift.alive <= b || int(camera.size()) <= b || !smooth_surface(camera[size_t(b)])) {
    out.light.clear();
    out.status = ShiftStatus::not_invertible;
    return false;
  }
  const BidirVertex& zb = shift.path[size_t(b)];
  if (!smooth_surface(zb)) {
    out.light.clear();
    out.status = ShiftStatus::not_invertible;
    return false;
  }
  if (!rejoin_light_subpath(scene, light, j, zb, options, out)) return false;
  // z_b^off's BSDF between its camera-side direction and its new light-side neighbour
  // (radiance mode; no cosine: the rejoin's area factor holds it).
  const Vec3 wo = out.light.back().wi;
  const Vec3 wi_l = zb.sp.shading.to_local(zb.wi), wo_l = zb.sp.shading.to_local(wo);
  if (!(zb.sp.ng.dot(zb.wi) * wi_l.z() > 0.0f) || !(zb.sp.ng.dot(wo) * wo_l.z() > 0.0f)) {
    out.status = ShiftStatus::zero_contribution;
    return false;
  }
  const Rgb f = zb.bsdf->eval(scene::BsdfContext{zb.sp.uv, scene::TransportMode::radiance}, wi_l, wo_l);
  out.value = out.throughput * f * zb.beta;
  if (is_black(out.value)) {
    out.status = ShiftStatus::zero_contribution;
    return false;
  }
  out.status = ShiftStatus::ok;
  return true;
}

}  // namespace dp::gradients
