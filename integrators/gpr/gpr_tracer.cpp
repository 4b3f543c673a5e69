#include "integrators/gpr/gpr_tracer.h"

#include <algorithm>
#include <vector>

#include "integrators/gpr/early_out.h"

namespace dp::integrators {

using pathspace::Path;

void GprCounters::flush(core::Stats& stats) const {
  reuse.flush(stats, "gpr");
  stats.add("gpr.rr.bases", bases);
  stats.add("gpr.rr.tested", rr_tested);
  stats.add("gpr.rr.skipped", rr_skipped);
  stats.add("gpr.early_out.cut", cut);
  stats.add("gpr.early_out.cut_vertices", cut_vertices);
  stats.add("gpr.early_out.dark", dark);
  stats.add("gpr.table1.pixel_estimates", pixel_estimates);
  stats.add("gpr.table1.pixel_paths", pixel_paths);
  stats.add("gpr.table1.gradient_estimates", gradient_estimates);
  stats.add("gpr.table1.gradient_paths", gradient_paths);
}

GprTracer::GprTracer(const scene::Scene& scene, const GprSettings& settings, int max_depth)
    : m_scene(scene), m_settings(settings), m_pr(scene, settings.reuse, max_depth) {}

ReuseTile GprTracer::extended(const ReuseTile& inner, int width, int height, bool border) {
  ReuseTile e = inner;
  if (border) {  // Bauszat 2017, Sec. 3.2, Fig. 4: one pixel right and bottom
    e.x1 = std::min(width, inner.x1 + 1);
    e.y1 = std::min(height, inner.y1 + 1);
  }
  return e;
}

double GprTracer::survival(const Path& base, gradients::PairTerms& scratch) const {
  const double delta = m_settings.rr_delta;
  if (!(delta > 0.0)) return 1.0;
  // The base's path-traced value (power heuristic over its NEE and BSDF technique).
  scratch.set_base(m_scene, m_settings.reuse.nee, base);
  Rgbd v = Rgbd::Zero();
  for (const gradients::PairTerm& t : scratch.terms(nullptr, 2)) v += t.base_strategy_weight() * t.fb;
  const double lum = 0.212671 * v[0] + 0.715160 * v[1] + 0.072169 * v[2];
  // Bauszat 2017, Sec. 3.3: q = max(min(1, lum / delta), q_min). NaN lum: q = 1 (the
  // fan is then dropped as non-finite).
  const double q = std::min(1.0, lum / delta);
  if (m_settings.faults.rr_without_floor) [[unlikely]]
    return std::max(q, 0.0);
  return std::max(q, m_settings.rr_min);
}

void GprTracer::render_tile(const ReuseTile& inner, core::Rng& rng, gradients::GradientBuffers& buf,
                            GprCounters& c) const {
  thread_local std::vector<Path> bases;
  thread_local Path cut;
  thread_local ReuseFan fan;
  thread_local gradients::PairTerms scratch;
  thread_local std::vector<Rgbd> est;
  const int w = buf.width(), h = buf.height();
  const ReuseTile ext = extended(inner, w, h, !m_settings.faults.no_border);
  ++c.reuse.tiles;
  m_pr.build_bases(ext, rng, bases);
  const int npix = ext.pixels(), tw = ext.width();
  est.assign(size_t(npix), Rgbd::Zero());
  auto is_inner = [&](int m) {
    const int x = ext.x0 + m % tw, y = ext.y0 + m / tw;
    return x < inner.x1 && y < inner.y1;
  };
  for (int q = 0; q < npix; ++q) {
    const Path& full = bases[size_t(q)];
    if (is_inner(q) && full.size() >= 2 && !m_settings.reuse.hide_emitters) {  // own base walk only
      const Rgb direct = full[1].emission;
      if (is_finite(direct)) buf.add_direct(ext.x0 + q % tw, ext.y0 + q / tw, direct.cast<double>());
      else ++c.reuse.nan_dropped;
    }
    ++c.bases;
    // Proportional Russian roulette on the base path (Sec. 3.3).
    const double survive = survival(full, scratch);
    if (survive < 1.0) {
      ++c.rr_tested;
      if (!(rng.uniform_double() < survive)) {
        ++c.rr_skipped;
        continue;
      }
    }
    // Early out (early_out.h): shift only the part of the walk that can carry light.
    const Path* base = &full;
    if (m_settings.early_out) {
      const int a = live_prefix(full);
      if (a < full.size()) {
        cut.raster = full.raster;
        cut.vertices.assign(full.vertices.begin(), full.vertices.begin() + a);
        cut.nee.assign(full.nee.begin(), full.nee.begin() + a);
        base = &cut;
        ++c.cut;
        c.cut_vertices += full.size() - a;
      }
      if (!can_contribute(*base)) {
        ++c.dark;
        continue;
      }
    }
    m_pr.reuse(*base, q, ext, fan, c.reuse, &bases);  // primary rays traced once per tile
    bool finite = true;
    for (const Rgbd& v : fan.value) finite = finite && v.isFinite().all();
    if (!finite) {
      ++c.reuse.nan_dropped;  // counted once and dropped whole, never splatted
      continue;
    }
    const double inv_q = 1.0 / survive;
    for (int m = 0; m < npix; ++m) est[size_t(m)] += inv_q * fan.value[size_t(m)];
    // Table 1: base paths used per inner pixel and per inner pair.
    auto used = [&](int m) { return !(fan.value[size_t(m)] == 0.0).all(); };
    for (int m = 0; m < npix; ++m) {
      if (!is_inner(m)) continue;
      c.pixel_paths += used(m);
      const int x = m % tw, y = m / tw;
      if (x + 1 < tw) c.gradient_paths += used(m) || used(m + 1);
      if (y + 1 < ext.height()) c.gradient_paths += used(m) || used(m + tw);
    }
  }
  // Stitching (Fig. 4): the inner part only. Eq. 8: gradient (i -> j) = E_j - E_i.
  for (int m = 0; m < npix; ++m) {
    if (!is_inner(m)) continue;
    const int x = m % tw, y = m / tw;
    const int px = ext.x0 + x, py = ext.y0 + y;
    buf.add_primal(px, py, est[size_t(m)]);
    buf.add_samples(px, py, 1);
    ++c.pixel_estimates;
    if (x + 1 < tw) {
      buf.add_dx(px, py, est[size_t(m + 1)] - est[size_t(m)]);
      ++c.gradient_estimates;
    }
    if (y + 1 < ext.height()) {
      buf.add_dy(px, py, est[size_t(m + tw)] - est[size_t(m)]);
      ++c.gradient_estimates;
    }
  }
}

}  // namespace dp::integrators
