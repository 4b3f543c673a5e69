#include "integrators/vcm/vcm_settings.h"

#include <cmath>

#include "core/error.h"

namespace dp::integrators {

std::string VcmSettings::mode_name(VcmMode m) {
  switch (m) {
    case VcmMode::vcm: return "vcm";
    case VcmMode::bpt: return "bpt";
    case VcmMode::vm: return "vm";
    case VcmMode::ppm: return "ppm";
    case VcmMode::lt: return "lt";
  }
  return "vcm";
}

bool read_adaptive_kernel(Settings& s, bool def) {
  return s.get_bool("adaptive_kernel", def,
                    "shrink the merging radius along the camera subpath, r_t = 0.5^(10 tau(z_(t-1))) r_(t-1) with tau "
                    "the roughness, 1 for diffuse, 0 through Dirac lobes (Sun et al. 2017, Sec. 6), in the merges, "
                    "their shifts and the MIS weights alike");
}

VcmSettings VcmSettings::read(Settings& s) {
  VcmSettings v;
  const std::string mode = s.get_string(
      "mode", "vcm",
      "strategies: vcm (connections + merging), bpt (connections), vm (merging, bidirectional photon mapping), "
      "ppm (merging at the first non-Dirac camera vertex), lt (light tracing)",
      {"vcm", "bpt", "vm", "ppm", "lt"});
  for (VcmMode m : {VcmMode::vcm, VcmMode::bpt, VcmMode::vm, VcmMode::ppm, VcmMode::lt})
    if (mode == mode_name(m)) v.mode = m;
  v.radius = float(s.get_double("radius", v.radius, "initial merging radius, relative to the scene's bounding-sphere radius"));
  v.radius_alpha = float(s.get_double("radius_alpha", v.radius_alpha,
                                      "radius reduction: r_i = r_0 * i^((alpha-1)/2) at iteration i = 1, 2, ... (1 = fixed radius)"));
  v.rr_depth = s.get_int("rr_depth", v.rr_depth, "Russian roulette on each subpath after this many segments");
  const std::string mis = s.get_string("mis", "power", "MIS heuristic over the strategies (Veach 1997, Sec. 9.2)",
                                       {"power", "balance"});
  v.heuristic = mis == "balance" ? pathspace::MisHeuristic::balance : pathspace::MisHeuristic::power;
  v.adaptive_kernel = read_adaptive_kernel(s, v.adaptive_kernel);
  if (!(v.radius > 0.0f) || !std::isfinite(v.radius)) throw ValueError("setting 'radius' must be > 0 (got " + std::to_string(v.radius) + ")", "--set");
  if (!(v.radius_alpha > 0.0f && v.radius_alpha <= 1.0f))
    throw ValueError("setting 'radius_alpha' must be in (0, 1] (got " + std::to_string(v.radius_alpha) + ")", "--set");
  if (v.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  return v;
}

}  // namespace dp::integrators
