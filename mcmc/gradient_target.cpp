#include "mcmc/gradient_target.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace dp::mcmc {

void GradientTargetCounters::merge(const GradientTargetCounters& o) {
  for (size_t i = 0; i < cases.size(); ++i) cases[i] += o.cases[i];
  for (size_t i = 0; i < shift_status.size(); ++i) shift_status[i] += o.shift_status[i];
  shifts += o.shifts;
  incmw_shifts += o.incmw_shifts;
  incmw_declared += o.incmw_declared;
  walks.merge(o.walks);
}

GradientTarget::GradientTarget(const scene::Scene& scene, const gradients::Shift& shift,
                               const kernels_adaptive::PairKernel& kernel, const GradientTargetOptions& options)
    : m_shift(shift),
      m_kernel(kernel),
      m_opt(options),
      m_builder(scene, options.walk),
      m_w(scene.camera().width()),
      m_h(scene.camera().height()) {
  if (kernel.width != m_w || kernel.height != m_h ||
      kernel.offsets.size() != size_t(m_w) * size_t(m_h) + 1)
    throw ValueError("gdmlt: pair kernel is " + std::to_string(kernel.width) + "x" + std::to_string(kernel.height) +
                     ", the image " + std::to_string(m_w) + "x" + std::to_string(m_h));
}

TargetValue GradientTarget::evaluate(pathspace::SampleStream& stream) {
  const float u_j = stream.next();
  const Vec2 u = stream.next2();
  const float W = float(m_w), H = float(m_h);
  // u < 1, but u * W may round up to W: keep the raster position inside the image.
  const Vec2 raster(std::min(u.x() * W, std::nextafter(W, 0.0f)), std::min(u.y() * H, std::nextafter(H, 0.0f)));
  const int px = int(raster.x()), py = int(raster.y());
  const auto nb = kernels_adaptive::neighbours(m_kernel, py * m_w + px);  // N_i
  const int count = int(nb.size());
  m_builder.build_from_raster(raster, stream, m_base);

  TargetValue t;
  t.raster = raster;
  Rgbd primal = Rgbd::Zero(), grad = Rgbd::Zero();
  m_terms.set_base(m_builder.scene(), m_opt.walk.nee, m_base);
  const gradients::ShiftResult* offset = nullptr;
  const kernels_adaptive::PairKernel::Entry* chosen = nullptr;
  if (count > 0) {
    chosen = &nb[size_t(std::min(count - 1, int(u_j * float(count))))];
    const int jx = chosen->j % m_w, jy = chosen->j / m_w;
    if (m_base.size() > m_opt.min_segments - 1) {  // else no term can reach min_segments
      m_shift.shift(m_base, Vec2(float(jx - px), float(jy - py)), m_res);
      ++m_counters.shifts;
      m_counters.incmw_shifts += m_res.declared > 0;
      m_counters.incmw_declared += m_res.declared;
      ++m_counters.shift_status[size_t(m_res.alive == m_base.size() ? gradients::ShiftStatus::ok : m_res.status)];
      if (m_res.walk_status >= 0)
        m_counters.walks.record(m_res.walk_refused ? manifold::WalkStatus::ok : manifold::WalkStatus(m_res.walk_status),
                                m_res.walk_iterations);
      // The pixel filter (box): an offset that stays in pixel i (T_0) contributes nothing to j.
      const bool in_j =
          int(std::floor(m_res.path.raster.x())) == jx && int(std::floor(m_res.path.raster.y())) == jy;
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
    t.gradient = (grad * (double(chosen->weight) * double(count))).cast<float>();
    t.gradient_row = chosen->row;
  }
  // f(z) = |N_i| ||Delta^i_ij|| + alpha ||f*(x)|| (Manzi 2014, Sec. 4).
  t.f = double(count) * gradients::magnitude(grad) + m_opt.alpha * gradients::magnitude(primal);
  if (!std::isfinite(t.f) || !is_finite(t.value) || !is_finite(t.gradient)) t.f = std::nan("");
  return t;
}

}  // namespace dp::mcmc
