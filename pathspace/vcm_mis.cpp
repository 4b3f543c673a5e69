#include "pathspace/vcm_mis.h"

#include <algorithm>
#include <cmath>

namespace dp::pathspace {

namespace {

// Dirac-derived densities are stored as 0 and cancel between strategies (bidir_vertex.h).
double remap(float pdf) { return pdf != 0.0f ? double(pdf) : 1.0; }

struct Heuristic {
  bool power;
  double operator()(double x) const { return power ? x * x : x; }
};

double merge_factor(const VcmMisConfig& c, const Heuristic& h) { return c.eta > 0.0f ? h(double(c.eta)) : 0.0; }

double finite_weight(double w) { return std::isfinite(w) ? w : 0.0; }

}  // namespace

bool vcm_mergeable(const BidirVertex& v, bool interior, float min_roughness) {
  return v.kind == BidirKind::surface && v.bsdf && !v.bsdf->is_purely_delta() && !(interior && v.delta) &&
         !(min_roughness > 0.0f && v.bsdf->roughness() < min_roughness);
}

double vcm_kernel_shrink(const BidirVertex& v, const VcmMisConfig& config) {
  // A vertex the path crossed through a Dirac lobe is specular for the path (tau = 0).
  if (!config.adaptive_kernel || v.kind != BidirKind::surface || !v.bsdf || v.delta) return 1.0;
  const double tau = std::min(1.0, double(v.bsdf->roughness()));  // diffuse: +inf -> 1; Dirac: 0
  return std::exp2(-20.0 * tau);                                  // 0.25^(10 tau) = (0.5^(10 tau))^2
}

void vcm_prefixes(const BidirVertex* path, int n, bool camera_side, const VcmMisConfig& config, VcmPrefix* out) {
  const Heuristic h{config.heuristic == MisHeuristic::power};
  const double V = merge_factor(config, h);
  double interior_prev = 0.0;  // I_{i-1}; light order: its connection-derived part
  double merges_prev = 0.0;    // light order: the merge-derived part of I_{i-1}
  bool merge_prev = false;     // a merge at v_{i-1} (as an interior vertex)
  for (int i = 0; i < n; ++i) {
    const BidirVertex& v = path[i];
    const double inv = h(1.0 / remap(v.pdf_fwd));
    // Connection strategy in which the other side generated v_i and connected it to
    // v_{i-1}: light order i = 0 is the camera walk hitting the light (impossible for
    // delta lights); camera order i = 0 is hitting the pinhole (never), i = 1 light
    // tracing (nothing at infinity projects to the pinhole).
    bool conn = config.connections;
    if (i == 0) conn = conn && !camera_side && !v.is_delta_light();
    else if (camera_side && i == 1) conn = conn && !v.infinite();
    else conn = conn && !path[i - 1].delta;
    VcmPrefix& p = out[i];
    p.a = conn ? inv : 0.0;
    const double rev_prev = i >= 1 ? h(remap(path[i - 1].pdf_rev)) : 0.0;
    if (camera_side) {
      // A merge at v_{i-1} has eta * prod c(v_1 .. v_{i-2}) = eta * m_{i-2}.
      const double v_prev = merge_prev ? V * h(i >= 2 ? out[i - 2].m : 1.0) : 0.0;
      p.b = i >= 1 ? inv * (v_prev + interior_prev) : 0.0;
      p.m = (i >= 1 ? out[i - 1].m : 1.0) * vcm_kernel_shrink(v, config);
    } else {
      // The merge at v_{i-1} enters m with no shrink yet; earlier ones pass v_{i-1}.
      const double c_prev = i >= 1 ? h(vcm_kernel_shrink(path[i - 1], config)) : 1.0;
      p.b = i >= 1 ? inv * interior_prev : 0.0;
      p.m = i >= 1 ? inv * (V * double(merge_prev) + merges_prev * c_prev) : 0.0;
      merges_prev = p.m * rev_prev;
    }
    const bool drop = v.delta && config.fault != VcmFault::dirac_interior_kept;
    interior_prev = (drop ? 0.0 : p.a) + p.b * rev_prev;
    merge_prev = V > 0.0 && vcm_mergeable(v, true, config.min_merge_roughness);
  }
}

float vcm_connection_weight(const scene::Scene& scene, const BidirVertex* light, const VcmPrefix* lp, int s,
                            const BidirVertex* camera, const VcmPrefix* cp, int t, const VcmMisConfig& config) {
  const Heuristic h{config.heuristic == MisHeuristic::power};
  const double V = merge_factor(config, h);
  const ReversePdfs rev = connection_reverse_pdfs(scene, light, s, camera, t);
  // prod c(z_1 .. z_{t-1}): the shrink of every merge on the light side (t = 1: the pinhole's 1).
  const double shrink_camera = cp[t - 1].m;
  double w_light = 0.0, w_camera = 0.0;
  if (s >= 1) {
    const double k = config.fault == VcmFault::shrink_light_side_lost
                         ? 1.0
                         : h(vcm_kernel_shrink(light[s - 1], config) * shrink_camera);
    const double d = s >= 2 ? lp[s - 1].a + (lp[s - 1].b + k * lp[s - 1].m) * h(remap(rev.y[1])) : lp[0].a;
    const bool merge = vcm_mergeable(light[s - 1], false, config.min_merge_roughness);
    w_light = h(remap(rev.y[0])) * (V * h(shrink_camera) * double(merge) + d);
  }
  if (t >= 2) {
    // For s = 0 the camera endpoint is the light endpoint x_0: no merge there.
    const bool merge = s >= 1 && vcm_mergeable(camera[t - 1], false, config.min_merge_roughness);
    const double d = cp[t - 1].a + cp[t - 1].b * h(remap(rev.z[1]));
    w_camera = h(remap(rev.z[0])) * (V * h(cp[t - 2].m) * double(merge) + d);
  }
  return float(finite_weight(1.0 / (1.0 + w_light + w_camera)));
}

VcmPhotonMis vcm_photon_mis(const BidirVertex* light, const VcmPrefix* lp, int j) {
  VcmPhotonMis m;
  m.wi = light[j].wi;
  m.prefix = lp[j];
  m.prev_area = solid_angle_to_area(1.0f, light[j], light[j - 1]);
  return m;
}

float vcm_merge_weight(const VcmPhotonMis& photon, const BidirVertex* camera, const VcmPrefix* cp, int t,
                       const VcmMisConfig& config) {
  const Heuristic h{config.heuristic == MisHeuristic::power};
  const double V = merge_factor(config, h);
  const BidirVertex& z = camera[t - 1];
  if (!(V > 0.0) || !vcm_mergeable(z, false, config.min_merge_roughness)) return 0.0f;
  // y_{j-1} generated by the camera walk continuing from z along the photon's direction,
  // at the distance and cosine of the light path's own segment y_j -> y_{j-1}.
  const float pdf_y_prev = bsdf_pdf(z, z.wi, photon.wi, scene::TransportMode::radiance) * photon.prev_area;
  // z_{t-2} generated by the light walk continuing from z (arriving along the photon's wi).
  const float pdf_z_prev =
      solid_angle_to_area(bsdf_pdf(z, photon.wi, z.wi, scene::TransportMode::importance), z, camera[t - 2]);
  const VcmPrefix& lp = photon.prefix;
  // The merged vertex is z_{t-1}: the light side's merges pass it and z_{t-2} .. z_1.
  const double k = config.fault == VcmFault::shrink_light_side_lost ? 1.0 : h(cp[t - 1].m);
  const double d_light =
      lp.a + (config.fault == VcmFault::merge_without_light_prefix ? 0.0 : (lp.b + k * lp.m) * h(remap(pdf_y_prev)));
  const double d_camera = cp[t - 1].a + cp[t - 1].b * h(remap(pdf_z_prev));
  const double v_self = V * h(cp[t - 2].m);  // eta * prod c(z_1 .. z_{t-2})
  return float(finite_weight(1.0 / (1.0 + (d_light + d_camera) / v_self)));
}

}  // namespace dp::pathspace
