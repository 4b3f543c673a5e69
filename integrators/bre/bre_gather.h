// The beam radiance estimate (Jarosz et al. 2008, Sec. 4; the primal BRE of Gruson et al.
// 2018, Sec. 5.1): the whole camera segment c + t w, t in [0, s], inside a medium is one
// beam query against the photon points. A photon y_k within r of the beam, at projected
// distance t_k in [0, s], contributes through a 2D uniform kernel across the beam and the
// transmittance along it:
//   L_m ~ 1/N sum_k Tr(t_k) rho_p(w_k, -w) beta_k K2(|y_k - (c + t_k w)|)
// (the 3D kernel of Eq. 5 integrated along the beam is a 2D kernel; photon weights as
// photon_tracer.h). Only photons of the same medium and of depth <= the path-length
// budget count. No distance is sampled: the estimate is deterministic given the photons.
// kernel=3d (Point-Beam 3D, Gruson et al. 2018, Sec. 5.1): every photon within r of the
// segment contributes its 3D kernel integrated along it,
//   L_m ~ 1/N sum_k rho_p(w_k, -w) beta_k K3 int_{chord_k} Tr(t) dt
// (volume_kernel.h's chord, scene/media/free_flight.h's integral in closed form): the
// expectation of `vpm`'s gather with its distance sampling integrated out.
#pragma once

#include "integrators/bre/bre_settings.h"
#include "integrators/media_photons/media_camera.h"
#include "integrators/media_photons/photon_bvh.h"

namespace dp::integrators {

class BreGather final : public MediumGather {
 public:
  BreGather(const scene::Scene& scene, const BreSettings& settings, const PhotonBvh& photons, float radius,
            int64_t light_paths)
      : m_scene(scene), m_settings(settings), m_photons(photons), m_radius(radius), m_paths(light_paths) {}
  Rgb gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
             GatherCounters& counters) const override;

 private:
  const scene::Scene& m_scene;
  const BreSettings& m_settings;
  const PhotonBvh& m_photons;
  float m_radius;
  int64_t m_paths;
};

}  // namespace dp::integrators
