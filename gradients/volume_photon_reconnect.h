// Reconnection of a shifted medium photon to its parent (G-VPM, Gruson et al. 2018,
// Sec. 4.3; docs/gvpm_plan.md step 4). The photon b = y_s was sampled from its parent
// a = y_{s-1} by a direction at a (phase function, BSDF or emission) and a free-flight
// distance t; the offset photon b' (volume_photon_shift.h) keeps the light prefix
// y_0 .. a and is reconnected to a.
// In the volume measure (Eq. 4: G = 1 / t^2 without cosines at medium vertices) the edge
// a -> b and the vertex b contribute
//   f(a -> b) = rho(a; w) tau(a, b) G(a, b) sigma_s(b) = rho(a; w) Tr(t) sigma_s / t^2,
// with rho(a; w) the phase function (medium parent), the BSDF times |cos| at a (surface
// parent) or the emitted radiance times the emitter's cos (light parent), and the photon
// tracer (integrators/media_photons/photon_tracer.h) sampled b with
//   p(b | a) = p_dir(a; w) p_ff(t) / t^2   (direction x free-flight mixture, dV = t^2 dw dt),
// so its photon weight is beta_a f(a -> b) / p(b | a). The offset photon b' of a shift with
// Jacobian 1 in the volume measure reconnected to a weighs
//   beta_a f(a -> b') / p(b | a) = beta_b f(a -> b') / f(a -> b)       (Eq. 11, light side),
// and the offset light path's own density, for the MIS of Eq. 19, is p(b' | a). In the
// parent's sampling coordinates (w, t) the same reconnection has the Jacobian
//   |d(w', t') / d(w, t)| = t^2 / t'^2                                  (Sec. 4.3)
// -- the ratio of the 1 / t^2 of the volume measure; test_gvpm_reconnect.cpp checks it
// against central differences of the traced map.
// t = |b - a|, w = (b - a) / t; densities per unit volume, f per channel.
#pragma once

#include <cstdint>

#include "core/math.h"
#include "scene/media/medium.h"

namespace dp::scene {
class Bsdf;
class Emitter;
class Scene;
}  // namespace dp::scene

