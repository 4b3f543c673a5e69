#include "integrators/gvcm/gvcm_settings.h"

#include <cmath>

#include "core/error.h"
#include "integrators/vcm/vcm_settings.h"

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
  g.roughness_threshold = float(s.get_double(
      "roughness_threshold", g.roughness_threshold,
      "no merging at vertices whose roughness (microfacet alpha) is below this: near-specular surfaces are left to "
      "connections, consistently in the MIS weights (Sun et al. 2017: 0.01); 0 = merge at every non-Dirac vertex"));
  g.adaptive_kernel = read_adaptive_kernel(s, g.adaptive_kernel);
  if (!(g.roughness_threshold >= 0.0f) || !std::isfinite(g.roughness_threshold))
    throw ValueError("setting 'roughness_threshold' must be >= 0", "--set");
  return g;
}

}  // namespace dp::integrators
