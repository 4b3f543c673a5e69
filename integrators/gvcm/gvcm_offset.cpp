#include "integrators/gvcm/gvcm_offset.h"

#include "integrators/vcm/vcm_camera.h"
#include "pathspace/bidir_connect.h"

namespace dp::integrators {

using gradients::ShiftStatus;
using pathspace::BidirVertex;
using pathspace::VcmPrefix;

const VcmPrefix kGvcmPinholePrefix{};

bool gvcm_offset(const GvcmOffsetContext& ctx, const GvcmStrategy& st, const Vec2& offset,
                 gradients::LightTracingShift& lt, gradients::MergeShift& ms, std::vector<VcmPrefix>& off_lp,
                 GvcmOffset& out, GvcmCounters& counters) {
  const gradients::CameraSubpathShift& sh = ctx.shift;
  if (!st.merge && st.t == 1) {  // light tracing: the light subpath rejoined at the offset's y_1
    ++counters.light_shifts;
    const bool ok = gradients::shift_light_tracing(ctx.scene, st.light, st.s, st.raster, offset, ctx.shift_options, lt);
    if (lt.walked) counters.walks.merge(lt.chain.stats);
    if (!ok) {
      ++counters.light_fail[size_t(lt.status)];
      counters.light_chain += lt.specular_chain;
      return false;
    }
    ++counters.light_shifted;
    const int n = int(lt.light.size());
    off_lp.resize(size_t(n));
    pathspace::vcm_prefixes(lt.light.data(), n, false, ctx.mis, off_lp.data());
    out.value = lt.value;
    out.R = lt.mis_ratio;
    out.w = double(pathspace::vcm_connection_weight(ctx.scene, lt.light.data(), off_lp.data(), st.s, ctx.camera.data(),
                                                    &kGvcmPinholePrefix, 1, ctx.mis));
    return true;
  }
  if (!st.merge) {  // camera strategy: the offset camera prefix with the same light subpath
    const gradients::StrategyOffset so = gradients::camera_strategy_offset(sh, ctx.camera, st.t);
    if (!so.exists) return false;
    pathspace::Connection c;
    const bool ok = pathspace::connect(ctx.scene, st.light, st.s, sh.path.data(), st.t,
                                       pathspace::MisConfig{.unweighted = true}, c, so.test_visibility);
    counters.connections += c.tested;
    counters.occluded += c.occluded;
    if (!ok) return false;
    out.value = c.value;
    out.R = so.mis_ratio;
    out.w = double(pathspace::vcm_connection_weight(ctx.scene, st.light, st.lp, st.s, sh.path.data(),
                                                    ctx.off_cp.data(), st.t, ctx.mis));
    return true;
  }
  // Merges: the base's kernel normalises the offset's value too (f(Tx)|T'| / p(x)); R
  // carries the ratio of the two kernels' areas, eta_k(Tx) / eta_k(x) (adaptive kernel,
  // pathspace/vcm_mis.h; 1 without it), as the merge's density holds pi r^2.
  const int k = st.t - 1;
  const double shrink_base = ctx.cp[size_t(k - 1)].m;
  const float norm = merge_kernel(1.0f, ctx.merge_norm, ctx.cp.data(), st.t).norm;
  if (sh.rejoined && k >= sh.join && k < int(sh.path.size())) {  // case 1: z_k and the photon shared
    ++counters.merge_case1;
    const BidirVertex& zk = sh.path[size_t(k)];
    out.value = merge_bsdf(zk, st.photon.wi) * st.photon_beta * zk.beta * norm;
    out.R = sh.mis_ratio[size_t(st.t)] * (ctx.off_cp[size_t(k - 1)].m / shrink_base);
    out.w = double(pathspace::vcm_merge_weight(st.photon, sh.path.data(), ctx.off_cp.data(), st.t, ctx.mis));
    return true;
  }
  if (k != sh.b) {  // a mixed vertex before b, or after a shift that did not rejoin: no map
    ++counters.merge_unshiftable;
    return false;
  }
  // Case 2: the photon's light subpath rejoined at z_b^off (a probabilistic connection).
  if (k - 1 >= int(ctx.off_cp.size())) return false;
  ++counters.merge_case2;
  const bool ok = gradients::shift_merge(ctx.scene, st.light, st.j, ctx.camera, sh, ctx.shift_options, ms);
  if (ms.walked) counters.walks.merge(ms.chain.stats);
  if (!ok) {
    ++counters.merge_fail[size_t(ms.status)];
    counters.merge_chain += ms.specular_chain;
    return false;
  }
  ++counters.merge_case2_shifted;
  const int n = int(ms.light.size());
  off_lp.resize(size_t(n));
  pathspace::vcm_prefixes(ms.light.data(), n, false, ctx.mis, off_lp.data());
  out.value = ms.value * norm;
  out.R = ms.direction_ratio * ms.area_ratio * (ctx.off_cp[size_t(k - 1)].m / shrink_base);
  const pathspace::VcmPhotonMis pm = pathspace::vcm_photon_mis(ms.light.data(), off_lp.data(), n - 1);
  out.w = double(pathspace::vcm_merge_weight(pm, sh.path.data(), ctx.off_cp.data(), st.t, ctx.mis));
  return true;
}

}  // namespace dp::integrators
