// The point-point estimate of volumetric photon mapping (Jensen & Christensen 1998; as
// Gruson et al. 2018, Sec. 4, sample it): along a camera segment of length s inside a
// medium, `distance_samples` gather distances t_j, stratified in the CDF of
//   p(t) = 1/3 sum_c sigma_t[c] exp(-sigma_t[c] t) / (1 - exp(-sigma_t[c] s))   (Eq. 14,
// truncated to the segment, the channel mixture of free_flight.h; a channel without
// extinction is uniform on a finite segment and left out of an infinite one), and at each
// gather point d = c + t w a 3D point query of radius r:
//   L_m ~ 1/M sum_j Tr(t_j) / p(t_j) * 1/N sum_k rho_p(w_k, -w) beta_k K3(d_j - y_k)
// (Eq. 5: tau(d, c) / p(d), the merged vertex's phase function, the photon's throughput
// with sigma_s, the kernel; photon_tracer.h). Only photons of the same medium and of
// depth <= the path-length budget count.
#pragma once

#include "integrators/media_photons/media_camera.h"
#include "integrators/media_photons/photon_bvh.h"
#include "integrators/vpm/vpm_settings.h"

namespace dp::integrators {

// Truncated-exponential distance sampling on [0, s] for one extinction value (s may be
// +inf when sigma > 0): the distance for u in [0, 1) and its density.
float sample_truncated_distance(float sigma, float s, float u);
float truncated_distance_pdf(float sigma, float s, float t);

class VpmGather final : public MediumGather {
 public:
  VpmGather(const scene::Scene& scene, const VpmSettings& settings, const PhotonBvh& photons, float radius,
            int64_t light_paths)
      : m_scene(scene), m_settings(settings), m_photons(photons), m_radius(radius), m_paths(light_paths) {}
  Rgb gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
             GatherCounters& counters) const override;

 private:
  const scene::Scene& m_scene;
  const VpmSettings& m_settings;
  const PhotonBvh& m_photons;
  float m_radius;
  int64_t m_paths;
};

}  // namespace dp::integrators
