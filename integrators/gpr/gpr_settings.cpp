#include "integrators/gpr/gpr_settings.h"

#include <cmath>

#include "core/error.h"
#include "reconstruct/problem.h"

namespace dp::integrators {

GprSettings GprSettings::read(Settings& s) {
  GprSettings g;
  g.reuse = PrSettings::read(s);  // tile, rr_depth, nee, shift_threshold, hide_emitters
  g.alpha = reconstruct::kDefaultAlpha;
  g.rr_delta = s.get_double("rr_delta", g.rr_delta,
                            "proportional Russian roulette on base paths (Bauszat 2017, Sec. 3.3): a base path "
                            "survives with q = max(min(1, luminance / rr_delta), rr_min) and is then reused "
                            "weighted 1/q; 0 turns it off");
  g.rr_min = s.get_double("rr_min", g.rr_min,
                          "floor q_min of the base-path survival probability; > 0, since a base path of zero "
                          "contribution may have shifted paths that carry light");
  g.jitter = s.get_bool("jitter", g.jitter, "offset the tile grid randomly per iteration (no tile edge persists)");
  g.early_out = s.get_bool("early_out", g.early_out,
                           "do not shift the part of a base path behind a reconnection vertex that carries no "
                           "light whatever the direction it is reached from (no emitter, no visible light sample)");
  g.alpha = float(s.get_double("alpha", double(g.alpha), "screened Poisson weight of the primal image (L1 and L2)"));
  g.reconstruction = s.get_string("reconstruction", g.reconstruction,
                                  "reconstruction shown as the RGB layer (both are written as layers)", {"l1", "l2"});
  if (!(g.rr_delta >= 0.0) || !std::isfinite(g.rr_delta)) throw ValueError("setting 'rr_delta' must be >= 0", "--set");
  if (!(g.rr_min > 0.0 && g.rr_min <= 1.0)) throw ValueError("setting 'rr_min' must be in (0, 1]", "--set");
  if (!(g.alpha > 0.0f) || !std::isfinite(g.alpha)) throw ValueError("setting 'alpha' must be > 0", "--set");
  return g;
}

}  // namespace dp::integrators
