#include "integrators/gbdpt/gbdpt_settings.h"

#include <cmath>

#include "core/error.h"
#include "reconstruct/problem.h"

namespace dp::integrators {

GbdptSettings GbdptSettings::read(Settings& s) {
  GbdptSettings g;
  g.alpha = reconstruct::kDefaultAlpha;
  g.rr_depth = s.get_int("rr_depth", g.rr_depth, "Russian roulette on each subpath after this many segments");
  const std::string mis = s.get_string("mis", "power",
                                       "MIS heuristic of the primal over the s/t strategies (the gradients always use "
                                       "the balance heuristic over both pixels' strategies, Manzi et al. 2015)",
                                       {"power", "balance"});
  g.mis.heuristic = mis == "balance" ? pathspace::MisHeuristic::balance : pathspace::MisHeuristic::power;
  g.alpha = float(s.get_double("alpha", double(g.alpha), "screened Poisson weight of the primal image (L1 and L2)"));
  g.reconstruction = s.get_string("reconstruction", g.reconstruction,
                                  "reconstruction shown as the RGB layer (both are written as layers)", {"l1", "l2"});
  g.primal = s.get_string("primal", g.primal,
                          "primal image: pairs (every shifted pair's estimates of both pixels, balance-weighted, "
                          "as G-PT) or bdpt (the plain BDPT estimate with the `mis` heuristic, as Manzi et al. 2015)",
                          {"pairs", "bdpt"});
  g.manifold = s.get_bool("manifold", g.manifold,
                          "walk specular chains b..c of the shift (Manzi et al. 2015, Sec. 4: the chain pinned at "
                          "its end c walked to the offset's b); false: such shifts fail (T_0 fallback)");
  if (g.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  if (!(g.alpha > 0.0f) || !std::isfinite(g.alpha)) throw ValueError("setting 'alpha' must be > 0", "--set");
  return g;
}

}  // namespace dp::integrators
