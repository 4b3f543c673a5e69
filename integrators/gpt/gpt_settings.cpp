#include "integrators/gpt/gpt_settings.h"

#include <cmath>

#include "core/error.h"
#include "pathspace/classify.h"
#include "reconstruct/problem.h"

namespace dp::integrators {

GptSettings GptSettings::read(Settings& s) {
  GptSettings g;
  g.shift_threshold = pathspace::kDefaultShiftThreshold;
  g.alpha = reconstruct::kDefaultAlpha;
  g.rr_depth = s.get_int("rr_depth", g.rr_depth, "Russian roulette only after this many path segments");
  g.nee = s.get_bool("nee", g.nee, "next-event estimation on base and offset paths (power-heuristic MIS)");
  g.shift_threshold = float(s.get_double("shift_threshold", double(g.shift_threshold),
                                         "BSDF roughness at or below which a vertex is glossy/specular "
                                         "(half-vector copy) instead of connectable (reconnection)"));
  g.alpha = float(s.get_double("alpha", double(g.alpha), "screened Poisson weight of the primal image (L1 and L2)"));
  g.reconstruction = s.get_string("reconstruction", g.reconstruction,
                                  "reconstruction shown as the RGB layer (both are written as layers)", {"l1", "l2"});
  g.shift = s.get_string("shift", g.shift,
                         "shift mapping: reconnection (the G-PT hybrid shift, Kettunen 2015) or manifold "
                         "(the hybrid shift plus manifold walks through specular chains ending at a "
                         "connectable vertex, so caustic offsets rejoin the base; Jakob & Marschner 2012)",
                         {"reconnection", "manifold"});
  g.manifold_chains = s.get_string("manifold_chains", g.manifold_chains,
                                   "shift=manifold: which specular chains are walked -- emitter (chains ending on an "
                                   "emitter: caustics) or all (every chain ending on a connectable vertex)",
                                   {"emitter", "all"});
  g.manifold_walk = s.get_string("manifold_walk", g.manifold_walk,
                                 "shift=manifold: fallback (walk a chain only where the half-vector copy leaves "
                                 "the base's shapes, e.g. misses the light) or always (walk every such chain)",
                                 {"fallback", "always"});
  if (g.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  if (!(g.shift_threshold >= 0.0f)) throw ValueError("setting 'shift_threshold' must be >= 0", "--set");
  if (!(g.alpha > 0.0f) || !std::isfinite(g.alpha)) throw ValueError("setting 'alpha' must be > 0", "--set");
  return g;
}

}  // namespace dp::integrators
