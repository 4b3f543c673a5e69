#include "mcmc/gradient_target.h"

#include <algorithm>
#include <cmath>

namespace dp::mcmc {

void GradientTargetCounters::merge(const GradientTargetCounters& o) {
  for (size_t i = 0; i < cases.size(); ++i) cases[i] += o.cases[i];
  for (size_t i = 0; i < shift_status.size(); ++i) shift_status[i] += o.shift_status[i];
  shifts += o.shifts;
  walks.merge(o.walks);
}

GradientTarget::GradientTarget(const scene::Scene& scene, const gradients::Shift& shift,
                               const GradientTargetOptions& options)
    : m_shift(shift),
      m_opt(options),
      m_builder(scene, options.walk),
      m_w(scene.camera().width()),
      m_h(scene.camera().height()) {}

namespace {
// A neighbour of the standard kernel: its pixel, the gradient row of the pair and the
// sign turning Delta^i_ij (part of I_i - I_j) into the row's value (rows are I_b - I_a
// with a left of / above b).
struct Neighbour {
  int dx, dy;
  int64_t row;
  double sign;
};

int neighbours(int x, int y, int w, int h, std::array<Neighbour, 4>& out) {
  const int64_t p = int64_t(y) * w + x, plane = int64_t(w) * h;
  int n = 0;
  if (x + 1 < w) out[size_t(n++)] = {1, 0, p, -1.0};              // row = I_j - I_i
  if (x > 0) out[size_t(n++)] = {-1, 0, p - 1, 1.0};              // row = I_i - I_j
  if (y + 1 < h) out[size_t(n++)] = {0, 1, plane + p, -1.0};
  if (y > 0) out[size_t(n++)] = {0, -1, plane + p - w, 1.0};
  return n;
}
}  // namespace

TargetValue GradientTarget::evaluate(pathspace::SampleStream& stream) {
  const float u_j = stream.next();
  const Vec2 u = stream.next2();
  const float W = float(m_w), H = float(m_h);
  // u < 1, but u * W may round up to W: keep the raster position inside the image.
  const Vec2 raster(std::min(u.x() * W, std::nextafter(W, 0.0f)), std::min(u.y() * H, std::nextafter(H, 0.0f)));
  const int px = int(raster.x()), py = int(raster.y());
  std::array<Neighbour, 4> nb;
  const int count = neighbours(px, py, m_w, m_h, nb);
  m_builder.build_from_raster(raster, stream, m_base);

  TargetValue t;
  t.raster = raster;
  Rgbd primal = Rgbd::Zero(), grad = Rgbd::Zero();
  m_terms.set_base(m_builder.scene(), m_opt.walk.nee, m_base);
  const gradients::ShiftResult* offset = nullptr;
  const Neighbour* chosen = nullptr;
  if (count > 0) {
    chosen = &nb[size_t(std::min(count - 1, int(u_j * float(count))))];
    if (m_base.size() > m_opt.min_segments - 1) {  // else no term can reach min_segments
      m_shift.shift(m_base, Vec2(float(chosen->dx), float(chosen->dy)), m_res);
      ++m_counters.shifts;
      ++m_counters.shift_status[size_t(m_res.alive == m_base.size() ? gradients::ShiftStatus::ok : m_res.status)];
      if (m_res.walk_status >= 0)
        m_counters.walks.record(m_res.walk_refused ? manifold::WalkStatus::ok : manifold::WalkStatus(m_res.walk_status),
                                m_res.walk_iterations);
      // The pixel filter (box): an offset that stays in pixel i (T_0) contributes nothing to j.
      const bool in_j = int(std::floor(m_res.path.raster.x())) == px + chosen->dx &&
                        int(std::floor(m_res.path.raster.y())) == py + chosen->dy;
      offset = in_j ? &m_res : nullptr;
    }
  }
  for (const gradients::PairTerm& term : m_terms.terms(offset, m_opt.min_segments)) {
    // Strategy (NEE/BSDF) weights of the path and of its offset (power heuristic, as the
    // reference PT), then Manzi 2014 Eqs. 4-6 per concrete path.
    const Rgbd fb = term.fb * term.base_strategy_weight();
    const Rgbd fo = term.fo * term.offset_strategy_weight();
    primal += fb;
    if (!chosen) continue;
    const gradients::GradientSample s =
        gradients::symmetric_gradient(fb, fo, term.has_offset, term.jacobian, m_opt.gradient);
    if (!(fb == 0.0).all()) ++m_counters.cases[size_t(s.kind)];
    grad += s.value;
  }
  t.value = primal.cast<float>();
  if (chosen) {
    t.gradient = (grad * (chosen->sign * double(count))).cast<float>();
    t.gradient_row = chosen->row;
  }
  // f(z) = |N_i| ||Delta^i_ij|| + alpha ||f*(x)|| (Manzi 2014, Sec. 4).
  t.f = double(count) * gradients::magnitude(grad) + m_opt.alpha * gradients::magnitude(primal);
  if (!std::isfinite(t.f) || !is_finite(t.value) || !is_finite(t.gradient)) t.f = std::nan("");
  return t;
}

}  // namespace dp::mcmc
