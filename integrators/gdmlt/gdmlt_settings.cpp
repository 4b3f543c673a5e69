#include "integrators/gdmlt/gdmlt_settings.h"

#include <cmath>

#include "core/error.h"
#include "reconstruct/problem.h"

namespace dp::integrators {

GdmltSettings GdmltSettings::read(Settings& s) {
  GdmltSettings g;
  g.alpha = reconstruct::kDefaultAlpha;
  g.kernel = s.get_string("kernel", g.kernel,
                          "gradient kernel: adaptive (structure-adaptive pairs from a feature pass: the n most "
                          "similar pixels of a window by the Eq. 7 affinity, Manzi 2014 Sec. 3.5) or standard "
                          "(forward differences to the 4 neighbours, Lehtinen 2013)",
                          {"standard", "adaptive"});
  g.feature_spp = s.get_int("feature_spp", g.feature_spp,
                            "kernel=adaptive: jittered primary rays per pixel of the feature pass (normal, albedo, depth)");
  g.affinity.window = s.get_int("adaptive_window", g.affinity.window,
                                "kernel=adaptive: side of the square window searched for partners (odd, >= 3)");
  g.symmetric_weight = s.get_double(
      "symmetric_weight", g.symmetric_weight,
      "kernel=adaptive: weight of each of a symmetric pair's two rows in the Poisson solve; 1 as in the paper "
      "(the pair then counts twice against alpha's screening), 0.5 screens like the standard kernel");
  g.affinity.neighbours = s.get_int("adaptive_neighbours", g.affinity.neighbours,
                                    "kernel=adaptive: n, partners chosen per pixel");
  g.shift = s.get_string("shift", g.shift,
                         "T_1: manifold (specular chains re-solved by manifold walks, reconnection at the "
                         "first diffuse pair; Lehtinen 2013), reconnection (G-PT's hybrid shift) or identity "
                         "(T_0 only: gradients become finite differences of the primal)",
                         {"manifold", "reconnection", "identity"});
  g.shift_threshold = float(s.get_double("shift_threshold", double(g.shift_threshold),
                                         "BSDF roughness at or below which a vertex is glossy/specular"));
  g.mwgi = s.get_bool("mwgi", g.mwgi, "multiple weighted gradient integrals: fall back to T_0 where the "
                                      "contributions of base and offset differ by more than mwgi_threshold (Eq. 6)");
  g.mwgi_threshold = s.get_double("mwgi_threshold", g.mwgi_threshold, "t of Manzi 2014 Eq. 6");
  g.incmw = s.get_bool("incmw", g.incmw,
                       "incremental manifold walk (Sec. 3.4): at the first diffuse vertex of the shift, the next "
                       "vertex is declared specular and moved by a manifold walk where the screen-space ambient "
                       "occlusion of both base and offset exceeds ao_threshold (one declared vertex)");
  g.ao_threshold = s.get_double("ao_threshold", g.ao_threshold, "incmw: AO coefficient above which a vertex is declared");
  g.ao_radius = s.get_double("ao_radius", g.ao_radius,
                             "incmw: AO ray length as a fraction of the image size, projected at the hit's depth");
  g.ao_rays = s.get_int("ao_rays", g.ao_rays, "incmw: cosine-distributed AO rays per pixel");
  g.alpha = float(s.get_double("alpha", double(g.alpha),
                               "weight of the primal in the target f(z) and in the screened Poisson solve"));
  g.reconstruction = s.get_string("reconstruction", g.reconstruction,
                                  "reconstruction shown as the RGB layer (both are written as layers)", {"l1", "l2"});
  g.mutations = s.get_string("mutations", g.mutations,
                             "proposals for x: pss (primary-sample-space small/large steps) or path (path-space "
                             "mutations of memlt on states (x, j), G-BDPT's shift as T_1; incmw does not apply)",
                             {"pss", "path"});
  if (g.mutations == "path") {
    g.path_mutations.read(s);
    g.candidates = s.get_int("candidates", g.candidates,
                             "mutations=path: seeder paths (with their neighbour) estimating the target's "
                             "normalisation b_g and resampled for the chains' start states");
    if (g.candidates < 1) throw ValueError("setting 'candidates' must be >= 1", "--set");
  }
  g.large_step_prob = s.get_double("large_step_prob", g.large_step_prob, "probability of a large step");
  g.bootstrap = s.get_int("bootstrap", int(g.bootstrap), "independent samples estimating b and seeding the chains");
  g.large_step_b = s.get_bool("large_step_b", g.large_step_b, "refine b with every large step's f");
  g.chains = s.get_int("chains", g.chains, "independent Markov chains (0: 4 per thread; 16 per part for --part/--mpi)");
  g.rr_depth = s.get_int("rr_depth", g.rr_depth, "Russian roulette only after this many path segments");
  g.nee = s.get_bool("nee", g.nee, "next-event estimation with power-heuristic MIS");
  g.direct_spp = s.get_int("direct_spp", g.direct_spp,
                           "samples per pixel of the direct pass (paths of at most 2 segments, path tracer), added "
                           "after reconstruction as in the paper; 0 = auto: interleaved with the chains, one "
                           "sample per pixel per mutation per pixel (--spp and --time)");
  if (!(g.symmetric_weight > 0.0) || !std::isfinite(g.symmetric_weight))
    throw ValueError("setting 'symmetric_weight' must be > 0", "--set");
  if (g.feature_spp < 1) throw ValueError("setting 'feature_spp' must be >= 1", "--set");
  if (g.affinity.window < 3 || g.affinity.window % 2 == 0)
    throw ValueError("setting 'adaptive_window' must be odd and >= 3", "--set");
  if (g.affinity.neighbours < 1) throw ValueError("setting 'adaptive_neighbours' must be >= 1", "--set");
  if (!(g.ao_threshold >= 0.0 && g.ao_threshold <= 1.0)) throw ValueError("setting 'ao_threshold' must be in [0, 1]", "--set");
  if (!(g.ao_radius > 0.0 && g.ao_radius < 1.0)) throw ValueError("setting 'ao_radius' must be in (0, 1)", "--set");
  if (g.ao_rays < 1) throw ValueError("setting 'ao_rays' must be >= 1", "--set");
  if (!(g.large_step_prob > 0.0 && g.large_step_prob <= 1.0))
    throw ValueError("setting 'large_step_prob' must be in (0, 1]", "--set");
  if (g.bootstrap < 1) throw ValueError("setting 'bootstrap' must be >= 1", "--set");
  if (g.chains < 0) throw ValueError("setting 'chains' must be >= 0", "--set");
  if (g.rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
  if (g.direct_spp < 0) throw ValueError("setting 'direct_spp' must be >= 0 (0 = auto)", "--set");
  if (!(g.mwgi_threshold > 1.0)) throw ValueError("setting 'mwgi_threshold' must be > 1", "--set");
  if (!(g.alpha > 0.0f) || !std::isfinite(g.alpha)) throw ValueError("setting 'alpha' must be > 0", "--set");
  if (!(g.shift_threshold >= 0.0f)) throw ValueError("setting 'shift_threshold' must be >= 0", "--set");
  return g;
}

}  // namespace dp::integrators
