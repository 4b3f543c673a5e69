// The manifold walk b..c of the G-BDPT shift (Manzi et al. 2015, Sec. 4; Jakob & Marschner
// 2012, Sec. 4-5; docs/gbdpt_reference_notes.md Sec. 7). A full path written camera end
// first has x_b (the first smooth-lobe vertex), a specular chain x_{b+1} .. x_{c-1} (each a
// Dirac lobe of a purely specular BSDF, no emitter, no index-matched refraction) and its
// end x_c (a surface the chain's shapes can be re-traced to: a smooth lobe, an emitter, or
// an area light's endpoint). The offset's y_b replaces x_b; the chain pinned at x_c is
// walked until it ends at y_b (manifold::walk_exact), so the offset rejoins the base at
// x_c and shares every later vertex.
//
// The base sampled the chain from one side: the camera walk (x_b first; radiance) or the
// light walk (x_c first; importance). Its Dirac lobes are replayed from that side at the
// offset's vertices (same lobe and lobe-selection number), whose direction must be the
// walked one up to float round-off.
//
// Jacobians (chains pinned at the same x_c; generalized geometry term G, manifold/
// constraints.h): d w_b = G(b <-> c) / |cos_b| dA_c (the camera-side coordinate, the
// direction at b) and d w_c = G(b <-> c) / |cos_c| dA_b (the light-side coordinate, the
// direction at c), cosines toward the chain's neighbour, geometric normals. Hence
//   end_jacobian   = |d w'_b / d w_b| = [G'/|cos'_b|] / [G/|cos_b|]   (same x_c),
//   start_density  = [G'/|cos'_c|] / [G/|cos_c|] = |d w'_c / dA(y_b)| / |d w_c / dA(x_b)|.
// Without a chain both reduce to the reconnection's solid-angle and area factors.
//
// Invertibility: the reverse shift walks the offset's own float chain back to x_b; that
// walk must converge to the base's chain (Newton's basin is not symmetric near caustic
// folds), else the shift fails (not_invertible), so T(x) exists iff T^-1(T(x)) does.
#pragma once

#include <span>
#include <vector>

#include "gradients/shift.h"
#include "manifold/walk.h"
#include "pathspace/bidir_vertex.h"

namespace dp::gradients {

struct BidirShiftOptions {
  JacobianFault fault = JacobianFault::none;  // tests' negative controls only (shift.h)
  bool walk_chains = true;       // false: specular chains after b fail (T_0 fallback)
  manifold::WalkSettings walk;   // the chain walks' settings (manifold/walk.h)
};

// An offset chain vertex y_k, b < k < c, and its Dirac lobe replayed from the base's side.
struct ChainStep {
  scene::SurfaceHit hit;
  Rgb weight = Rgb::Zero();  // f |cos| / pdf of the lobe
  float pdf = 0;             // its lobe-selection probability
};

struct BidirChainWalk {
  std::vector<ChainStep> steps;  // y_{b+1} .. y_{c-1}, camera order
  double end_jacobian = 1;       // |d w'_b / d w_b| (header)
  double start_density = 1;      // [G'/|cos'_c|] / [G/|cos_c|] (header)
  manifold::WalkStatus walk_status = manifold::WalkStatus::ok;
  manifold::WalkStats stats;     // this shift's walks (forward and reverse)
};

// v may lie inside a walkable chain (a Dirac lobe of a purely specular, non-emitting surface).
bool chain_interior(const pathspace::BidirVertex& v);
// v may end a walkable chain: a surface vertex with a smooth lobe or an emitter, or an
// area light's endpoint.
bool chain_end(const pathspace::BidirVertex& v);

// Walks the chain x = {x_b, x_{b+1}, .., x_c} (camera order; x.size() >= 3) so that it ends
// at y_b; `mode`: radiance if the camera walk sampled the chain, importance if the light
// walk did. ok, or why the offset does not exist (walk failure, occlusion of the float
// re-trace, a replayed lobe that does not follow the walked chain, an irreversible walk).
ShiftStatus walk_bidir_chain(const scene::Scene& scene, std::span<const pathspace::BidirVertex* const> x,
                             const pathspace::BidirVertex& yb, scene::TransportMode mode,
                             const manifold::WalkSettings& settings, BidirChainWalk& out);

}  // namespace dp::gradients
