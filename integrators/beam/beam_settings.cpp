#include "integrators/beam/beam_settings.h"

namespace dp::integrators {

BeamSettings BeamSettings::read(Settings& s) {
  BeamSettings b;
  b.read_common(s, 0.001,
                "light paths traced per iteration; each of their segments inside a scattering medium is stored "
                "as a photon beam (Gruson et al. 2018, Sec. 6.1: 20e3 beams per iteration)");
  const std::string kernel =
      s.get_string("kernel", b.kernel_name(),
                   "3d: Beam-Beam 3D, a point sampled on the beam and the camera chord within r of it "
                   "integrated (Gruson et al. 2018, Sec. 5.2 and 6.1); 1d: Beam x Beam 1D at the closest "
                   "points, K1(u) / sin(theta) (Jarosz et al. 2011)",
                   {"3d", "1d"});
  b.kernel = kernel == "1d" ? BeamKernel::k1d : BeamKernel::k3d;
  return b;
}

}  // namespace dp::integrators
