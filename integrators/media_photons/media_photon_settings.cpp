#include "integrators/media_photons/media_photon_settings.h"

#include "core/error.h"

namespace dp::integrators {

void MediaPhotonSettings::read_common(Settings& s, double radius_default, const char* photons_doc) {
  radius_scale = radius_default;
  photons = s.get_int("photons", photons,
                      photons_doc ? photons_doc
                                  : "light paths traced per iteration; photons are stored at their medium scattering "
                                    "events (Gruson et al. 2018 use 1M)");
  radius_scale = s.get_double("radius_scale", radius_scale,
                              "first iteration's kernel radius as a fraction of the scene's bounding-box diagonal "
                              "(Gruson et al. 2018, Sec. 6.1: 0.15% for VPM, 0.10% otherwise)");
  radius_alpha = s.get_double("radius_alpha", radius_alpha,
                              "progressive radius reduction: the kernel volume (3D) or area (2D) shrinks by "
                              "(i + alpha) / (i + 1) per iteration (Knaus & Zwicker 2011); 1 keeps the radius");
  rr_depth = s.get_int("rr_depth", rr_depth, "Russian roulette only after this many path segments");
  if (photons < 1) throw ValueError("setting 'photons' must be >= 1", "--set");
  if (!(radius_scale > 0.0)) throw ValueError("setting 'radius_scale' must be > 0", "--set");
  if (!(radius_alpha > 0.0 && radius_alpha <= 1.0)) throw ValueError("setting 'radius_alpha' must be in (0, 1]", "--set");
  if (rr_depth < 1) throw ValueError("setting 'rr_depth' must be >= 1", "--set");
}

}  // namespace dp::integrators
