// Per-camera-sample physics of gradient-domain volumetric photon mapping (G-VPM, Gruson
// et al. 2018, Sec. 4; docs/gvpm_plan.md). One camera sample through a jittered position
// of pixel i:
//  * the primary ray's segments inside media (through index-matched boundaries, up to the
//    first surface) are gathered as `vpm` does (vpm_gather.h: `distance_samples`
//    stratified distances from Eq. 14's truncated pdf, a 3D point query at each), and
//    every (gather point, photon) term is shifted to the four neighbours:
//      camera (Sec. 4.1): the primary ray through the same sub-pixel position of pixel j,
//        traced through the same boundaries; segment k of the base maps to segment k of
//        the offset, the distance is copied (t' = t, Jacobian 1 in (raster, t)); the
//        shift fails when the offset segment is missing, lies in another medium or is
//        not longer than t (Fig. 3; checked in both directions, so symmetric);
//      photon (Sec. 4.2): the mixed shift of Eq. 16 (or the simple one), Jacobian 1;
//      reconnection (Sec. 4.3): a shifted photon is reconnected to its parent
//        (gradients/volume_photon_reconnect.h, reconnect_photon_edge: medium, smooth-
//        surface and finite-light parents, the edge walked through index-matched
//        boundaries, any other surface blocks it), or, behind a purely specular chain,
//        walked to it (gradients/volume_photon_chain.h: a manifold walk of at most
//        `manifold_iterations`, Sec. 6's relaxed acceptance inside the offset kernel);
//        other specular parents and parents at infinity fail, counted;
//    offset value f(Tx)|T'|/p(x) = beta'_k Tr(t) rho_p(w_b', -w') beta_b ratio K / (N M p(t)),
//    MIS (Eq. 19, balance heuristic) w = 1 / (1 + R), R = p'(t) / p(t) (Eq. 14 on the
//    offset segment) x p(b' | a) / p(b | a) (1 for a null shift); a failed shift is the
//    T_0 fallback (the pair's gradient -f(x)/p(x)). Primal as G-PT's pair estimates.
//  gbre (Sec. 5.1) gathers every photon within r of a segment with a gather point uniform
//  on its camera chord; gbeam (Sec. 5.2, Beam-Beam 3D) draws a photon b uniformly on
//  each beam piece's chord near the segment (weight beta Tr(v)/P(v) sigma_s |chord_b|,
//  beam_gather.h) and then a gather point as gbre; the shift is gbre's, b reconnected to
//  the beam's parent. R's light factor for gbeam is the point photon's density ratio times
//  C(b, w_b) / C(b', w_b'), C the chord of the photon's line (through it along its incident
//  direction) within r of the base / offset camera segment: the beam's sampling density up
//  to P(v) / p_ff(v), which is constant for grey media (any density evaluated alike on
//  both sides keeps Eq. 19's weights summing to 1).
//  * Everything else of the camera path -- emission seen directly, surface NEE and BSDF
//    sampling, gathers on segments after the first surface -- is `vpm`'s camera path
//    (media_camera.h) and goes to the `direct` layer unshifted (added to both
//    reconstructions), counted by gvpm.direct_paths.
#pragma once

#include <array>
#include <deque>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/rng.h"
#include "core/stats.h"
#include "gradients/gradient_buffers.h"
#include "gradients/volume_photon_reconnect.h"
#include "integrators/beam/beam_bvh.h"
#include "integrators/gvpm/gvpm_settings.h"
#include "integrators/media_photons/media_camera.h"
#include "integrators/media_photons/photon_bvh.h"
#include "integrators/pair_splats.h"
#include "integrators/plane/plane_gather.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

struct GvpmCounters {
  MediaCameraCounters camera;  // the unshifted (direct) part: vpm's camera path
  int64_t samples = 0, nan_dropped = 0, direct_paths = 0;
  int64_t primary_segments = 0, gather_points = 0, photons_gathered = 0, depth_skipped = 0, empty_segments = 0;
  int64_t shifts = 0, shift_null = 0, shift_simple = 0, shift_reflected = 0, reconnections = 0;
  int64_t fail_segment_missing = 0, fail_medium = 0, fail_distance = 0, fail_occluded = 0, fail_zero = 0;
  std::array<int64_t, gradients::kParentKindCount> fail_parent{};
  int64_t plane_rotations = 0, fail_plane_degenerate = 0, fail_plane_segment = 0;  // gplane (volume_plane_shift.h)
  // Photons behind specular chains (volume_photon_chain.h): walks by status, and
  // reconnections made through a chain.
  manifold::WalkStats walks;
  int64_t chain_reconnections = 0, fail_chain_occluded = 0;
  int64_t pairs_shifted = 0, pairs_fallback = 0, outside_image = 0;
  // prefix: the integrator's name; `names`: how camera.gather is named (gplane: planes).
  void flush(core::Stats& stats, const std::string& prefix, const GatherCounterNames& names = {}) const;
};

struct GvpmSegment {
  Ray ray;          // origin at the segment's start, unit direction
  float len = 0;    // may be +inf
  int medium = -1;
  Rgb beta = Rgb::Ones();  // transmittance of the earlier segments
};

