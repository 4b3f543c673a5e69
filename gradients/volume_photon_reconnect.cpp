#include "gradients/volume_photon_reconnect.h"

#include "scene/media/free_flight.h"
#include "scene/media/phase_function.h"

namespace dp::gradients {

float photon_volume_pdf(const MediumParent& parent, const scene::HomogeneousMedium& medium, const Vec3& b,
                        ReconnectFault fault) {
  const Vec3 d = b - parent.a;
  const float t2 = d.squaredNorm();
  if (!(t2 > 0.0f)) return 0.0f;
  const float t = std::sqrt(t2);
  const float phase = scene::HenyeyGreenstein(medium.phase).pdf(parent.w_in, d / t);
  // dV = t^2 dw dt (Eq. 4's G at two medium vertices).
  return phase * scene::free_flight_pdf(medium, t) / (fault == ReconnectFault::no_volume_factor ? 1.0f : t2);
}

Rgb photon_edge_throughput(const MediumParent& parent, const scene::HomogeneousMedium& medium, const Vec3& b,
                           ReconnectFault fault) {
  const Vec3 d = b - parent.a;
  const float t2 = d.squaredNorm();
  if (!(t2 > 0.0f)) return Rgb::Zero();
  const float t = std::sqrt(t2);
  const float phase = scene::HenyeyGreenstein(medium.phase).eval(parent.w_in, d / t);
  // rho_p(a) tau(a, b) G(a, b) sigma_s(b) (Eqs. 2-4).
  return phase * scene::transmittance(medium, t) * medium.sigma_s / (fault == ReconnectFault::no_volume_factor ? 1.0f : t2);
}

}  // namespace dp::gradients
