#include "integrators/gpm/gpm_settings.h"

namespace dp::integrators {

GpmSettings GpmSettings::read(Settings& s) {
  GpmSettings g;
  g.read_common(s,
                "merging radius at the first connectable camera vertex z_b, in pixel footprints (the disk whose "
                "projection covers one pixel, per camera path; Sun et al. 2017, Sec. 6)");
  g.primal = s.get_string("primal", g.primal,
                          "primal image: pairs (every shifted pair's estimates of both pixels, MIS-weighted, as "
                          "G-PT) or ppm (the plain photon-mapping estimate of the base pixel)",
                          {"pairs", "ppm"});
  return g;
}

}  // namespace dp::integrators
