// Reconnection of a shifted medium photon behind a specular chain by a manifold walk
// (G-VPM and kin, Gruson et al. 2018, Sec. 4.3 and 6; Jakob & Marschner 2012).
//
// The photon b = y_s was reached from its last reconnectable vertex, the anchor a (a finite
// light, a smooth surface or a medium vertex: volume_photon_reconnect.h's PhotonParent),
// through Dirac vertices s_1 .. s_m of purely specular surfaces (the lens of SPOTLIGHT).
// The offset photon b' (volume_photon_shift.h) keeps the light prefix up to a; the chain
// pinned at a is walked (manifold/walk.h) until its last ray passes through b': the end
// of the chain is a medium point, represented by a virtual plane through b' normal to the
// base's last segment (manifold::Chain::end_plane); the walk moves the end in that plane.
// Sec. 6: at most 5 walk iterations, and the relaxed acceptance -- the walk may stop as
// soon as its end lies inside the offset gather point's kernel (`accept_distance`); the
// offset photon is then that end, b'' (a bias that vanishes as the radius shrinks).
//
// Measure. With the chain's Dirac constraints integrated out, the photon's density and
// contribution in the volume measure carry the generalized geometry factor
//   D(a -> b) = d w_0 / dA_perp(b)
// (w_0 the direction leaving a, A_perp the area normal to the last segment at b, so that
// dV(b) = dA_perp dt along the last segment), i.e. manifold::generalized_geometry of the
// chain pinned at a without a surface there, ending on the plane through b normal to the
// last segment. Without a chain D = 1 / t^2 (volume_photon_reconnect.h's G). Then
//   f(a -> b) = rho(a; w_0) prod_i [f_i |cos_i|] Tr(a .. b) sigma_s(b) D,
//   p(b | a)  = p_dir(a; w_0) prod_i P_i  prod P(pass) p_ff(t_last) D,
// with f_i |cos_i| = weight_i P_i of the Dirac lobe the light walk sampled at s_i
// (replayed at the offset's vertices with the base's lobe and lobe-selection number,
// importance mode), P_i its selection probability, Tr and P(pass) over every sub-segment
// (index-matched boundaries switch the medium as in the photon tracer), p_ff the free
// flight's density of the last one. The map b -> b' has Jacobian 1 in the volume measure
// (Sec. 4), so the offset photon weighs beta_b f(a -> b') / f(a -> b) and the light side of
// Eq. 19's MIS is p(b' | a) / p(b | a) -- as the plain reconnection, with D in place of
// 1 / t^2.
//
// Failure (counted by the caller, the same for base and offset: the anchor and the chain's
// kind do not change under the shift): the walk fails (Newton, occlusion of the float
// re-trace, TIR, a replayed lobe that does not follow the walked chain), or a chain segment
// other than the last crosses an index-matched boundary (the exact re-trace does not skip
// them), or b' lies in another medium than b.
#pragma once

#include <cstdint>
#include <vector>

#include "gradients/volume_photon_reconnect.h"
#include "manifold/walk.h"
#include "manifold/walk_stats.h"

namespace dp::gradients {

// One Dirac vertex s_i of a photon's chain, as the photon tracer sampled it.
struct PhotonChainStep {
  Vec3 p{0, 0, 0};
  int32_t shape = -1, prim = -1;
  uint32_t lobe = 0;     // the sampled Dirac lobe (scene::BsdfSample::lobe)
  float u_lobe = 0;      // its lobe-selection number
  bool refraction = false;
  float eta = 1;         // refraction: interior over exterior index (manifold/chain.h)
  int medium_out = -1;   // the medium the light leaves s_i into
};

// A photon's specular chain back to its anchor (PhotonParent::chain indexes these).
struct PhotonChain {
  PhotonParent anchor;                // kind medium, surface or light; `medium`: the first segment's
  std::vector<PhotonChainStep> steps; // s_1 .. s_m in light order (m >= 1)
};

// The longest chain the photon tracer records (longer ones: PhotonParent::chain = -1).
constexpr int kMaxPhotonChain = 8;

// Deliberate defects for the tests (test_volume_photon_chain.cpp).
enum class ChainFault : uint8_t {
  none,
  direct_distance,  // D = 1 / |b - s_m|^2 (the plain reconnection's G from the last Dirac vertex)
};

struct ChainReconnectSettings {
  int max_iterations = 5;      // Sec. 6
  double accept_distance = 0;  // relaxed acceptance (Sec. 6): absolute; 0 = exact walk
  ChainFault fault = ChainFault::none;
};

struct ChainReconnection : PhotonReconnection {  // ratio, pdf_ratio, w (at the offset photon), ok
  Vec3 b_offset{0, 0, 0};   // the offset photon: b' (exact walk) or the walk's end b''
  manifold::WalkStatus walk = manifold::WalkStatus::invalid_input;
  bool occluded = false;    // the walked chain's float re-trace was blocked (or left the medium)
};

// D(a -> end) of a chain pinned at a point (manifold/chain.h; the chain's v[0] without a
// surface, its end on a plane normal to the last segment): d w_0 / dA_perp.
manifold::WalkStatus chain_volume_density(const manifold::Chain& chain, double& D,
                                          ChainFault fault = ChainFault::none);

// The manifold chain a, s_1 .. s_m, (plane end through `end` normal to `normal`) of a
// photon chain record; false if a vertex's local geometry cannot be rebuilt.
bool build_photon_chain(const scene::Scene& scene, const PhotonChain& c, const Vec3d& end, const Vec3d& normal,
                        manifold::Chain& out);

// The base side of a reconnection, the same for every shift of one photon (the caller may
// keep it for the photon's other neighbours): the chain re-traced exactly from its anchor,
// ending on the plane through b normal to its last segment, its D, f and p.
struct ChainBase {
  manifold::WalkStatus status = manifold::WalkStatus::invalid_input;  // ok: the rest is valid
  manifold::Chain exact;
  Vec3d last{0, 0, 1};  // unit direction of the last segment
  double D = 0, p = 0;
  Rgb f = Rgb::Zero();
};
ChainBase chain_base(const scene::Scene& scene, const PhotonChain& chain, int photon_medium, const Vec3& b,
                     ChainFault fault = ChainFault::none, manifold::WalkStats* stats = nullptr);

// The reconnection of base photon b (in `photon_medium`; `base` its chain_base) to b_offset.
ChainReconnection reconnect_photon_chain(const scene::Scene& scene, const PhotonChain& chain, const ChainBase& base,
                                         int photon_medium, const Vec3& b_offset, const ChainReconnectSettings& settings,
                                         manifold::WalkStats* stats = nullptr);
// The same, computing the base side first.
ChainReconnection reconnect_photon_chain(const scene::Scene& scene, const PhotonChain& chain, int photon_medium,
                                         const Vec3& b, const Vec3& b_offset, const ChainReconnectSettings& settings,
                                         manifold::WalkStats* stats = nullptr);

}  // namespace dp::gradients
