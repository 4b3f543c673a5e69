// The state of a path-space Markov chain (Veach 1997, Ch. 11; docs/memlt_plan.md, Sec. 6-7):
// one full path, light end first, x_0 on a light (kind light) .. x_K the pinhole, with the
// vertex conventions of pathspace/bidir_vertex.h. `delta` of a vertex marks the path's
// component there: a Dirac lobe (the vertex's measure is discrete; it can neither end a
// connection nor bound a mutation), else a smooth lobe.
//
// The target is f = lum F (F the measurement contribution). Mutations never need F itself:
// every ratio they form is one of C_s = F / p_s, the unweighted contribution of the path
// as BDPT strategy s (s light vertices, K + 1 - s camera vertices) samples it, with
// p_s the product of all its vertex densities (Dirac lobes: their discrete probability,
// the deltas of F and p_s cancel). evaluate_path() computes every C_s from the vertex
// positions alone, exactly as BDPT's connect() would for subpaths with those vertices:
//   C_s = beta_light(x_0 .. x_{s-1}) * connection(x_{s-1}, x_s) * beta_camera(x_s .. x_K).
// For a consistent F (flat shading) all C_s p_s agree; with interpolated shading normals
// the light and camera sides evaluate slightly different F (no adjoint correction, as
// BDPT), and the state's F is that of its first valid strategy (`ref`).
// Visibility is not tested here: the edges of a state come from walks, and a mutation
// tests the one edge it connects.
#pragma once

#include <vector>

#include "pathspace/bidir_vertex.h"

namespace dp::mcmc {

struct PathState {
  std::vector<pathspace::BidirVertex> v;  // x_0 (light) .. x_K (pinhole)
  // Per strategy s = 0 .. K: 1 / lum(C_s), 0 where strategy s cannot sample the path (a
  // connection at a Dirac vertex, the camera walk hitting a point light, ...).
  std::vector<double> inv_c;
  int ref = -1;               // the first valid strategy
  Rgb c_ref = Rgb::Zero();    // C_ref (what BDPT's strategy `ref` adds for this path)
  Vec2 raster{0, 0};          // where the eye edge x_{K-1} x_K meets the image
  bool nonfinite = false;     // a strategy's value was NaN or infinite (the path is refused)
  // Extended path space (gdmlt, mcmc/path_gradient.h): the target is lum F * factor, with
  // u_pair a uniform coordinate the chain redraws at every proposal (it picks the
  // neighbour j); pair = the splatted pair sample per lum F, into gradient row pair_row.
  // Unused (factor 1) by the primal chains.
  double u_pair = 0;
  double factor = 1;
  Rgb pair = Rgb::Zero();
  int64_t pair_row = -1;

  int depth() const { return int(v.size()) - 1; }
  Rgb colour() const { return c_ref / luminance(c_ref); }  // F / lum F, the splat's colour
};

// Subpath copies evaluate_path() fills: `light` = x_0 .. x_K walked from the light
// (importance mode, wi toward x_{i-1}, beta from the positions), `camera` = x_K .. x_0
// walked from the pinhole (radiance mode). Kept to reuse their allocation.
struct PathSides {
  std::vector<pathspace::BidirVertex> light, camera;
};

// Fills inv_c, ref, c_ref and raster of `state` from its vertices (state.v, with `delta`,
// `lobe` and `u_lobe` of Dirac vertices set). False if no strategy gives a finite
// non-zero contribution, the eye edge misses the image, or a value is not finite
// (`nonfinite`: a NaN from a BSDF or light must never reach a chain).
bool evaluate_path(const scene::Scene& scene, PathState& state, PathSides& sides);

// Fills `sides` for the path's vertices v (x_0 .. x_K) without evaluating any strategy:
// the light walk's copy and the camera walk's (with each vertex's pdf_out / weight_out as
// a camera walk through these vertices records them; rr_out = 1).
void path_sides(const scene::Scene& scene, const std::vector<pathspace::BidirVertex>& v, PathSides& sides);

// Unit direction from vertex `from` toward vertex `to` (along a light at infinity's direction).
Vec3 direction_between(const pathspace::BidirVertex& from, const pathspace::BidirVertex& to);

// The full path of BDPT strategy (s, t) of the given subpaths (pathspace/bidir_subpath.h):
// light[0 .. s-1] then camera[t-1 .. 0]; for s = 0 the camera vertex on the emitter
// becomes the light endpoint. The connection's ends are smooth (delta false).
void path_of_strategy(const pathspace::BidirVertex* light, int s, const pathspace::BidirVertex* camera, int t,
                      std::vector<pathspace::BidirVertex>& out);

}  // namespace dp::mcmc
