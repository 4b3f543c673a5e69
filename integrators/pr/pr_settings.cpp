#include "integrators/pr/pr_settings.h"

#include "core/error.h"
#include "pathspace/classify.h"

namespace dp::integrators {

PrSettings PrSettings::read(Settings& s) {
  PrSettings p;
  p.shift_threshold = pathspace::kDefaultShiftThreshold;
  p.tile = s.get_int("tile", p.tile,
                     "reuse tile size T: every base path is reused by the T x T pixels of its tile "
                     "(the tile grid is offset randomly per iteration)");
  p.rr_depth = s.get_int("rr_depth", p.rr_depth, "Russian roulette only after this many path segments");
  p.nee = s.get_bool("nee", p.nee, "next-event estimation on base and reused paths");
  p.shift_threshold = float(s.get_double("shift_threshold", double(p.shift_threshold),
                                         "BSDF roughness at or below which a vertex is glossy/specular "
                                         "(half-vector copy) instead of connectable (reconnection)"));
  p.hide_emitters = s.get_bool("hide_emitters", p.hide_emitters, "do not show emitters seen directly by the camera");
  if (p.tile < 1 || p.tile > 32) throw ValueError("setting 'tile' must be in [1, 32]", "--set");
  if (p.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  if (!(p.shift_threshold >= 0.0f)) throw ValueError("setting 'shift_threshold' must be >= 0", "--set");
  return p;
}

}  // namespace dp::integrators