namespace dp::gradients {

struct MediumParent {
  Vec3 a{0, 0, 0};
  Vec3 w_in{0, 0, 1};  // unit direction the light travelled to reach a
};

// Deliberate defect for the tests (test_volume_photon_shift.cpp, test_gvpm_reconnect.cpp):
// f and p in solid angle times distance (no 1 / t^2), so the ratio misses t_b^2 / t_b'^2.
enum class ReconnectFault : uint8_t { none, no_volume_factor };

// p(b | a) per unit volume; 0 at b = a.
float photon_volume_pdf(const MediumParent& parent, const scene::HomogeneousMedium& medium, const Vec3& b,
                        ReconnectFault fault = ReconnectFault::none);
// f(a -> b) per channel (see above); 0 at b = a.
Rgb photon_edge_throughput(const MediumParent& parent, const scene::HomogeneousMedium& medium, const Vec3& b,
                           ReconnectFault fault = ReconnectFault::none);

// The parent of a stored photon, any kind. `kind` says whether (and why not) the photon
// can be reconnected:
//   medium, surface (a smooth lobe was sampled), light (a finite emitter: area, point,
//   spot) -- reconnectable;
//   specular (a Dirac lobe was sampled at a surface parent: reconnected by the manifold
//   walk of volume_photon_chain.h when `chain` >= 0, else the shift fails), light_infinite (environment/directional: the parent is at infinity),
//   none (no record: the light endpoint could not be re-drawn) -- the shift fails (counted; the same for base and offset, since the light prefix is
//   not changed by the shift, so the symmetric MIS stays unbiased).
// An edge may cross index-matched boundaries (straight, media switched):
// reconnect_photon_edge() walks it (at most 16 crossings, else it counts as blocked).
enum class ParentKind : uint8_t { none, medium, surface, light, specular, light_infinite };
constexpr int kParentKindCount = 6;
const char* to_string(ParentKind kind);

struct PhotonParent {
  Vec3 a{0, 0, 0};      // y_{s-1}
  Vec3 w{0, 0, 1};      // medium: the direction light travelled to reach a; surface: toward the previous vertex (wi)
  Vec3 ng{0, 0, 1};     // surface / area light: geometric normal
  Frame shading;        // surface: shading frame
  Vec2 uv{0, 0};        // surface / area light
  const scene::Bsdf* bsdf = nullptr;
  const scene::Emitter* emitter = nullptr;
  int medium = -1;      // the medium the edge leaves a into (-1: vacuum)
  ParentKind kind = ParentKind::none;
  // kind == specular: the index of the photon's specular chain back to its last
  // reconnectable vertex in the photon tracer's chain records (volume_photon_chain.h),
  // -1 if there is none (a Dirac lobe of a BSDF that is not purely specular, an anchor at
  // infinity, too long a chain).
  int32_t chain = -1;
};

// rho(a; w) and its solid-angle sampling density p_dir(a; w) (the header's terms) for a
// reconnectable parent; false where w is impossible (back side of a surface or an area
// light).
bool parent_direction(const PhotonParent& parent, const Vec3& w, Rgb& rho, float& p_dir);

// rho(a; w) and p_dir(a; w) for any reconnectable parent, a medium one included (its
// phase function in the scene's medium parent.medium).
bool anchor_direction(const scene::Scene& scene, const PhotonParent& parent, const Vec3& w, Rgb& rho, float& p_dir);

// A straight segment of a light path from `o` (leaving into `medium`) along unit `w` over
// distance `t`, walked through index-matched boundaries as the photon tracer crosses them:
// Tr and the free-flight pass probability of every sub-segment but the last; the last
// sub-segment's medium and length. `blocked`: a surface that is not an index-matched
// boundary lies before t (or more than 16 boundaries).
struct SegmentMedia {
  Rgb tr = Rgb::Ones();
  double p_pass = 1;
  int medium = -1;  // of the last sub-segment
  float last = 0;   // its length
  bool blocked = false;
};
SegmentMedia walk_segment(const scene::Scene& scene, const Vec3& o, const Vec3& w, float t, int medium);

// f(a -> x) and p(x | a) in the volume measure (the header's formulas) for a reconnectable
// parent in medium `medium`; false (f = 0, p = 0) where the direction a -> x is not
// possible (back side of a surface or an area light, x = a).
bool photon_edge(const PhotonParent& parent, const scene::HomogeneousMedium& medium, const Vec3& x, Rgb& f,
                 float& pdf, ReconnectFault fault = ReconnectFault::none);

// The reconnection of base photon b to offset position b' (both in `medium`; visibility
// of a -> b' is the caller's): ratio = f(a -> b') / f(a -> b) per channel (multiplies the
// photon's weight), pdf_ratio = p(b' | a) / p(b | a) (the light side of Eq. 19's MIS),
// w = the offset photon's incident direction (b' - a) / |b' - a|.
struct PhotonReconnection {
  bool ok = false;
  Rgb ratio = Rgb::Zero();
  double pdf_ratio = 0;
  Vec3 w{0, 0, 1};
};
PhotonReconnection reconnect_photon(const PhotonParent& parent, const scene::HomogeneousMedium& medium, const Vec3& b,
                                    const Vec3& b_offset, ReconnectFault fault = ReconnectFault::none);

// The same through the scene (what the integrator uses): the edges a -> b and a -> b' are
// walked through index-matched boundaries as the photon tracer crosses them (straight;
// each medium segment before the last contributes Tr to f and the free-flight pass
// probability P(pass) to p, vacuum 1; the last segment Tr(t_last) sigma_s and
// p_ff(t_last), in the photon's medium), with G = 1 / t^2 over the whole distance.
// Fails (ok false, `blocked` true) if a surface that is not an index-matched boundary
// lies on a -> b' (visibility), b' is in another medium than `photon_medium`, or b' lies
// on the other side of a surface parent than b (its medium there is not recorded).
PhotonReconnection reconnect_photon_edge(const scene::Scene& scene, const PhotonParent& parent, int photon_medium,
                                         const Vec3& b, const Vec3& b_offset, bool& blocked,
                                         ReconnectFault fault = ReconnectFault::none);

// t^2 / t'^2: the reconnection's Jacobian in the parent's (direction, distance) coordinates.
inline double reconnection_jacobian(const Vec3d& a, const Vec3d& b, const Vec3d& b_offset) {
  return (b - a).squaredNorm() / (b_offset - a).squaredNorm();
}

}  // namespace dp::gradients