struct GvpmGatherPoint {
  int segment = 0;
  float t = 0, pdf = 0;  // distance from the segment's start, Eq. 14's density
  Vec3 d{0, 0, 0};
  uint32_t first = 0, count = 0;  // its terms
};

struct GvpmTerm {
  const MediumPhoton* photon = nullptr;
  Rgb value = Rgb::Zero();  // base f(x)/p(x)
};

// gplane: one visible hit of a primary segment with a photon plane.
struct GvpmPlaneTerm {
  int segment = 0;
  const MediumPlane* plane = nullptr;
  PlaneHit hit;
  Rgb value = Rgb::Zero();  // base f(x)/p(x)
};

struct GvpmScratch {
  std::vector<GvpmSegment> base, offset;
  std::vector<GvpmGatherPoint> points;
  std::vector<GvpmTerm> terms;
  std::vector<GvpmPlaneTerm> plane_terms;  // gplane
  std::deque<MediumPhoton> beam_photons;  // gbeam: the photons drawn on beams (stable addresses)
  std::unordered_map<const MediumPhoton*, gradients::ChainBase> chain_bases;  // this sample's chain photons
  PairSplats splats;
};

// What one iteration's light pass leaves for the camera samples (all null without media).
struct GvpmLightData {
  const PhotonBvh* photons = nullptr;                             // gvpm, gbre
  const std::vector<gradients::PhotonParent>* parents = nullptr;  // per photon; gbeam: per beam (beam.index)
  const std::vector<gradients::PhotonChain>* chains = nullptr;    // the parents' specular chains (PhotonParent::chain)
  const BeamBvh* beams = nullptr;                                 // gbeam
  const PlaneBvh* planes = nullptr;                               // gplane
  const MediumGather* later = nullptr;  // the gathers of the segments after the first surface
  // gplane: the primary segments' unshifted part (the beams not from scattering events,
  // plane_gather.h's (B)), added to `direct`.
  const MediumGather* primary_unshifted = nullptr;
  int64_t light_paths = 0;
};

class GvpmTracer {
 public:
  GvpmTracer(const scene::Scene& scene, const GvpmSettings& settings, int max_depth, float radius,
             const GvpmLightData& data);
  void sample(int px, int py, core::Rng& rng, GvpmScratch& scratch, gradients::GradientBuffers& buf,
              GvpmCounters& counters) const;

 private:
  void primary_segments(const Ray& primary, std::vector<GvpmSegment>& out) const;
  // Eq. 14's density of gather distance t on a segment of length len in medium m (channel mixture).
  float distance_pdf(const scene::HomogeneousMedium& m, float len, float t, bool truncated) const;
  void gather(const GvpmSegment& seg, int k, core::Rng& rng, GvpmScratch& sc, GvpmCounters& counters) const;
  // gbre's / gbeam's gathers of segment k (its medium `med` scatters: checked by gather()).
  void gather_beam(const GvpmSegment& seg, int k, const scene::HomogeneousMedium& med, core::Rng& rng, GvpmScratch& sc,
                   GvpmCounters& counters) const;
  void gather_beams(const GvpmSegment& seg, int k, const scene::HomogeneousMedium& med, core::Rng& rng,
                    GvpmScratch& sc, GvpmCounters& counters) const;
  // gbre / gbeam: photon ph (within r of the segment; [lo, hi] its chord on it) gets a
  // gather point uniform on the chord; adds the (gather point, photon) term.
  void chord_term(const GvpmSegment& seg, int k, const scene::HomogeneousMedium& med,
                  const scene::HenyeyGreenstein& phase, const MediumPhoton& ph, float lo, float hi, core::Rng& rng,
                  GvpmScratch& sc, GvpmCounters& counters) const;
  void offsets(int nb, int px, int py, const Vec2& raster, GvpmScratch& sc, int w, int h, GvpmCounters& counters) const;
  // gplane (gvpm_plane.cpp): the primary segment's plane hits, and their shifts to
  // neighbour nb (sc.offset already traced).
  void gather_planes(const GvpmSegment& seg, int k, GvpmScratch& sc, GvpmCounters& counters) const;
  void plane_offsets(int nb, int px, int py, GvpmScratch& sc, GvpmCounters& counters) const;

  const scene::Scene& m_scene;
  const GvpmSettings& m_settings;
  int m_max_depth;
  const PhotonBvh* m_photons;
  const std::vector<gradients::PhotonParent>* m_parents;
  const std::vector<gradients::PhotonChain>* m_chains;
  float m_radius;
  bool m_beam;     // gbre's and gbeam's gather points, uniform on a camera chord
  const BeamBvh* m_beams;  // gbeam's photon beams (null otherwise)
  double m_scale;  // K3(r) / (N M), M = 1 for gbre
  const MediumGather* m_later;
  const MediumGather* m_primary_unshifted;
  const PlaneBvh* m_planes;  // gplane's photon planes (null otherwise)
  int64_t m_paths;
  MediaCameraTracer m_camera;
};

}  // namespace dp::integrators
