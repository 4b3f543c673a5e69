#include "integrators/gpt/gpt_tracer.h"

#include <cmath>
#include <string>

#include "gradients/mis.h"
#include "gradients/pair_terms.h"
#include "gradients/shift_factory.h"

namespace dp::integrators {

using gradients::ShiftResult;
using gradients::ShiftStatus;
using pathspace::Path;
using pathspace::Vertex;

void GptCounters::flush(core::Stats& stats) const {
  stats.add("gpt.samples", samples);
  stats.add("gpt.nan_dropped", nan_dropped);
  stats.add("gpt.shift.attempted", shifts);
  stats.add("gpt.shift.complete", shifts_full);
  stats.add("gpt.shift.outside_image", shifts_outside);
  for (int i = 1; i < gradients::kShiftStatusCount; ++i) {
    const std::string cause = gradients::to_string(ShiftStatus(i));
    stats.add("gpt.shift.fail." + cause, fail[size_t(i)]);
    stats.add("gpt.shift.nee_fail." + cause, nee_fail[size_t(i)]);
  }
  stats.add("gpt.shift.nee_base_zero_density", nee_base_zero);
  if (walks.attempted > 0) stats.add("gpt.manifold.converged_but_refused", walks_refused);
  for (int i = 0; i < gradients::kStepKindCount; ++i) {
    const std::string kind = gradients::to_string(gradients::StepKind(i));
    stats.add("gpt.step." + kind + ".attempted", attempted[size_t(i)]);
    stats.add("gpt.step." + kind + ".succeeded", succeeded[size_t(i)]);
  }
  if (walks.attempted > 0) walks.flush(stats, "gpt.manifold");
}

namespace {
std::unique_ptr<gradients::Shift> make_shift(const scene::Scene& scene, const GptSettings& settings) {
  gradients::ShiftChoice c;
  c.kind = settings.shift;
  c.threshold = settings.shift_threshold;
  c.manifold_emitter_chains_only = settings.manifold_chains == "emitter";
  c.manifold_walk_as_fallback = settings.manifold_walk == "fallback";
  c.fault = settings.faults.jacobian;
  return gradients::make_shift(scene, c);
}
}  // namespace

GptTracer::GptTracer(const scene::Scene& scene, const GptSettings& settings, int max_depth)
    : m_scene(scene),
      m_settings(settings),
      m_builder(scene, pathspace::WalkOptions{max_depth, settings.rr_depth, settings.nee, settings.shift_threshold}),
      m_shift(make_shift(scene, settings)) {}

void GptTracer::count(const Path& base, const ShiftResult& r, GptCounters& c) const {
  const int n = base.size();
  ++c.shifts;
  if (r.alive == n) ++c.shifts_full;
  else ++c.fail[size_t(r.status)];
  for (int k = 0; k + 1 < n && k + 1 <= r.alive; ++k) {
    ++c.attempted[size_t(r.step[size_t(k)])];
    if (r.alive >= k + 2) ++c.succeeded[size_t(r.step[size_t(k)])];
  }
  if (r.walk_status >= 0) {
    // A refused walk converged (counted so), but the reverse shift would copy.
    c.walks_refused += r.walk_refused;
    c.walks.record(r.walk_refused ? manifold::WalkStatus::ok : manifold::WalkStatus(r.walk_status), r.walk_iterations);
    c.walks.traces += r.walk_traces;
  }
  for (int k = 1; k < r.alive; ++k) {
    if (r.nee_step[size_t(k)] == gradients::StepKind::none && r.nee_status[size_t(k)] == ShiftStatus::ok) continue;
    ++c.attempted[size_t(r.nee_step[size_t(k)])];
    if (r.nee_status[size_t(k)] == ShiftStatus::ok) ++c.succeeded[size_t(r.nee_step[size_t(k)])];
    else if (!(base.nee[size_t(k)].pdf > 0.0)) ++c.nee_base_zero;  // e.g. the back of the light: no shift needed
    else ++c.nee_fail[size_t(r.nee_status[size_t(k)])];
  }
}

namespace {
// The symmetric power-heuristic weight (gradients/mis.h), or the MisFault defect of a
// tests' negative control (one predictable branch).
double mis_weight(double other_base, double offset_same, double offset_other, MisFault fault) {
  if (fault == MisFault::without_offset) [[unlikely]]
    return gradients::symmetric_power_weight(other_base, 0.0, 0.0);
  return gradients::symmetric_power_weight(other_base, offset_same, offset_other);
}

}  // namespace

void GptTracer::sample(int px, int py, pathspace::SampleStream& stream, gradients::GradientBuffers& buf,
                       GptCounters& counters) const {
  thread_local Path base;
  thread_local ShiftResult res;
  thread_local gradients::PairTerms pairs;
  ++counters.samples;
  m_builder.build(px, py, stream, base);
  const int n = base.size();
  const int w = buf.width(), h = buf.height();
  if (n >= 2) {
    const Rgb direct = base[1].emission;
    if (is_finite(direct)) buf.add_direct(px, py, direct.cast<double>());
    else ++counters.nan_dropped;
  }
  pairs.set_base(m_scene, m_settings.nee, base);
  static constexpr int kDx[4] = {1, -1, 0, 0}, kDy[4] = {0, 0, 1, -1};
  for (int nb = 0; nb < 4; ++nb) {
    const int qx = px + kDx[nb], qy = py + kDy[nb];
    const bool inside = qx >= 0 && qy >= 0 && qx < w && qy < h;
    if (inside) {
      m_shift->shift(base, Vec2(float(kDx[nb]), float(kDy[nb])), res);
      count(base, res, counters);
    } else {
      ++counters.shifts_outside;
    }
    Rgbd primal_i = Rgbd::Zero(), primal_j = Rgbd::Zero(), grad = Rgbd::Zero();
    // Every concrete path (NEE or BSDF, >= 2 segments) of the pair, weighted by the
    // symmetric MIS weight: both pixels' primal estimates and the pair's gradient
    // f_j(Tx)|T'| - f_i(x) (a failed shift leaves only the base term).
    for (const gradients::PairTerm& t : pairs.terms(inside ? &res : nullptr, 2)) {
      const double wgt = mis_weight(t.b_other, t.c, t.d, m_settings.faults.mis);
      primal_i += wgt * t.fb;
      if (t.has_offset) {
        primal_j += wgt * t.fo;
        grad += wgt * (t.fo - t.fb);
      } else if (inside) {
        grad -= wgt * t.fb;
      }
    }
    if (!primal_i.isFinite().all() || !primal_j.isFinite().all() || !grad.isFinite().all()) {
      ++counters.nan_dropped;  // counted and dropped, never splatted
      continue;
    }
    buf.add_primal(px, py, 0.25 * primal_i);
    if (!inside) continue;
    buf.add_primal(qx, qy, 0.25 * primal_j);
    // grad estimates I_j - I_i; the buffers hold forward differences.
    if (kDx[nb] == 1) buf.add_dx(px, py, grad);
    else if (kDx[nb] == -1) buf.add_dx(qx, qy, -grad);
    else if (kDy[nb] == 1) buf.add_dy(px, py, grad);
    else buf.add_dy(qx, qy, -grad);
  }
  buf.add_samples(px, py, 1);
}

}  // namespace dp::integrators
