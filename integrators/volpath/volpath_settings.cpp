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
  v.equiangular = s.get_bool("equiangular", v.equiangular,
                             "next-event estimation also at one point per camera-path segment in a homogeneous "
                             "medium drawn by equiangular sampling toward a light point, MIS-weighted with "
                             "free-flight NEE and phase sampling (Kulla & Fajardo 2012; needs nee)");
  v.mnee = s.get_bool("mnee", v.mnee,
                      "manifold next-event estimation: light seen through refractive surfaces (glass) is sampled "
                      "by a manifold walk from medium and surface vertices, MIS-weighted with BSDF/phase sampling "
                      "(scenes with media, area lights; Hanika et al. 2015)");
  v.mnee_max_chain = s.get_int("mnee_max_chain", v.mnee_max_chain,
                               "most refractive boundaries between a vertex and the light that MNEE solves for");
  v.mnee_shapes = s.get_bool("mnee_shapes", v.mnee_shapes,
                             "MNEE also solves chains seeded at each purely specular shape (scenes with at most 4): "
                             "one reflection off it, and two refractions through it where the straight segment to "
                             "the light misses it");
  v.mnee_seeds = s.get_int("mnee_seeds", v.mnee_seeds,
                            "with mnee_scan=0: seed directions per MNEE connection, the straight line, then pairs "
                            "across the first refracting shape; every distinct solution found is added");
  v.mnee_scan = s.get_int("mnee_scan", v.mnee_scan,
                           "MNEE seeds from a scan: this many directions across the refracting shape are traced "
                           "through the chain to the light's plane, and each sign change of the miss (or a "
                           "near-zero minimum, a caustic fold) seeds a walk (0: the fixed seeds of mnee_seeds)");
  v.mnee_iterations = s.get_int("mnee_iterations", v.mnee_iterations, "Newton steps of an MNEE manifold walk");
  v.light_tracing = s.get_bool("light_tracing", v.light_tracing,
                               "with MNEE: one light path per camera sample through glass, joined to the camera "
                               "(splatted) and to every camera-path vertex, MIS-weighted with MNEE and BSDF sampling: "
                               "for small lights seen through glass, whose MNEE estimates are heavy-tailed near the "
                               "caustic's folds (homogeneous media, area lights)");
  if (v.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  if (v.mnee_max_chain < 1 || v.mnee_max_chain > 8)
    throw ValueError("setting 'mnee_max_chain' must be in 1 .. 8", "--set");
  if (v.mnee_seeds < 1 || v.mnee_seeds > 9) throw ValueError("setting 'mnee_seeds' must be in 1 .. 9", "--set");
  if (v.mnee_scan != 0 && (v.mnee_scan < 3 || v.mnee_scan > 64))
    throw ValueError("setting 'mnee_scan' must be 0 or in 3 .. 64", "--set");
  if (v.mnee_iterations < 1) throw ValueError("setting 'mnee_iterations' must be >= 1", "--set");
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
