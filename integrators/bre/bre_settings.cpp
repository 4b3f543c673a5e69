#include "integrators/bre/bre_settings.h"

namespace dp::integrators {

BreSettings BreSettings::read(Settings& s) {
  BreSettings b;
  b.read_common(s, 0.001);
  b.kernel_dim = s.get_string("kernel", "2d",
                              "2d: the beam radiance estimate's 2D kernel across the camera beam (Jarosz et al. 2008); "
                              "3d: each photon's 3D kernel integrated along the camera segment (Point-Beam 3D, the "
                              "primal of gbre; Gruson et al. 2018, Sec. 5.1)",
                              {"2d", "3d"}) == "3d"
                     ? 3
                     : 2;
  return b;
}

}  // namespace dp::integrators
