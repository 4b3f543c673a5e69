#include "integrators/plane/plane_settings.h"

#include "core/error.h"

namespace dp::integrators {

PlaneSettings PlaneSettings::read(Settings& s) {
  PlaneSettings p;
  p.read_common(s, 0.001,
                "light paths traced per iteration; each medium scattering event makes a photon plane, each "
                "segment from a light or surface vertex a photon beam (Gruson et al. 2018, Sec. 6.1: 20e3)");
  p.piece_scale = s.get_double("plane_piece_scale", p.piece_scale,
                               "smallest side of a plane's BVH piece as a fraction of the scene diagonal (at most "
                               "8x8 pieces a plane)");
  if (!(p.piece_scale > 0.0)) throw ValueError("setting 'plane_piece_scale' must be > 0", "--set");
  return p;
}

}  // namespace dp::integrators
