#include "integrators/gvcm/gvcm_settings.h"

#include <cmath>

#include "core/error.h"

namespace dp::integrators {

GvcmSettings GvcmSettings::read(Settings& s) {
  GvcmSettings g;
  const std::string mode = s.get_string("mode", "vcm",
                                        "strategies: vcm (connections and merges) or bpt (connections only, VCM's "
                                        "loop without photons: no merging pass runs)",
                                        {"vcm", "bpt"});
  g.merging = mode == "vcm";
  g.radius_scale = float(s.get_double("radius_scale", g.radius_scale,
                                      "merging radius in pixel footprints: the median over the image of the disk at "
                                      "the first connectable camera vertex whose projection covers one pixel "
                                      "(Sun et al. 2017, Sec. 6), one global radius per iteration"));
  g.radius_alpha = float(s.get_double("radius_alpha", g.radius_alpha,
                                      "radius reduction: r_i = r_1 * i^((alpha-1)/2) at iteration i = 1, 2, ... "
                                      "(1 = fixed radius; the paper's runs: 0.9)"));
  g.rr_depth = s.get_int("rr_depth", g.rr_depth, "Russian roulette on each subpath after this many segments");
  const std::string mis = s.get_string("mis", "power",
                                       "MIS over connections and merges, active and passive (Sun et al. 2017, Eq. "
                                       "21-23): power (beta = 2) or balance (beta = 1)",
                                       {"power", "balance"});
  g.heuristic = mis == "balance" ? pathspace::MisHeuristic::balance : pathspace::MisHeuristic::power;
  g.alpha = float(s.get_double("alpha", double(g.alpha), "screened Poisson weight of the primal image (L1 and L2)"));
  g.reconstruction = s.get_string("reconstruction", g.reconstruction,
                                  "reconstruction shown as the RGB layer (both are written as layers)", {"l1", "l2"});
  g.primal = s.get_string("primal", g.primal,
                          "primal image: pairs (every shifted pair's estimates of both pixels, MIS-weighted, as "
                          "G-PT) or vcm (the plain VCM estimate of the base pixel)",
                          {"pairs", "vcm"});
  g.manifold = s.get_bool("manifold", g.manifold,
                          "walk specular chains: the camera side's b..c (Manzi et al. 2015) and a photon's chain to "
                          "the offset's z_b (Sun et al. 2017, Eq. 19-20); false: such shifts fail (T_0 fallback)");
  if (!(g.radius_scale > 0.0f) || !std::isfinite(g.radius_scale))
    throw ValueError("setting 'radius_scale' must be > 0 (got " + std::to_string(g.radius_scale) + ")", "--set");
  if (!(g.radius_alpha > 0.0f && g.radius_alpha <= 1.0f))
    throw ValueError("setting 'radius_alpha' must be in (0, 1] (got " + std::to_string(g.radius_alpha) + ")", "--set");
  if (g.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  if (!(g.alpha > 0.0f) || !std::isfinite(g.alpha)) throw ValueError("setting 'alpha' must be > 0", "--set");
  return g;
}

}  // namespace dp::integrators
