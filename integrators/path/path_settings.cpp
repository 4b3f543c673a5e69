#include "integrators/path/path_settings.h"

#include "core/error.h"

namespace dp::integrators {

PathSettings PathSettings::read(Settings& s) {
  PathSettings p;
  p.rr_depth = s.get_int("rr_depth", p.rr_depth, "Russian roulette only after this many path segments");
  p.nee = s.get_bool("nee", p.nee, "next-event estimation with power-heuristic MIS (false: BSDF sampling only)");
  p.hide_emitters = s.get_bool("hide_emitters", p.hide_emitters, "do not show emitters seen directly by the camera");
  if (p.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  return p;
}

}  // namespace dp::integrators
