#include "integrators/gpt/gpt_tracer.h"

#include <cmath>
#include <limits>
#include <string>

#include "gradients/manifold_shift.h"
#include "gradients/mis.h"
#include "pathspace/measure.h"
#include "pathspace/scatter.h"

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
  const gradients::ReconnectionShiftOptions ro{settings.shift_threshold,
                                               scene.caps().has_glossy || scene.caps().has_specular,
                                               settings.faults.jacobian};
  if (settings.shift == "manifold")
    return std::make_unique<gradients::ManifoldShift>(
        scene, gradients::ManifoldShiftOptions{ro, {}, settings.manifold_chains == "emitter",
                                               settings.manifold_walk == "fallback"});
  return std::make_unique<gradients::ReconnectionShift>(scene, ro);
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

// NEE is performed at vertex m of a walk (so NEE can produce the path through x_m).
bool nee_at(const Vertex& v, bool nee) {
  return nee && v.is_surface() && v.hit.bsdf && !v.hit.bsdf->is_purely_delta() && !v.delta_lobe();
}
}  // namespace

void GptTracer::sample(int px, int py, pathspace::SampleStream& stream, gradients::GradientBuffers& buf,
                       GptCounters& counters) const {
  thread_local Path base;
  thread_local ShiftResult res;
  thread_local std::vector<Rgbd> beta, beta_o;
  thread_local std::vector<double> ratio;
  thread_local std::vector<double> b_other_bsdf;  // base light pdf / bsdf pdf per BSDF path, lazily (NaN: not yet)
  ++counters.samples;
  m_builder.build(px, py, stream, base);
  const int n = base.size();
  const int w = buf.width(), h = buf.height();
  if (n >= 2) {
    const Rgb direct = base[1].emission;
    if (is_finite(direct)) buf.add_direct(px, py, direct.cast<double>());
    else ++counters.nan_dropped;
  }
  // Base throughput f/p of every prefix, in double.
  beta.assign(size_t(n), Rgbd::Ones());
  for (int k = 1; k + 1 < n; ++k)
    beta[size_t(k + 1)] = beta[size_t(k)] * base[k].f_cos.cast<double>() / (base[k].pdf * double(base[k].rr));

  b_other_bsdf.assign(size_t(n), std::numeric_limits<double>::quiet_NaN());
  static constexpr int kDx[4] = {1, -1, 0, 0}, kDy[4] = {0, 0, 1, -1};
  for (int nb = 0; nb < 4; ++nb) {
    const int qx = px + kDx[nb], qy = py + kDy[nb];
    const bool inside = qx >= 0 && qy >= 0 && qx < w && qy < h;
    int alive = 0;
    if (inside) {
      m_shift->shift(base, Vec2(float(kDx[nb]), float(kDy[nb])), res);
      count(base, res, counters);
      alive = res.alive;
      // Offset throughput relative to the base density, and pdf ratios p_j(T x)|T'| / p_i(x)
      // per prefix (Kettunen 2015, Sec. 5.3: ratios in double, RR follows the base).
      beta_o.assign(size_t(n), Rgbd::Zero());
      ratio.assign(size_t(n), 0.0);
      if (alive >= 2) beta_o[1] = Rgbd::Ones(), ratio[1] = 1.0;
      for (int k = 1; k + 1 < alive; ++k) {
        const Vertex& o = res.path[k];
        const double J = res.jacobian[size_t(k)];
        beta_o[size_t(k + 1)] = beta_o[size_t(k)] * o.f_cos.cast<double>() * J / (base[k].pdf * double(base[k].rr));
        ratio[size_t(k + 1)] = ratio[size_t(k)] * o.pdf * J / base[k].pdf;
      }
    } else {
      ++counters.shifts_outside;
    }
    Rgbd primal_i = Rgbd::Zero(), primal_j = Rgbd::Zero(), grad = Rgbd::Zero();
    // One concrete path (NEE or BSDF) of the pair, weighted by the symmetric MIS weight:
    // both pixels' primal estimates and the pair's gradient f_j(Tx)|T'| - f_i(x) (a failed
    // shift leaves only the base term).
    auto accumulate = [&](const Rgbd& fb, const Rgbd& fo, double wgt, bool has_offset) {
      if ((fb == 0.0).all() && (fo == 0.0).all()) return;
      primal_i += wgt * fb;
      if (has_offset) {
        primal_j += wgt * fo;
        grad += wgt * (fo - fb);
      } else if (inside) {
        grad -= wgt * fb;
      }
    };
    // NEE paths (x_0..x_k, light sample).
    for (int k = 1; k < n; ++k) {
      const pathspace::LightSample& bl = base.nee[size_t(k)];
      if (!bl.valid || !(bl.pdf > 0.0)) continue;
      const Rgbd fb = bl.visible ? Rgbd(beta[size_t(k)] * (bl.f_cos * bl.radiance).cast<double>() / bl.pdf) : Rgbd::Zero();
      const double b_other = bl.visible ? bl.bsdf_pdf / bl.pdf : 0.0;
      double c = 0, d = 0;
      Rgbd fo = Rgbd::Zero();
      const bool has_offset = inside && res.nee_ok(k);
      if (has_offset) {
        const pathspace::LightSample& ol = res.path.nee[size_t(k)];
        const double J = res.nee_jacobian[size_t(k)];
        c = ratio[size_t(k)] * J * ol.pdf / bl.pdf;
        d = ol.visible ? ratio[size_t(k)] * J * ol.bsdf_pdf / bl.pdf : 0.0;
        if (ol.visible) fo = beta_o[size_t(k)] * (ol.f_cos * ol.radiance).cast<double>() * (J / bl.pdf);
      }
      accumulate(fb, fo, mis_weight(b_other, c, d, m_settings.faults.mis), has_offset);
    }
    // BSDF paths (x_0..x_k), k >= 2, whose last vertex may emit. The light densities (for
    // the MIS weights) are only needed where the base or the offset vertex emits; the
    // base's is the same for all four neighbours.
    for (int k = 2; k < n; ++k) {
      const int m = k - 1;
      const Vertex& bv = base[k];
      const bool has_offset = inside && k < alive;
      const bool base_emits = !is_black(bv.emission);
      if (!base_emits && !(has_offset && !is_black(res.path[k].emission))) continue;
      const Rgbd fb = base_emits ? Rgbd(beta[size_t(k)] * bv.emission.cast<double>()) : Rgbd::Zero();
      double& b_other = b_other_bsdf[size_t(k)];
      if (std::isnan(b_other))
        b_other = nee_at(base[m], m_settings.nee) ? pathspace::light_pdf(m_scene, base[m].p(), bv) / base[m].pdf : 0.0;
      double c = 0, d = 0;
      Rgbd fo = Rgbd::Zero();
      if (has_offset) {
        const Vertex& om = res.path[m];
        const Vertex& ov = res.path[k];
        c = ratio[size_t(k)];
        d = nee_at(om, m_settings.nee)
                ? ratio[size_t(m)] * res.jacobian[size_t(m)] * pathspace::light_pdf(m_scene, om.p(), ov) / base[m].pdf
                : 0.0;
        fo = beta_o[size_t(k)] * ov.emission.cast<double>();
      }
      accumulate(fb, fo, mis_weight(b_other, c, d, m_settings.faults.mis), has_offset);
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
