#include "integrators/gpm/gpm_tracer.h"

#include <cmath>
#include <string>

#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"
#include "integrators/vcm/vcm_camera.h"
#include "pathspace/vcm_mis.h"

namespace dp::integrators {

using gradients::ShiftStatus;
using pathspace::BidirVertex;

void GpmCounters::flush(core::Stats& stats) const {
  stats.add("gpm.samples", samples);
  stats.add("gpm.nan_dropped", nan_dropped);
  stats.add("gpm.no_merge_vertex", no_merge_vertex);
  stats.add("gpm.direct_paths", direct);
  stats.add("gpm.unshifted_merges", unshifted_merges);
  stats.add("gpm.merge_queries", merge_queries);
  stats.add("gpm.wide_queries", wide_queries);
  stats.add("gpm.merges", merges);
  stats.add("gpm.merges_depth_skipped", depth_skipped);
  stats.add("gpm.shift.camera.attempted", camera_shifts);
  stats.add("gpm.shift.merge.attempted", merge_shifts);
  stats.add("gpm.shift.merge.succeeded", merge_shifted);
  for (int i = 1; i < gradients::kShiftStatusCount; ++i) {
    const std::string cause = gradients::to_string(ShiftStatus(i));
    stats.add("gpm.shift.camera.fail." + cause, camera_fail[size_t(i)]);
    stats.add("gpm.shift.merge.fail." + cause, merge_fail[size_t(i)]);
  }
  stats.add("gpm.shift.merge.fail.specular_chain", merge_chain);
  stats.add("gpm.pairs.shifted", pairs_shifted);
  stats.add("gpm.pairs.fallback", pairs_fallback);
  stats.add("gpm.pairs.outside_image", outside_image);
  if (walks.attempted > 0) walks.flush(stats, "gpm.manifold");
  else stats.add("gpm.manifold.walks", 0);  // no specular chain before a photon: no walk ran
}

namespace {


}  // namespace

GpmTracer::GpmTracer(const scene::Scene& scene, const GpmSettings& settings, int max_depth, double radius_factor,
                     const LightPathStore& light, const PhotonGrid& grid)
    : m_scene(scene),
      m_settings(settings),
      m_max_depth(max_depth),
      m_radius_factor(radius_factor),
      m_inv_paths(light.paths() > 0 ? 1.0 / double(light.paths()) : 0.0),
      m_light(light),
      m_grid(grid) {
  m_shift.fault = settings.faults.jacobian;
  m_shift.walk_chains = settings.manifold;
  m_pair_primal = settings.primal == "pairs";
}

Rgb GpmTracer::gather(const BidirVertex& z, int k, double r, GpmScratch& sc, GpmCounters& counters) const {
  sc.terms.clear();
  ++counters.merge_queries;
  if (float(r) > m_grid.radius()) ++counters.wide_queries;
  const double norm = m_inv_paths / (kPiD * r * r);
  Rgb sum = Rgb::Zero();
  m_grid.query(z.sp.p, float(r), [&](uint32_t slot) {
    const VcmPhoton& ph = m_light.photons[slot];
    if (ph.depth + k > m_max_depth) {  // j light segments + k camera segments
      ++counters.depth_skipped;
      return;
    }
    const Rgb f = merge_bsdf(z, ph.mis.wi);
    if (is_black(f)) return;
    ++counters.merges;
    const Rgb v = f * ph.beta * z.beta * float(norm);
    sc.terms.push_back({slot, v});
    sum += v;
  });
  return sum;
}

void GpmTracer::sample(int px, int py, core::Rng& rng, GpmScratch& sc, gradients::GradientBuffers& buf,
                       GpmCounters& counters) const {
  ++counters.samples;
  const int w_img = buf.width(), h_img = buf.height();
  const Vec2 raster(float(px) + rng.uniform(), float(py) + rng.uniform());
  pathspace::SubpathParams params{m_max_depth + 1, m_settings.rr_depth};
  params.stop_after_smooth = true;
  pathspace::camera_subpath(m_scene, raster, params, rng, sc.camera);
  sc.splats.clear();
  sc.splats.pair_primal = m_pair_primal;
  sc.terms.clear();
  const int nc = int(sc.camera.size());
  const pathspace::MisConfig unweighted{.unweighted = true};
  int b = -1;
  for (int k = 1; k < nc; ++k) {
    const BidirVertex& z = sc.camera[size_t(k)];
    pathspace::Connection c;
    // Emission through a Dirac-only prefix (z_k's own emission; no merge samples it).
    if (z.emitter && pathspace::connect(m_scene, nullptr, 0, sc.camera.data(), k + 1, unweighted, c)) {
      sc.splats.add(px, py, 1, c.value.cast<double>());
      ++counters.direct;
    }
    if (!z.delta) {
      b = k;
      break;
    }
    // A mixed vertex whose Dirac lobe the walk took: its smooth part is merged here, unshifted.
    if (pathspace::vcm_mergeable(z, false) && k < m_max_depth && !m_grid.empty()) {
      const Rgb v = gather(z, k, m_radius_factor * footprint_radius(m_scene, sc.camera.data(), k), sc, counters);
      counters.unshifted_merges += int64_t(sc.terms.size());
      if (!is_black(v)) sc.splats.add(px, py, 1, v.cast<double>());
    }
  }
  sc.terms.clear();
  double r = 0;
  if (b < 1 || b >= m_max_depth || !pathspace::vcm_mergeable(sc.camera[size_t(b)], false) || m_grid.empty()) {
    ++counters.no_merge_vertex;
  } else {
    r = m_radius_factor * footprint_radius(m_scene, sc.camera.data(), b);
    const Rgb base = r > 0 ? gather(sc.camera[size_t(b)], b, r, sc, counters) : Rgb::Zero();
    if (!m_pair_primal && !is_black(base)) sc.splats.add(px, py, 0, base.cast<double>());
  }
  if (!sc.terms.empty())
    for (int nb = 0; nb < 4; ++nb) offsets(nb, px, py, raster, b, r, sc, w_img, h_img, counters);
  if (!sc.splats.flush(buf, px, py)) ++counters.nan_dropped;  // the whole sample is dropped, never splatted
}

void GpmTracer::offsets(int nb, int px, int py, const Vec2& raster, int b, double r, GpmScratch& sc, int w, int h,
                        GpmCounters& counters) const {
  const int qx = px + kPairDx[nb], qy = py + kPairDy[nb];
  if (qx < 0 || qy < 0 || qx >= w || qy >= h) {
    counters.outside_image += int64_t(sc.terms.size());  // no pair: the base pixel keeps its own estimate
    for (const GpmTerm& t : sc.terms) sc.splats.unpaired(px, py, t.value.cast<double>(), 1.0);
    return;
  }
  gradients::shift_camera_subpath(m_scene, sc.camera, raster, Vec2(float(kPairDx[nb]), float(kPairDy[nb])), m_shift, sc.shift);
  ++counters.camera_shifts;
  if (sc.shift.status != ShiftStatus::ok) ++counters.camera_fail[size_t(sc.shift.status)];
  const bool camera_ok = sc.shift.alive > b && sc.shift.b == b;
  const double r_off = camera_ok ? m_radius_factor * footprint_radius(m_scene, sc.shift.path.data(), b) : 0.0;
  const double beta = m_settings.beta();
  const double norm = m_inv_paths / (kPiD * r * r);
  for (const GpmTerm& t : sc.terms) {
    const Rgbd base = t.value.cast<double>();
    Rgbd off = Rgbd::Zero();
    double R = 0;
    if (camera_ok && r_off > 0) {
      const VcmPhoton& ph = m_light.photons[t.photon];
      const pathspace::VcmPrefix* unused = nullptr;
      int len = 0;
      const BidirVertex* light = m_light.path(int64_t(ph.path), &unused, &len);
      ++counters.merge_shifts;
      gradients::MergeShift& ms = sc.merge;
      const bool ok = gradients::shift_merge(m_scene, light, ph.depth, sc.camera, sc.shift, m_shift, ms);
      if (ms.walked) counters.walks.merge(ms.chain.stats);
      if (ok) {
        ++counters.merge_shifted;
        off = ms.value.cast<double>() * norm;
        if (m_settings.faults.unit_area_ratio && ms.area_ratio > 0) off /= ms.area_ratio;
        R = ms.direction_ratio * ms.area_ratio * (r_off / r) * (r_off / r);
      } else {
        ++counters.merge_fail[size_t(ms.status)];
        counters.merge_chain += ms.specular_chain;
      }
    }
    // One strategy per pixel: both VCM-style weights are 1, the weight is 1 / (1 + R^beta).
    const bool paired = sc.splats.mis_pair(nb, px, py, base, 1.0, true, off, 1.0, R, beta,
                                           m_settings.faults.mis_without_offset);
    ++(paired ? counters.pairs_shifted : counters.pairs_fallback);
  }
}

}  // namespace dp::integrators
