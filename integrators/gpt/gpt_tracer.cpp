#include "integrators/gpt/gpt_tracer.h"

#include <cmath>
#include <string>

#include "gradients/pair_terms.h"
#include "gradients/shift_factory.h"
#include "integrators/gpt/gpt_splat.h"

namespace dp::integrators {

using gradients::ShiftResult;
using gradients::ShiftStatus;
using pathspace::Path;
using pathspace::Vertex;

void GptCounters::flush(core::Stats& stats) const {
  stats.add("gpt.samples", samples);
  stats.add("gpt.nan_dropped", nan_dropped);
  stats.add("gpt.media_skipped", media_skipped);
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

void GptTracer::sample(int px, int py, pathspace::SampleStream& stream, gradients::GradientBuffers& buf,
                       GptCounters& counters) const {
  thread_local Path base;
  thread_local ShiftResult res;
  thread_local gradients::PairTerms pairs;
  ++counters.samples;
  ++counters.media_skipped;  // this tracer has no medium code (scenes without media)
  m_builder.build(px, py, stream, base);
  const int n = base.size();
  const int w = buf.width(), h = buf.height();
  if (n >= 2) {
    const Rgb direct = base[1].emission;
    if (is_finite(direct)) buf.add_direct(px, py, direct.cast<double>());
    else ++counters.nan_dropped;
  }
  pairs.set_base(m_scene, m_settings.nee, base);
  for (int nb = 0; nb < 4; ++nb) {
    const int qx = px + kGptDx[nb], qy = py + kGptDy[nb];
    const bool inside = qx >= 0 && qy >= 0 && qx < w && qy < h;
    if (inside) {
      m_shift->shift(base, Vec2(float(kGptDx[nb]), float(kGptDy[nb])), res);
      count(base, res, counters);
    } else {
      ++counters.shifts_outside;
    }
    // Every concrete path (NEE or BSDF, >= 2 segments) of the pair (gpt_splat.h).
    if (!splat_gpt_pair(pairs.terms(inside ? &res : nullptr, 2), px, py, nb, inside, m_settings.faults.mis, buf))
      ++counters.nan_dropped;  // counted and dropped, never splatted
  }
  buf.add_samples(px, py, 1);
}

}  // namespace dp::integrators
