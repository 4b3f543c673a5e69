#include "integrators/volpath/volpath_settings.h"

#include "core/error.h"

namespace dp::integrators {

VolpathSettings VolpathSettings::read(Settings& s) {
  VolpathSettings v;
  v.rr_depth = s.get_int("rr_depth", v.rr_depth, "Russian roulette only after this many path segments");
  v.nee = s.get_bool("nee", v.nee,
                     "next-event estimation at surface and medium vertices, transmittance along the shadow ray, "
                     "power-heuristic MIS with BSDF/phase sampling (false: BSDF and phase sampling only)");
  v.hide_emitters = s.get_bool("hide_emitters", v.hide_emitters, "do not show emitters seen directly by the camera");
  if (v.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  return v;
}

VolpathSettings VolpathSettings::from_path(const PathSettings& p) {
  VolpathSettings v;
  v.rr_depth = p.rr_depth;
  v.nee = p.nee;
  v.hide_emitters = p.hide_emitters;
  return v;
}

}  // namespace dp::integrators
