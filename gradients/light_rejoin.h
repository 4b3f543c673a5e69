// The end of a light subpath moved to a new surface vertex T, shared by G-BDPT's
// light-tracing shift (T = the offset's primary hit y_1; bidir_shift.h) and G-VCM's
// merging shift (T = the offset camera vertex z_b^off; merge_shift.h). The base light
// subpath light[0 .. end] leaves its last smooth vertex z = light[e] toward light[e+1];
// the offset leaves z toward T instead:
//  * e = end - 1 and z connectable: a reconnection z -> T (visibility tested from T);
//  * light[end-1] .. light[e+1] a specular chain (bidir_chain.h) ending at z: the chain
//    pinned at z walked so that it ends at T (the light walk's side: importance).
// `throughput` is the offset light subpath's throughput arriving at T in area measure over
// the base's sampling density of light[0 .. end] (area measure, RR as the base):
//   beta(z) f_z(w'_z) |cos'_z| [Dirac factors rho'/(p rr)] area_ratio / (pdf_out(z) rr(z)),
// area_ratio = [d w_z / dA(T)] / [d w_z / dA(light[end])] (bidir_chain.h's start_density
// for a walked chain; |cos_T| d^2 / (|cos_end| d_T^2) for a reconnection). It does not
// include any factor of T itself (its BSDF toward the camera side).
#pragma once

#include <vector>

#include "gradients/bidir_chain.h"

namespace dp::gradients {

struct LightRejoin {
  std::vector<pathspace::BidirVertex> light;  // light[0 .. e], the walked chain, T (densities re-derived)
  ShiftStatus status = ShiftStatus::ok;
  int e = -1;                   // light[e] = z, the last shared vertex
  bool specular_chain = false;  // failed because light[end-1] starts a chain that cannot be walked
  bool walked = false;          // a chain walk was attempted (chain.stats counts it)
  BidirChainWalk chain;
  Rgb throughput = Rgb::Zero();
  double area_ratio = 1;        // (header); includes a JacobianFault::unit_manifold defect
  double direction_ratio = 1;   // pdf(z -> offset successor) / pdf(z -> base successor), solid angle
};

// `light` has at least end + 1 vertices, end >= 1; `target` is a surface vertex with a
// smooth lobe (wi unused: re-derived toward its light-side neighbour).
bool rejoin_light_subpath(const scene::Scene& scene, const pathspace::BidirVertex* light, int end,
                          const pathspace::BidirVertex& target, const BidirShiftOptions& options, LightRejoin& out);

}  // namespace dp::gradients
