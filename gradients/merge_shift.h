// G-VCM's vertex-merging shift at the camera subpath's first connectable vertex z_b
// (Sun et al. 2017, Sec. 4, case 2; docs/gvcm_plan.md). The base merged the photon
// y_j = light[j] (within the kernel radius r of z_b); base and offset kernels differ, so
// the offset is a physically valid path built as a probabilistic connection: the light
// subpath light[0 .. j-1] rejoined at the offset camera vertex z_b^off (light_rejoin.h:
// a reconnection from a connectable y_{j-1}, Eq. 18, or the manifold walk of the specular
// chain before the photon, pinned at its last connectable vertex y_d, Eq. 19-20), then the
// offset camera prefix z_{b-1}^off .. z_0 (bidir_shift.h).
//
//   value = f(x_off) / p_off(x*) * pi r^2
//         = throughput(z_b^off) * f(z_b^off; wi camera side, wo light side) * beta_off(z_b),
// throughput = the light side's f over the base's density of light[0 .. j] including the
// photon's own arrival density (area measure, RR as the base; light_rejoin.h), beta_off =
// the offset camera prefix's f(T z)|T'| / p(z) (= 1 / (p(z) J_z), Eq. 18). pi r^2 and VCM's
// light-path count N are the caller's kernel normalisation, as for the base merge
// (base value: photon beta * f(z_b; wi, photon wi) * beta(z_b)). For ideal specular chains
// the paper's half-vector Jacobian J_y is 1; the chain's G'/G enters through the rejoin's
// area_ratio. The photon's own position is not preserved by the map (the paper: a bias
// that vanishes as r -> 0).
#pragma once

#include "gradients/bidir_shift.h"

namespace dp::gradients {

struct MergeShift : LightRejoin {  // `light`: the offset light subpath, ending at z_b^off
  Rgb value = Rgb::Zero();          // (header)
};

// light[0 .. j]: the photon's light subpath (j >= 1); `camera`: the base camera subpath and
// `shift` its shift (shift.b = the merge vertex's index, shift.path[b] = z_b^off). Both z_b
// and z_b^off must have a smooth lobe (a merge evaluates the BSDF there), so the condition
// is the same for the reverse shift.
bool shift_merge(const scene::Scene& scene, const pathspace::BidirVertex* light, int j,
                 const std::vector<pathspace::BidirVertex>& camera, const CameraSubpathShift& shift,
                 const BidirShiftOptions& options, MergeShift& out);

}  // namespace dp::gradients
