#include "integrators/vpm/vpm_settings.h"

#include "core/error.h"

namespace dp::integrators {

int VpmSettings::read_distance_samples(Settings& s, int fallback) {
  const int n = s.get_int("distance_samples", fallback,
                          "stratified gather distances per camera segment inside a medium, each a point query "
                          "(Gruson et al. 2018, Eq. 14 and Sec. 6.1: 40)");
  if (n < 1) throw ValueError("setting 'distance_samples' must be >= 1", "--set");
  return n;
}

VpmSettings VpmSettings::read(Settings& s) {
  VpmSettings v;
  v.read_common(s, 0.0015);
  v.distance_samples = read_distance_samples(s, v.distance_samples);
  return v;
}

}  // namespace dp::integrators
