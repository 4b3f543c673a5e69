#include "integrators/vpm/vpm_settings.h"

#include "core/error.h"

namespace dp::integrators {

VpmSettings VpmSettings::read(Settings& s) {
  VpmSettings v;
  v.read_common(s, 0.0015);
  v.distance_samples = s.get_int("distance_samples", v.distance_samples,
                                 "stratified gather distances per camera segment inside a medium, each a point query "
                                 "(Gruson et al. 2018, Eq. 14 and Sec. 6.1: 40)");
  if (v.distance_samples < 1) throw ValueError("setting 'distance_samples' must be >= 1", "--set");
  return v;
}

}  // namespace dp::integrators
