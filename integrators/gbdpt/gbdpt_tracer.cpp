#include "integrators/gbdpt/gbdpt_tracer.h"

#include <string>

#include "pathspace/bidir_connect.h"
#include "pathspace/bidir_subpath.h"

namespace dp::integrators {

using gradients::ShiftStatus;

void GbdptCounters::flush(core::Stats& stats) const {
  stats.add("gbdpt.samples", samples);
  stats.add("gbdpt.nan_dropped", nan_dropped);
  stats.add("gbdpt.connections", connections);
  stats.add("gbdpt.connections_occluded", occluded);
  stats.add("gbdpt.direct_paths", direct);
  stats.add("gbdpt.shift.camera.attempted", camera_shifts);
  stats.add("gbdpt.shift.camera.rejoined", camera_rejoined);
  stats.add("gbdpt.shift.light_tracing.attempted", light_shifts);
  stats.add("gbdpt.shift.light_tracing.succeeded", light_shifted);
  for (int i = 1; i < gradients::kShiftStatusCount; ++i) {
    const std::string cause = gradients::to_string(ShiftStatus(i));
    stats.add("gbdpt.shift.camera.fail." + cause, camera_fail[size_t(i)]);
    stats.add("gbdpt.shift.light_tracing.fail." + cause, light_fail[size_t(i)]);
  }
  stats.add("gbdpt.pairs.shifted", pairs_shifted);
  stats.add("gbdpt.pairs.fallback", pairs_fallback);
  stats.add("gbdpt.pairs.outside_image", outside_image);
  // Specular chains after b that cannot be walked (ending at the environment or a delta
  // light, or manifold=false) fail as not_invertible (T_0 fallback); the walks by outcome.
  stats.add("gbdpt.shift.camera.fail.specular_chain", camera_chain);
  stats.add("gbdpt.shift.light_tracing.fail.specular_chain", light_chain);
  if (walks.attempted > 0) walks.flush(stats, "gbdpt.manifold");
  else stats.add("gbdpt.manifold.walks", 0);  // no specular chain: no walk machinery ran
}

GbdptTracer::GbdptTracer(const scene::Scene& scene, const GbdptSettings& settings, int max_depth)
    : m_scene(scene), m_settings(settings), m_max_depth(max_depth) {
  m_balance.heuristic = pathspace::MisHeuristic::balance;
  m_unweighted.unweighted = true;
  m_pair_primal = settings.primal == "pairs";
  m_shift.fault = settings.faults.jacobian;
  m_shift.walk_chains = settings.manifold;
}

namespace {
}

void GbdptTracer::sample(int px, int py, core::Rng& rng, GbdptScratch& sc, gradients::GradientBuffers& buf,
                         GbdptCounters& counters) const {
  ++counters.samples;
  const int w_img = buf.width(), h_img = buf.height();
  const Vec2 raster(float(px) + rng.uniform(), float(py) + rng.uniform());
  sc.camera_raster = raster;
  const pathspace::SubpathParams cam_params{m_max_depth + 1, m_settings.rr_depth};
  const pathspace::SubpathParams light_params{m_max_depth, m_settings.rr_depth};
  pathspace::camera_subpath(m_scene, raster, cam_params, rng, sc.camera);
  pathspace::light_subpath(m_scene, light_params, rng, sc.light);
  sc.terms.clear();
  sc.splats.clear();
  sc.splats.pair_primal = m_pair_primal;
  const int nc = int(sc.camera.size()), nl = int(sc.light.size());
  for (int t = 1; t <= nc; ++t)
    for (int s = 0; s <= nl; ++s) {
      if (s + t < 2 || s + t - 1 > m_max_depth) continue;
      // Value and visibility first; the reverse densities only for a non-zero value, once
      // for both heuristics (primal and gradient weights) and the offsets that keep them.
      pathspace::Connection c;
      const bool ok = pathspace::connect(m_scene, sc.light.data(), s, sc.camera.data(), t, m_unweighted, c);
      counters.connections += c.tested;
      counters.occluded += c.occluded;
      if (!ok) continue;
      GbdptTerm term{s, t, px, py, c.raster, c.value, 0.0, {}};
      term.reverse = pathspace::connection_reverse_pdfs(m_scene, sc.light.data(), s, sc.camera.data(), t);
      // The `mis` weight only where it is used (the direct layer, primal=bdpt); the
      // gradients' balance weight for every shifted term (the same when mis=balance).
      const bool direct = s + t == 2;
      const bool balance = m_settings.mis.heuristic == pathspace::MisHeuristic::balance;
      const bool primal_weight = direct || !m_pair_primal;
      const float w = primal_weight || balance
                          ? pathspace::mis_weight(sc.light.data(), s, sc.camera.data(), t, m_settings.mis, term.reverse)
                          : pathspace::mis_weight(sc.light.data(), s, sc.camera.data(), t, m_balance, term.reverse);
      if (!(w > 0.0f)) continue;  // the heuristics vanish together
      if (t == 1) {
        term.px = std::min(int(c.raster.x()), w_img - 1);
        term.py = std::min(int(c.raster.y()), h_img - 1);
      }
      if (primal_weight) sc.splats.add(term.px, term.py, direct ? 1 : 0, (c.value * w).cast<double>());
      if (direct) {
        ++counters.direct;
        continue;
      }
      term.w_bal = !primal_weight || balance
                       ? double(w)
                       : double(pathspace::mis_weight(sc.light.data(), s, sc.camera.data(), t, m_balance, term.reverse));
      sc.terms.push_back(term);
    }
  if (!sc.terms.empty())
    for (int nb = 0; nb < 4; ++nb) offsets(nb, sc, w_img, h_img, counters);
  if (!sc.splats.flush(buf, px, py)) ++counters.nan_dropped;  // the whole sample is dropped, never splatted
}

void GbdptTracer::offsets(int nb, GbdptScratch& sc, int w, int h, GbdptCounters& counters) const {
  const Vec2 offset(float(kPairDx[nb]), float(kPairDy[nb]));
  bool camera_shifted = false;
  for (const GbdptTerm& term : sc.terms) {
    const int qx = term.px + kPairDx[nb], qy = term.py + kPairDy[nb];
    const Rgbd base = term.value.cast<double>();
    if (qx < 0 || qy < 0 || qx >= w || qy >= h) {
      ++counters.outside_image;  // no pair: the base pixel keeps its own estimate
      sc.splats.unpaired(term.px, term.py, base, term.w_bal);
      continue;
    }
    Rgb off = Rgb::Zero();
    double w_off = 0.0, ratio = 1.0;
    if (term.t >= 2) {
      if (!camera_shifted) {
        gradients::shift_camera_subpath(m_scene, sc.camera, sc.camera_raster, offset, m_shift, sc.shift);
        camera_shifted = true;
        ++counters.camera_shifts;
        counters.camera_rejoined += sc.shift.rejoined;
        if (sc.shift.status != ShiftStatus::ok) ++counters.camera_fail[size_t(sc.shift.status)];
        counters.camera_chain += sc.shift.specular_chain;
        if (sc.shift.walked) counters.walks.merge(sc.shift.chain.stats);
      }
      const gradients::StrategyOffset so = gradients::camera_strategy_offset(sc.shift, sc.camera, term.t);
      if (so.exists) {
        pathspace::Connection c;
        if (pathspace::connect(m_scene, sc.light.data(), term.s, sc.shift.path.data(), term.t, m_balance, c,
                               so.test_visibility, so.same_reverse ? &term.reverse : nullptr)) {
          off = c.value;
          w_off = double(c.weight);
          ratio = so.mis_ratio;
        }
        counters.connections += c.tested;
        counters.occluded += c.occluded;
      }
    } else {
      ++counters.light_shifts;
      const bool shifted =
          gradients::shift_light_tracing(m_scene, sc.light.data(), term.s, term.raster, offset, m_shift, sc.lt);
      if (sc.lt.walked) counters.walks.merge(sc.lt.chain.stats);
      if (shifted) {
        ++counters.light_shifted;
        off = sc.lt.value;
        ratio = sc.lt.mis_ratio;
        w_off = double(pathspace::mis_weight(m_scene, sc.lt.light.data(), term.s, sc.camera.data(), 1, m_balance));
      } else {
        ++counters.light_fail[size_t(sc.lt.status)];
        counters.light_chain += sc.lt.specular_chain;
      }
    }
    const bool paired = sc.splats.mis_pair(nb, term.px, term.py, base, term.w_bal, true, off.cast<double>(), w_off, ratio, 1.0,
                                           m_settings.faults.mis_without_offset);
    ++(paired ? counters.pairs_shifted : counters.pairs_fallback);
  }
}

}  // namespace dp::integrators
