#include "integrators/gvcm/gvcm_settings.h"

namespace dp::integrators {

GvcmSettings GvcmSettings::read(Settings& s) {
  GvcmSettings g;
  const std::string mode = s.get_string("mode", "vcm",
                                        "strategies: vcm (connections and merges) or bpt (connections only, VCM's "
                                        "loop without photons: no merging pass runs)",
                                        {"vcm", "bpt"});
  g.merging = mode == "vcm";
  g.read_common(s,
                "merging radius in pixel footprints: the median over the image of the disk at the first "
                "connectable camera vertex whose projection covers one pixel (Sun et al. 2017, Sec. 6), one "
                "global radius per iteration");
  g.primal = s.get_string("primal", g.primal,
                          "primal image: pairs (every shifted pair's estimates of both pixels, MIS-weighted, as "
                          "G-PT) or vcm (the plain VCM estimate of the base pixel)",
                          {"pairs", "vcm"});
  return g;
}

}  // namespace dp::integrators
