#include "integrators/pr/pr_tracer.h"

#include <string>

#include "gradients/mis.h"
#include "gradients/shift_factory.h"
#include "pathspace/sample_stream.h"

namespace dp::integrators {

using gradients::PairTerm;
using gradients::ShiftResult;
using gradients::ShiftStatus;
using pathspace::Path;

void PrCounters::flush(core::Stats& stats, const std::string& prefix) const {
  const std::string& p = prefix;
  stats.add(p + ".tiles", tiles);
  stats.add(p + ".base_paths", base_paths);
  stats.add(p + ".base_paths_without_paths", bases_without_paths);
  stats.add(p + ".nan_dropped", nan_dropped);
  stats.add(p + ".estimates.own", own);
  stats.add(p + ".estimates.reused", reused);
  stats.add(p + ".shift.attempted", shifts);
  stats.add(p + ".shift.complete", shifts_full);
  for (int i = 1; i < gradients::kShiftStatusCount; ++i) {
    const std::string cause = gradients::to_string(ShiftStatus(i));
    stats.add(p + ".shift.fail." + cause, fail[size_t(i)]);
    stats.add(p + ".shift.nee_fail." + cause, nee_fail[size_t(i)]);
  }
  stats.add(p + ".shift.nee_base_zero_density", nee_base_zero);
  stats.add(p + ".shift.fail.not_invertible.class_mismatch", class_mismatch);
  for (int i = 1; i < gradients::kStepKindCount; ++i) {
    const std::string kind = gradients::to_string(gradients::StepKind(i));
    stats.add(p + ".step." + kind + ".attempted", attempted[size_t(i)]);
    stats.add(p + ".step." + kind + ".succeeded", succeeded[size_t(i)]);
  }
}

namespace {
std::unique_ptr<gradients::Shift> make_reuse_shift(const scene::Scene& scene, const PrSettings& settings) {
  gradients::ShiftChoice c;
  c.kind = "reconnection";
  c.threshold = settings.shift_threshold;
  c.fault = settings.faults.jacobian;
  c.match_classes = !settings.faults.any_class;  // R must compose over the tile (reconnection_shift.h)
  return gradients::make_shift(scene, c);
}
}  // namespace

PrTracer::PrTracer(const scene::Scene& scene, const PrSettings& settings, int max_depth)
    : m_scene(scene),
      m_settings(settings),
      m_builder(scene, pathspace::WalkOptions{max_depth, settings.rr_depth, settings.nee, settings.shift_threshold}),
      m_shift(make_reuse_shift(scene, settings)),
      m_reconnect(dynamic_cast<const gradients::ReconnectionShift*>(m_shift.get())) {}

void PrTracer::count(const Path& base, const ShiftResult& r, PrCounters& c) const {
  const int n = base.size();
  ++c.shifts;
  if (r.alive == n) ++c.shifts_full;
  else ++c.fail[size_t(r.status)];
  c.class_mismatch += r.class_mismatch;
  for (int k = 0; k + 1 < n && k + 1 <= r.alive; ++k) {
    ++c.attempted[size_t(r.step[size_t(k)])];
    if (r.alive >= k + 2) ++c.succeeded[size_t(r.step[size_t(k)])];
  }
  for (int k = 1; k < r.alive; ++k) {
    if (r.nee_step[size_t(k)] == gradients::StepKind::none && r.nee_status[size_t(k)] == ShiftStatus::ok) continue;
    ++c.attempted[size_t(r.nee_step[size_t(k)])];
    if (r.nee_status[size_t(k)] == ShiftStatus::ok) ++c.succeeded[size_t(r.nee_step[size_t(k)])];
    else if (!(base.nee[size_t(k)].pdf > 0.0)) ++c.nee_base_zero;
    else ++c.nee_fail[size_t(r.nee_status[size_t(k)])];
  }
}

void PrTracer::build_bases(const ReuseTile& tile, core::Rng& rng, std::vector<Path>& bases) const {
  pathspace::IndependentStream stream(rng);
  // Correlated primary rays (Bauszat 2017, Sec. 3.2): one sub-pixel position for the tile.
  const Vec2 u = stream.next2();
  bases.resize(size_t(tile.pixels()));
  for (int m = 0; m < tile.pixels(); ++m) {
    const Vec2 raster(float(tile.x0 + m % tile.width()) + u.x(), float(tile.y0 + m / tile.width()) + u.y());
    m_builder.build_from_raster(raster, stream, bases[size_t(m)]);
  }
}

void PrTracer::reuse(const Path& base, int q, const ReuseTile& tile, ReuseFan& fan, PrCounters& c,
                     const std::vector<Path>* tile_bases) const {
  const int npix = tile.pixels(), tw = tile.width();
  const size_t keys = ReuseFan::key(base.size() + 1, true);
  fan.value.assign(size_t(npix), Rgbd::Zero());
  fan.weight.assign(keys, 0.0);
  fan.other.assign(keys, 0.0);
  fan.present.assign(keys, 0);
  fan.denom.assign(keys, 0.0);
  fan.fb.assign(keys, Rgbd::Zero());
  fan.splats.clear();
  ++c.base_paths;
  fan.pairs.set_base(m_scene, m_settings.nee, base);
  // The base's own concrete paths (also those of value 0: their densities still weigh).
  bool any = false;
  for (const PairTerm& t : fan.pairs.terms(nullptr, 2, true)) {
    if (!t.base_visible && !m_settings.faults.occluded_nee) continue;  // not reused (see below)
    const size_t k = ReuseFan::key(t.segments, t.nee);
    fan.present[k] = 1;
    fan.fb[k] = t.fb;
    fan.other[k] = t.b_other;
    fan.denom[k] = 1.0 + t.b_other;
    any = true;
  }
  if (!any) {  // nothing to reuse (e.g. the primary ray escaped or hit a light and stopped)
    ++c.bases_without_paths;
    return;
  }
  // R_qm for every other pixel m of the tile (Sec. 3.1): the densities of m's techniques
  // for the shifted path, in x's measure, go into the denominators of Eq. 3.
  const int qx = q % tw, qy = q / tw;
  for (int m = 0; m < npix; ++m) {
    if (m == q) continue;
    if (tile_bases && m_reconnect) m_reconnect->shift_to_primary(base, (*tile_bases)[size_t(m)], fan.res);
    else m_shift->shift(base, Vec2(float(m % tw - qx), float(m / tw - qy)), fan.res);
    count(base, fan.res, c);
    for (const PairTerm& t : fan.pairs.terms(&fan.res, 2, true)) {
      // A failed reuse, or a light sample occluded from m's vertex: no technique of m
      // produces this path. Occlusion counts as failure for NEE as it does for BSDF
      // paths (whose reconnection fails when blocked), so that both techniques of a
      // pixel see the same set of samplers; counting occluded NEE offsets (their density
      // is > 0) but not blocked BSDF offsets gave NEE and BSDF weights that did not add
      // up: +4% under an environment map (test_pr).
      if (!t.has_offset || (!t.offset_visible && !m_settings.faults.occluded_nee)) continue;
      const size_t k = ReuseFan::key(t.segments, t.nee);
      if (!fan.present[k]) continue;
      fan.denom[k] += t.c + t.d;
      if (!(t.fo == 0.0).all()) fan.splats.push_back({m, k, t.fo});
    }
  }
  // Eq. 7: one weight per concrete path, the same in every pixel of the tile.
  Rgbd own = Rgbd::Zero();
  for (size_t k = 0; k < keys; ++k) {
    if (!fan.present[k]) continue;
    if (m_settings.faults.mis == PrMisFault::uniform) [[unlikely]]
      fan.weight[k] = 1.0 / (double(npix) * (1.0 + fan.other[k]));
    else
      fan.weight[k] = gradients::tile_balance_weight(fan.other[k], fan.denom[k] - 1.0 - fan.other[k]);
    own += fan.weight[k] * fan.fb[k];
  }
  fan.value[size_t(q)] = own;
  for (const ReuseFan::Splat& s : fan.splats) fan.value[size_t(s.pixel)] += fan.weight[s.key] * s.fo;
}

void PrTracer::render_tile(const ReuseTile& tile, core::Rng& rng, int width, std::vector<Rgbd>& sum,
                           PrCounters& c) const {
  thread_local std::vector<Path> bases;
  thread_local ReuseFan fan;
  ++c.tiles;
  build_bases(tile, rng, bases);
  const int npix = tile.pixels(), tw = tile.width();
  auto index = [&](int m) { return size_t(tile.y0 + m / tw) * size_t(width) + size_t(tile.x0 + m % tw); };
  for (int q = 0; q < npix; ++q) {
    const Path& base = bases[size_t(q)];
    if (base.size() >= 2 && !m_settings.hide_emitters) {  // directly visible emitter: own base walk only
      const Rgb direct = base[1].emission;
      if (is_finite(direct)) sum[index(q)] += direct.cast<double>();
      else ++c.nan_dropped;
    }
    reuse(base, q, tile, fan, c, &bases);
    for (int m = 0; m < npix; ++m) {
      const Rgbd& v = fan.value[size_t(m)];
      if (!v.isFinite().all()) {
        ++c.nan_dropped;  // counted and dropped, never splatted
        continue;
      }
      if ((v == 0.0).all()) continue;
      sum[index(m)] += v;
      ++(m == q ? c.own : c.reused);
    }
  }
}

}  // namespace dp::integrators
