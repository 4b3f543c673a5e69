#include "integrators/gpr/early_out.h"

namespace dp::integrators {

using pathspace::Path;
using pathspace::Vertex;
using pathspace::VertexKind;

namespace {
bool live_light(const pathspace::LightSample& l) {
  return l.valid && l.pdf > 0.0 && l.visible && !is_black(l.radiance);
}

bool dark(const Path& base, int j) {
  const Vertex& v = base[j];
  if (v.kind == VertexKind::environment) return is_black(v.emission);
  if (v.kind != VertexKind::surface || v.hit.emitter) return false;
  return !live_light(base.nee[size_t(j)]);
}
}  // namespace

int live_prefix(const Path& base) {
  const int n = base.size();
  // Scan from the end: `dark_from` is the smallest j such that x_j .. x_{n-1} are dark.
  int dark_from = n;
  while (dark_from > 2 && dark(base, dark_from - 1)) --dark_from;
  for (int a = dark_from; a < n; ++a) {
    const Vertex& prev = base[a - 1];
    const bool reconnects = prev.is_surface() && prev.connectable && prev.continued() && !prev.delta_lobe() &&
                            base[a].connectable;
    if (reconnects) return a;
  }
  return n;
}

bool can_contribute(const Path& base) {
  if (base.size() <= 1) return false;
  if (base.size() > 2) return true;
  return live_light(base.nee[1]);
}

}  // namespace dp::integrators
