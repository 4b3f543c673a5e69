#include "integrators/bre/bre_gather.h"

#include "integrators/media_photons/volume_kernel.h"
#include "scene/media/free_flight.h"
#include "scene/media/grid_tracking.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

Rgb BreGather::gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
                      GatherCounters& counters) const {
  if (max_photon_depth < 1 || m_photons.empty() || !(seg_len > 0.0f)) return Rgb::Zero();
  const scene::HomogeneousMedium& med = m_scene.media()[size_t(medium)];
  if (is_black(med.sigma_s)) {
    ++counters.empty_segments;
    return Rgb::Zero();
  }
  const scene::HenyeyGreenstein phase(med.phase);
  const Vec3 to_camera = -ray.d;
  const bool with_tr = m_settings.fault != BreFault::no_transmittance;
  ++counters.queries;
  Rgbd sum = Rgbd::Zero();
  const bool three = m_settings.kernel_dim == 3;
  // A grid medium: Tr and its integral over a chord from one ratio-tracking profile of the
  // segment (grid_tracking.h; unbiased at every distance, and by linearity the integral).
  thread_local scene::TransmittanceProfile profile;
  const bool grid = med.heterogeneous();
  if (grid && with_tr) profile.track(med, ray.o, ray.d, seg_len, rng);
  auto add = [&](const MediumPhoton& ph, const Rgb& camera) {
    if (ph.medium != medium) return;
    if (ph.depth > max_photon_depth) {
      ++counters.depth_skipped;
      return;
    }
    ++counters.photons;
    sum += (camera * phase.eval(ph.w, to_camera) * ph.beta).cast<double>();
  };
  if (three) {  // photons within r of the segment: projections in [-r, seg_len + r]
    const float r = m_radius;
    m_photons.query_beam(ray.o - r * ray.d, ray.d, seg_len + 2.0f * r, r, [&](const MediumPhoton& ph, float t, float d2) {
      float lo = 0, hi = 0;
      if (!point_beam_chord(t - r, d2, r, seg_len, lo, hi)) return;
      add(ph, !with_tr ? Rgb::Constant(hi - lo)
              : grid   ? Rgb::Constant(profile.integral(lo, hi))
                       : scene::integrated_transmittance(med, lo, hi));
    });
  } else {
    m_photons.query_beam(ray.o, ray.d, seg_len, m_radius, [&](const MediumPhoton& ph, float t, float) {
      add(ph, !with_tr ? Rgb::Ones() : grid ? Rgb::Constant(profile.at(t)) : scene::transmittance(med, t));
    });
  }
  const bool wrong_norm = m_settings.fault == BreFault::kernel_3d_norm;
  const int dim = wrong_norm ? 5 - m_settings.kernel_dim : m_settings.kernel_dim;
  return (sum * (uniform_kernel(dim, double(m_radius)) / double(m_paths))).cast<float>();
}

}  // namespace dp::integrators
