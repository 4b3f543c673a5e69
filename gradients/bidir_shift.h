// G-BDPT shifts of bidirectional paths (Manzi et al. 2015, Sec. 4; ALGORITHMS.md, G-BDPT;
// read for understanding: mmanzi/gradientdomain-mitsuba, docs/gbdpt_reference_notes.md).
// One map T on full paths x_0 (pinhole) .. x_{n-1} (light), written camera end first, for
// every strategy (s, t) that can sample the path (vertex convention: pathspace/bidir_vertex.h):
//  * y_0 = x_0; the primary ray through the base's raster position + the pixel offset
//    (same sub-pixel position: Jacobian 1 in raster coordinates);
//  * Dirac copies: while the base scattered through a Dirac lobe at x_k, y_k scatters
//    through the same lobe (same lobe-selection number; Jacobian 1); base and offset must
//    agree on hitting the scene;
//  * b = the first vertex where the path has a smooth lobe (a connection vertex always
//    has one): y_b must be connectable too, and the next vertex x_{b+1} must be
//    connectable (a smooth lobe, a light, or a connection vertex); then y_b reconnects to
//    x_{b+1} (visibility tested from y_b -- along the base's direction for a light at
//    infinity, never from the base's origin) and shares every later vertex;
//  * if instead x_{b+1} .. x_{c-1} is a specular chain ending at a connectable x_c, the
//    chain pinned at x_c is walked to end at y_b (Manzi's manifold walk b..c,
//    bidir_chain.h) and the offset shares x_c and every later vertex. Light-tracing paths
//    (b = 1) walk the same chain from the light side, so every strategy applies one map.
// Every decision depends on (x_k, y_k, x_{k+1}) symmetrically, so T is a bijection between
// the paths it succeeds on in the two pixels; a failed shift, or an offset of zero value,
// is the T_0 fallback (the pair is not formed; each pixel keeps its own estimate).
// Measures: the camera-side factors are in camera-walk coordinates (raster, solid-angle
// directions; the reconnection factor is the solid-angle one, jacobians.h), the light side
// in area measure; the light side is shared by every camera strategy, so its factors cancel.
#pragma once

#include <vector>

#include "gradients/bidir_chain.h"
#include "gradients/light_rejoin.h"
#include "gradients/shift.h"
#include "pathspace/bidir_vertex.h"

namespace dp::gradients {

// The shift of a camera subpath x_0 .. x_{n-1} (pathspace::camera_subpath) into the
// neighbouring pixel. `path` holds y_0 .. y_b (own vertices) and, after a successful
// reconnection, x_{b+1} .. x_{n-1} (the base's, wi re-derived at x_{b+1}); densities are
// re-derived from positions (pathspace::recompute_densities). beta of each offset vertex
// is f(y) |T'| / p(x) up to it: the offset's throughput over the BASE's sampling
// densities (Russian roulette follows the base), so a connection of the offset prefix
// with the base's light subpath (pathspace::connect) yields f(T x) |T'| / p(x) directly.
struct CameraSubpathShift {
  std::vector<pathspace::BidirVertex> path;
  ShiftStatus status = ShiftStatus::ok;  // why vertex `alive` (or the reconnection) failed
  int alive = 0;           // vertices [0, alive) of `path` exist
  int b = -1;              // first base vertex with a smooth lobe (-1: not reached)
  bool rejoined = false;   // y_b reconnected to x_{b+1}, or rejoined at the end of a walked chain
  int join = -1;           // the first shared vertex: b + 1, or the walked chain's end c
  bool specular_chain = false;  // failed because x_{b+1} starts a chain that cannot be walked
  bool walked = false;     // a chain walk was attempted (chain.stats counts it)
  BidirChainWalk chain;    // the walk's result
  double jacobian = 1;     // solid-angle factor at b (reconnection or walked chain)
  std::vector<double> mis_ratio;  // per t: q_t(T x) |T'| / q_t(x) of the camera prefix (MIS densities)
};

void shift_camera_subpath(const scene::Scene& scene, const std::vector<pathspace::BidirVertex>& base,
                          const Vec2& raster, const Vec2& offset, const BidirShiftOptions& options,
                          CameraSubpathShift& out);

// The offset of camera strategy (s, t >= 2) of the base, from its camera subpath's shift:
// the offset camera prefix is shift.path[0 .. t-1] with the base's light subpath.
struct StrategyOffset {
  bool exists = false;
  bool test_visibility = true;  // false: the connection segment is the base's own (shared)
  bool same_reverse = false;    // x_{t-1}, x_{t-2} and the light side are the base's: so are
                                // the connection's reverse densities (bidir_mis.h)
  double mis_ratio = 1;         // q_st(T x) |T'| / q_st(x) in the MIS densities of bidir_mis.h
};
StrategyOffset camera_strategy_offset(const CameraSubpathShift& shift,
                                      const std::vector<pathspace::BidirVertex>& base, int t);

// The shift of a light-tracing path (strategy (s, 1), s >= 2): camera, x_1 = light[s-1],
// light[s-2], ..., light[0]. The offset's first vertex is the primary hit y_1 through
// raster + offset; it reconnects to light[s-2], or, if light[s-2] .. light[e+1] is a
// specular chain ending at light[e], the chain pinned at light[e] is walked to end at y_1.
// `light` receives the offset light subpath (the base's vertices up to the shared one, the
// walked chain, y_1; densities re-derived); `value` = f(T x)|T'| / p(x) of the
// light-tracing strategy (its pixel is the base's pixel + offset).
struct LightTracingShift : LightRejoin {  // the rejoin at y_1 (light_rejoin.h) plus the camera's factors
  Rgb value = Rgb::Zero();  // f(T x)|T'| / p(x) of strategy (s, 1)
  double mis_ratio = 1;     // q_s1(T x) |T'| / q_s1(x)
  double jacobian = 1;      // area factor |dy_1 / dx_1| = p_cam(x_1) / p_cam(y_1)
};

bool shift_light_tracing(const scene::Scene& scene, const pathspace::BidirVertex* light, int s, const Vec2& raster,
                         const Vec2& offset, const BidirShiftOptions& options, LightTracingShift& out);

// Area density with which the pinhole's whole-image sampling reaches surface vertex v
// (pdf_direction |cos_v| / d^2; geometric normal).
double camera_area_pdf(const scene::Scene& scene, const pathspace::BidirVertex& v);

}  // namespace dp::gradients
