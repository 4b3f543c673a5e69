#include "integrators/photon_gradient_settings.h"

#include <cmath>

#include "core/error.h"

namespace dp::integrators {

void PhotonGradientSettings::read_common(Settings& s, const std::string& radius_doc) {
  radius_scale = float(s.get_double("radius_scale", radius_scale, radius_doc));
  radius_alpha = float(s.get_double("radius_alpha", radius_alpha,
                                    "radius reduction: r_i = r_1 * i^((alpha-1)/2) at iteration i = 1, 2, ... "
                                    "(1 = fixed radius; the paper's runs: 0.9)"));
  rr_depth = s.get_int("rr_depth", rr_depth, "Russian roulette on each subpath after this many segments");
  const std::string mis = s.get_string("mis", "power",
                                       "gradient MIS over the active and passive strategies (Sun et al. 2017, Eq. "
                                       "21-23): power (beta = 2) or balance (beta = 1)",
                                       {"power", "balance"});
  heuristic = mis == "balance" ? pathspace::MisHeuristic::balance : pathspace::MisHeuristic::power;
  alpha = float(s.get_double("alpha", double(alpha), "screened Poisson weight of the primal image (L1 and L2)"));
  reconstruction = s.get_string("reconstruction", reconstruction,
                                "reconstruction shown as the RGB layer (both are written as layers)", {"l1", "l2"});
  manifold = s.get_bool("manifold", manifold,
                        "walk specular chains: the camera side's b..c (Manzi et al. 2015) and a photon's chain to the "
                        "offset's z_b (Sun et al. 2017, Eq. 19-20); false: such shifts fail (T_0 fallback)");
  if (!(radius_scale > 0.0f) || !std::isfinite(radius_scale))
    throw ValueError("setting 'radius_scale' must be > 0 (got " + std::to_string(radius_scale) + ")", "--set");
  if (!(radius_alpha > 0.0f && radius_alpha <= 1.0f))
    throw ValueError("setting 'radius_alpha' must be in (0, 1] (got " + std::to_string(radius_alpha) + ")", "--set");
  if (rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  if (!(alpha > 0.0f) || !std::isfinite(alpha)) throw ValueError("setting 'alpha' must be > 0", "--set");
}

}  // namespace dp::integrators
