#include "mcmc/path_gradient.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "pathspace/bidir_connect.h"

namespace dp::mcmc {

PathGradientFactor::PathGradientFactor(const scene::Scene& scene, const kernels_adaptive::PairKernel& kernel,
                                       const PathGradientOptions& options)
    : m_scene(scene), m_kernel(kernel), m_opt(options), m_w(scene.camera().width()), m_h(scene.camera().height()) {
  if (kernel.width != m_w || kernel.height != m_h || kernel.offsets.size() != size_t(m_w) * size_t(m_h) + 1)
    throw ValueError("gdmlt: pair kernel is " + std::to_string(kernel.width) + "x" + std::to_string(kernel.height) +
                     ", the image " + std::to_string(m_w) + "x" + std::to_string(m_h));
}

void PathGradientFactor::evaluate(PathState& s) {
  s.pair = Rgb::Zero();
  s.pair_row = -1;
  const double lum = luminance(s.c_ref);
  const Rgbd fb = s.c_ref.cast<double>();
  if (s.ref < 0 || !(lum > 0.0)) {
    s.factor = std::nan("");
    return;
  }
  const int px = std::clamp(int(s.raster.x()), 0, m_w - 1), py = std::clamp(int(s.raster.y()), 0, m_h - 1);
  const auto nb = kernels_adaptive::neighbours(m_kernel, py * m_w + px);  // N_i
  const int count = int(nb.size());
  if (count == 0) {
    s.factor = m_opt.alpha * gradients::magnitude(fb) / lum;
    return;
  }
  const auto& chosen = nb[size_t(std::min(count - 1, int(s.u_pair * double(count))))];
  const Vec2 offset(float(chosen.j % m_w - px), float(chosen.j / m_w - py));
  const int K = s.depth(), t = K + 1 - s.ref;
  Rgbd fo = Rgbd::Zero();
  bool has_offset = false;
  double jacobian = 1.0;
  if (m_opt.identity) {
    // T_0 only: the pair sample is the primal (finite differences of the image).
  } else if (t >= 2) {
    path_sides(m_scene, s.v, m_sides);
    gradients::shift_camera_subpath(m_scene, m_sides.camera, s.raster, offset, m_opt.shift, m_shift);
    ++m_counters.shifts;
    ++m_counters.shift_status[size_t(m_shift.status)];
    if (m_shift.walked) m_counters.walks.merge(m_shift.chain.stats);
    const gradients::StrategyOffset so = gradients::camera_strategy_offset(m_shift, m_sides.camera, t);
    if (so.exists) {
      pathspace::MisConfig unweighted;
      unweighted.unweighted = true;
      pathspace::Connection c;
      if (pathspace::connect(m_scene, m_sides.light.data(), s.ref, m_shift.path.data(), t, unweighted, c,
                             so.test_visibility) &&
          !is_black(c.value)) {
        fo = c.value.cast<double>();
        has_offset = true;
        // Strategy s's coordinates: the prefix rejoined x before its end (its last vertex
        // is x's), so the offset carries the reconnection's factor; else none (header).
        jacobian = m_shift.rejoined && t - 1 >= m_shift.join ? m_shift.jacobian : 1.0;
      }
    }
  } else {
    ++m_light_tracing_only;
  }
  const gradients::GradientSample g = gradients::symmetric_gradient(fb, fo, has_offset, jacobian, m_opt.gradient);
  ++m_counters.cases[size_t(g.kind)];
  s.pair = (g.value * (double(chosen.weight) * double(count) / lum)).cast<float>();
  s.pair_row = chosen.row;
  s.factor = (double(count) * gradients::magnitude(g.value) + m_opt.alpha * gradients::magnitude(fb)) / lum;
  if (!std::isfinite(s.factor) || !is_finite(s.pair)) s.factor = std::nan("");
}

}  // namespace dp::mcmc
