#include "integrators/bre/bre_gather.h"

#include "integrators/media_photons/volume_kernel.h"
#include "scene/media/free_flight.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

Rgb BreGather::gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
                      GatherCounters& counters) const {
  (void)rng;
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
  m_photons.query_beam(ray.o, ray.d, seg_len, m_radius, [&](const MediumPhoton& ph, float t, float) {
    if (ph.medium != medium) return;
    if (ph.depth > max_photon_depth) {
      ++counters.depth_skipped;
      return;
    }
    ++counters.photons;
    const Rgb tr = with_tr ? scene::transmittance(med, t) : Rgb::Ones();
    sum += (tr * phase.eval(ph.w, to_camera) * ph.beta).cast<double>();
  });
  const int dim = m_settings.fault == BreFault::kernel_3d_norm ? 3 : 2;
  return (sum * (uniform_kernel(dim, double(m_radius)) / double(m_paths))).cast<float>();
}

}  // namespace dp::integrators
