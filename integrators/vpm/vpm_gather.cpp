#include "integrators/vpm/vpm_gather.h"

#include <cmath>

#include "integrators/media_photons/volume_kernel.h"
#include "scene/media/free_flight.h"
#include "scene/media/grid_tracking.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

float sample_truncated_distance(float sigma, float s, float u) {
  if (!(sigma > 0.0f)) return u * s;  // no extinction: uniform (finite s only)
  // Inverse CDF of sigma exp(-sigma t) / (1 - exp(-sigma s)) on [0, s]: exp(-sigma s)
  // underflows to 0 for s = inf (the untruncated exponential).
  return -std::log1p(u * std::expm1(-sigma * s)) / sigma;
}

float truncated_distance_pdf(float sigma, float s, float t) {
  if (!(sigma > 0.0f)) return std::isfinite(s) && s > 0.0f ? 1.0f / s : 0.0f;
  return sigma * std::exp(-sigma * t) / -std::expm1(-sigma * s);
}

Rgb VpmGather::gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
                      GatherCounters& counters) const {
  if (max_photon_depth < 1 || m_photons.empty() || !(seg_len > 0.0f)) return Rgb::Zero();
  const scene::HomogeneousMedium& med = m_scene.media()[size_t(medium)];
  const Rgb st = med.sigma_t();
  // The channels whose truncated exponential is a density on this segment.
  int channels[3], n_ch = 0;
  for (int c = 0; c < 3; ++c)
    if (st[c] > 0.0f || std::isfinite(seg_len)) channels[n_ch++] = c;
  if (n_ch == 0 || is_black(med.sigma_s)) {
    ++counters.empty_segments;
    return Rgb::Zero();
  }
  const bool truncated = m_settings.fault != VpmFault::untruncated_pdf;
  auto pdf = [&](float t) {
    float p = 0.0f;
    for (int k = 0; k < n_ch; ++k) {
      const float sig = st[channels[k]];
      p += truncated ? truncated_distance_pdf(sig, seg_len, t) : sig * std::exp(-sig * t);
    }
    return p / float(n_ch);
  };
  const scene::HenyeyGreenstein phase(med.phase);
  const Vec3 to_camera = -ray.d;
  const int m = m_settings.distance_samples;
  // A grid medium: sigma_t() is its grey scale (density 1), which shapes p(t) (any density
  // on the segment will do); Tr(t) from one ratio-tracking profile of the segment.
  thread_local scene::TransmittanceProfile profile;
  const bool grid = med.heterogeneous();
  if (grid) profile.track(med, ray.o, ray.d, seg_len, rng);
  Rgbd sum = Rgbd::Zero();
  for (int j = 0; j < m; ++j) {
    const int c = channels[std::min(int(rng.uniform() * float(n_ch)), n_ch - 1)];
    const float u = (float(j) + rng.uniform()) / float(m);  // stratified in the CDF
    const float t = std::min(sample_truncated_distance(st[c], seg_len, u), seg_len);
    const float p = pdf(t);
    if (!(p > 0.0f) || !std::isfinite(t)) continue;
    const Vec3 d = ray.at(t);
    ++counters.queries;
    Rgb est = Rgb::Zero();
    m_photons.query_point(d, m_radius, [&](const MediumPhoton& ph, float) {
      if (ph.medium != medium) return;
      if (ph.depth > max_photon_depth) {
        ++counters.depth_skipped;
        return;
      }
      ++counters.photons;
      est += phase.eval(ph.w, to_camera) * ph.beta;  // rho_p at the merged vertex (Eq. 3)
    });
    if (is_black(est)) continue;
    const Rgb tr = m_settings.fault == VpmFault::no_transmittance ? Rgb::Ones()
                   : grid                                          ? Rgb::Constant(profile.at(t))
                                                                   : scene::transmittance(med, t);
    sum += (tr * est / p).cast<double>();
  }
  const int dim = m_settings.fault == VpmFault::kernel_2d_norm ? 2 : 3;
  const double scale = uniform_kernel(dim, double(m_radius)) / (double(m_paths) * double(m));
  return (sum * scale).cast<float>();
}

}  // namespace dp::integrators
