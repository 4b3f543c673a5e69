#include "integrators/gvcm/gvcm_tracer.h"

#include "integrators/gvcm/gvcm_offset.h"

#include <cmath>
#include <string>

#include "integrators/vcm/vcm_camera.h"
#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"
#include "pathspace/vcm_mis.h"

namespace dp::integrators {

using gradients::ShiftStatus;
using pathspace::BidirVertex;
using pathspace::VcmPrefix;

void GvcmCounters::flush(core::Stats& stats) const {
  stats.add("gvcm.samples", samples);
  stats.add("gvcm.nan_dropped", nan_dropped);
  stats.add("gvcm.connections", connections);
  stats.add("gvcm.connections_occluded", occluded);
  stats.add("gvcm.direct_paths", direct);
  stats.add("gvcm.merge_queries", merge_queries);
  stats.add("gvcm.merges", merges);
  stats.add("gvcm.shift.camera.attempted", camera_shifts);
  stats.add("gvcm.shift.camera.rejoined", camera_rejoined);
  stats.add("gvcm.shift.camera.fail.specular_chain", camera_chain);
  stats.add("gvcm.shift.light_tracing.attempted", light_shifts);
  stats.add("gvcm.shift.light_tracing.succeeded", light_shifted);
  stats.add("gvcm.shift.light_tracing.fail.specular_chain", light_chain);
  stats.add("gvcm.shift.merge.case1", merge_case1);
  stats.add("gvcm.shift.merge.case2.attempted", merge_case2);
  stats.add("gvcm.shift.merge.case2.succeeded", merge_case2_shifted);
  stats.add("gvcm.shift.merge.case2.fail.specular_chain", merge_chain);
  stats.add("gvcm.shift.merge.unshiftable", merge_unshiftable);
  for (int i = 1; i < gradients::kShiftStatusCount; ++i) {
    const std::string cause = gradients::to_string(ShiftStatus(i));
    stats.add("gvcm.shift.camera.fail." + cause, camera_fail[size_t(i)]);
    stats.add("gvcm.shift.light_tracing.fail." + cause, light_fail[size_t(i)]);
    stats.add("gvcm.shift.merge.case2.fail." + cause, merge_fail[size_t(i)]);
  }
  stats.add("gvcm.pairs.shifted", pairs_shifted);
  stats.add("gvcm.pairs.fallback", pairs_fallback);
  stats.add("gvcm.pairs.outside_image", outside_image);
  if (walks.attempted > 0) walks.flush(stats, "gvcm.manifold");
  else stats.add("gvcm.manifold.walks", 0);  // no specular chain: no walk machinery ran
}

namespace {
}  // namespace

GvcmTracer::GvcmTracer(const scene::Scene& scene, const GvcmSettings& settings, const VcmIteration& it,
                       const LightPathStore& light, const PhotonGrid& grid)
    : m_scene(scene), m_settings(settings), m_it(it), m_light(light), m_grid(grid) {
  const double n = double(light.paths());
  m_merge_norm = n > 0 && it.radius > 0 ? float(1.0 / (kPiD * double(it.radius) * double(it.radius) * n)) : 0.0f;
  m_shift.fault = settings.faults.jacobian;
  m_shift.walk_chains = settings.manifold;
  m_pair_primal = settings.primal == "pairs";
}

void GvcmTracer::sample(int px, int py, core::Rng& rng, GvcmScratch& sc, gradients::GradientBuffers& buf,
                        GvcmCounters& counters) const {
  ++counters.samples;
  const int w_img = buf.width(), h_img = buf.height();
  sc.raster = Vec2(float(px) + rng.uniform(), float(py) + rng.uniform());
  pathspace::camera_subpath(m_scene, sc.raster, pathspace::SubpathParams{m_it.max_depth + 1, m_settings.rr_depth}, rng,
                            sc.camera);
  const int nc = int(sc.camera.size());
  sc.cp.resize(size_t(nc));
  pathspace::vcm_prefixes(sc.camera.data(), nc, true, m_it.mis, sc.cp.data());
  const VcmPrefix* lp = nullptr;
  int nl = 0;
  const BidirVertex* light = m_light.path(int64_t(py) * w_img + px, &lp, &nl);
  sc.terms.clear();
  sc.splats.clear();
  sc.splats.pair_primal = m_pair_primal;
  connections(px, py, light, lp, nl, sc, w_img, h_img, counters);
  if (m_it.mis.eta > 0.0f && !m_grid.empty()) merges(px, py, sc, counters);
  if (!sc.terms.empty())
    for (int nb = 0; nb < 4; ++nb) offsets(nb, light, lp, sc, w_img, h_img, counters);
  if (!sc.splats.flush(buf, px, py)) ++counters.nan_dropped;  // the whole sample is dropped, never splatted
}

void GvcmTracer::connections(int px, int py, const BidirVertex* light, const VcmPrefix* lp, int nl, GvcmScratch& sc,
                             int w, int h, GvcmCounters& counters) const {
  const pathspace::MisConfig unweighted{.unweighted = true};
  const int nc = int(sc.camera.size());
  for (int t = 1; t <= nc; ++t)
    for (int s = 0; s <= nl; ++s) {
      if (s + t < 2 || s + t - 1 > m_it.max_depth) continue;
      pathspace::Connection c;
      const bool ok = pathspace::connect(m_scene, light, s, sc.camera.data(), t, unweighted, c);
      counters.connections += c.tested;
      counters.occluded += c.occluded;
      if (!ok) continue;
      const VcmPrefix* cp = t == 1 ? &kGvcmPinholePrefix : sc.cp.data();
      const float wv = pathspace::vcm_connection_weight(m_scene, light, lp, s, sc.camera.data(), cp, t, m_it.mis);
      if (!(wv > 0.0f)) continue;
      GvcmTerm term;
      term.s = s;
      term.t = t;
      term.px = px;
      term.py = py;
      term.raster = c.raster;
      term.value = c.value;
      term.w = double(wv);
      if (t == 1) {
        term.px = std::min(int(c.raster.x()), w - 1);
        term.py = std::min(int(c.raster.y()), h - 1);
      }
      if (s + t == 2) {  // one segment: a light seen directly, never shifted
        sc.splats.add(term.px, term.py, 1, (c.value * wv).cast<double>());
        ++counters.direct;
        continue;
      }
      if (!m_pair_primal) sc.splats.add(term.px, term.py, 0, (c.value * wv).cast<double>());
      sc.terms.push_back(term);
    }
}

void GvcmTracer::merges(int px, int py, GvcmScratch& sc, GvcmCounters& counters) const {
  const int nc = int(sc.camera.size());
  for (int t = 2; t <= nc && t <= m_it.max_depth; ++t) {
    const BidirVertex& z = sc.camera[size_t(t - 1)];
    if (!pathspace::vcm_mergeable(z, false, m_it.mis.min_merge_roughness)) continue;
    const MergeKernel kernel = merge_kernel(m_it.radius, m_merge_norm, sc.cp.data(), t);
    if (!(kernel.radius > 0.0f)) continue;
    ++counters.merge_queries;
    m_grid.query(z.sp.p, kernel.radius, [&](uint32_t slot) {
      const VcmPhoton& ph = m_light.photons[slot];
      if (ph.depth + t - 1 > m_it.max_depth) return;
      const Rgb f = merge_bsdf(z, ph.mis.wi);
      if (is_black(f)) return;
      ++counters.merges;
      const float wv = pathspace::vcm_merge_weight(ph.mis, sc.camera.data(), sc.cp.data(), t, m_it.mis);
      if (!(wv > 0.0f)) return;
      GvcmTerm term;
      term.merge = true;
      term.t = t;
      term.px = px;
      term.py = py;
      term.photon = slot;
      term.value = f * ph.beta * z.beta * kernel.norm;
      term.w = double(wv);
      if (!m_pair_primal) sc.splats.add(px, py, 0, (term.value * wv).cast<double>());
      sc.terms.push_back(term);
    });
  }
}

void GvcmTracer::offsets(int nb, const BidirVertex* light, const VcmPrefix* lp, GvcmScratch& sc, int w, int h,
                         GvcmCounters& counters) const {
  const Vec2 offset(float(kPairDx[nb]), float(kPairDy[nb]));
  const double beta = m_settings.beta();
  bool camera_shifted = false;
  for (const GvcmTerm& term : sc.terms) {
    const int qx = term.px + kPairDx[nb], qy = term.py + kPairDy[nb];
    const Rgbd base = term.value.cast<double>();
    if (qx < 0 || qy < 0 || qx >= w || qy >= h) {
      ++counters.outside_image;  // no pair: the base pixel keeps its own estimate
      sc.splats.unpaired(term.px, term.py, base, term.w);
      continue;
    }
    if ((term.merge || term.t >= 2) && !camera_shifted) {
      gradients::shift_camera_subpath(m_scene, sc.camera, sc.raster, offset, m_shift, sc.shift);
      camera_shifted = true;
      ++counters.camera_shifts;
      counters.camera_rejoined += sc.shift.rejoined;
      if (sc.shift.status != ShiftStatus::ok) ++counters.camera_fail[size_t(sc.shift.status)];
      counters.camera_chain += sc.shift.specular_chain;
      if (sc.shift.walked) counters.walks.merge(sc.shift.chain.stats);
      const int n = int(sc.shift.path.size());
      sc.off_cp.resize(size_t(n));
      pathspace::vcm_prefixes(sc.shift.path.data(), n, true, m_it.mis, sc.off_cp.data());
    }
    GvcmStrategy st;
    st.merge = term.merge;
    st.s = term.s;
    st.t = term.t;
    st.raster = term.raster;
    st.light = light;
    st.lp = lp;
    if (term.merge) {
      const VcmPhoton& ph = m_light.photons[term.photon];
      const VcmPrefix* unused = nullptr;
      int len = 0;
      st.light = m_light.path(int64_t(ph.path), &unused, &len);
      st.lp = nullptr;
      st.j = ph.depth;
      st.photon = ph.mis;
      st.photon_beta = ph.beta;
    }
    const GvcmOffsetContext ctx{m_scene, m_it.mis, m_merge_norm, m_shift, sc.camera, sc.cp, sc.shift, sc.off_cp};
    GvcmOffset o;
    const bool ok = gvcm_offset(ctx, st, offset, sc.lt, sc.merge, sc.off_lp, o, counters);
    const bool paired = sc.splats.mis_pair(nb, term.px, term.py, base, term.w, ok, o.value.cast<double>(), o.w, o.R, beta,
                                           m_settings.faults.mis_without_offset);
    ++(paired ? counters.pairs_shifted : counters.pairs_fallback);
  }
}

}  // namespace dp::integrators
