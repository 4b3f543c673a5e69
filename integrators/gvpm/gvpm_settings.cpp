#include "integrators/gvpm/gvpm_settings.h"

#include <cmath>

#include "core/error.h"
#include "integrators/plane/plane_settings.h"
#include "integrators/vpm/vpm_settings.h"

namespace dp::integrators {

GvpmSettings GvpmSettings::read(Settings& s) {
  GvpmSettings g;
  g.read_common(s, 0.0015);
  g.distance_samples = VpmSettings::read_distance_samples(s, g.distance_samples);
  g.read_gradient_keys(s);
  return g;
}

GvpmSettings GvpmSettings::read_gbre(Settings& s) {
  GvpmSettings g;
  g.gather = GvpmGather::beam;
  g.distance_samples = 1;
  g.read_common(s, 0.001);
  g.read_gradient_keys(s);
  return g;
}

GvpmSettings GvpmSettings::read_gbeam(Settings& s) {
  GvpmSettings g;
  g.gather = GvpmGather::beams;
  g.distance_samples = 1;
  g.photons = 20000;  // light paths, as `beam` (beam_settings.h)
  // No manifold walk by default: a Beam-Beam 3D query shifts ~100x more photons than a
  // point query, and on SPOTLIGHT the walks made an iteration 5.3x slower (7.9 vs 1.5 s for
  // 2 iterations at 128^2) for no gain at equal time (bench/RESULTS.md).
  g.manifold = false;
  g.read_common(s, 0.001);
  g.read_gradient_keys(s);
  return g;
}

GvpmSettings GvpmSettings::read_gplane(Settings& s) {
  GvpmSettings g;
  g.gather = GvpmGather::planes;
  g.distance_samples = 1;
  const PlaneSettings p = PlaneSettings::read(s);  // plane's keys and defaults
  static_cast<MediaPhotonSettings&>(g) = p;
  g.plane_piece_scale = p.piece_scale;
  g.read_gradient_keys(s, false);
  return g;
}

void GvpmSettings::read_gradient_keys(Settings& s, bool photon_shift) {
  GvpmSettings& g = *this;
  g.alpha = float(s.get_double("alpha", double(g.alpha),
                               "screened Poisson weight of the primal image, L1 and L2 (Gruson et al. 2018, Sec. 6.1: 0.2)"));
  g.reconstruction = s.get_string("reconstruction", g.reconstruction,
                                  "reconstruction shown as the RGB layer (both are written as layers)", {"l1", "l2"});
  if (photon_shift)
    g.mixed = s.get_bool("mixed_shift", g.mixed,
                         "mixed photon shift (Gruson et al. 2018, Eq. 16: photons in both kernels are reused); "
                         "false: every photon takes the simple shift b + (d' - d) and is reconnected");
  if (!(g.alpha > 0.0f) || !std::isfinite(g.alpha)) throw ValueError("setting 'alpha' must be > 0", "--set");
  if (!photon_shift) return;  // gplane reconnects nothing
  g.manifold = s.get_bool("manifold", g.manifold,
                          "reconnect shifted photons behind purely specular surfaces by a manifold walk "
                          "(Gruson et al. 2018, Sec. 4.3); false: their shifts fail (counted)");
  g.manifold_iterations = int(s.get_int("manifold_iterations", g.manifold_iterations,
                                        "manifold walk iterations per shifted photon (Sec. 6: 5)"));
  g.manifold_relaxed = s.get_bool("manifold_relaxed", g.manifold_relaxed,
                                  "relaxed walk acceptance (Sec. 6): the walk stops once the photon lies in the "
                                  "offset kernel (biased, consistent); false: walk to the shifted photon exactly");
  if (g.manifold_iterations < 1 || g.manifold_iterations > 1000)
    throw ValueError("setting 'manifold_iterations' must be in [1, 1000]", "--set");
}

}  // namespace dp::integrators
