#include "integrators/bre/bre_settings.h"

namespace dp::integrators {

BreSettings BreSettings::read(Settings& s) {
  BreSettings b;
  b.read_common(s, 0.001);
  return b;
}

}  // namespace dp::integrators
