// One bidirectional strategy (s, t) (vertex convention in bidir_vertex.h): the
// unweighted contribution of the path y_0..y_{s-1} z_{t-1}..z_0 and its MIS weight.
//  * s = 0: camera[t-1] lies on an area emitter: beta_z * Le(z_{t-1} -> z_{t-2}).
//  * t = 1: light tracing. y_{s-1} is connected to the pinhole; the value is what one
//    light path adds to the pixel `raster` falls in, in units where the image is
//    sum(values) * pixel_count / light_paths (Veach 1997, Sec. 10.3.3):
//      beta_y * f_y |cos_y| / d^2 * pdf_direction(w)   (pdf_direction: camera.h).
//  * otherwise: beta_y f_y |cos_y| (1/d^2) |cos_z| f_z beta_z (y_0: Le cos instead of f cos).
// Cosines of scattering factors use shading normals (as the path tracer); area-density
// conversions use geometric normals. Visibility is tested only for non-zero values.
#pragma once

#include "pathspace/bidir_media.h"
#include "pathspace/bidir_mis.h"

namespace dp::pathspace {

struct Connection {
  Rgb value = Rgb::Zero();  // unweighted contribution (0 if the strategy gave nothing)
  float weight = 0;         // MIS weight of (s, t) (1 with MisConfig::unweighted)
  Vec2 raster{0, 0};        // t = 1: where the light vertex projects
  bool tested = false;      // a shadow ray was traced
  bool occluded = false;
};

// Fills `out` for strategy (s, t); returns true if value * weight may be non-zero.
// Needs s + t >= 2, t >= 1, s <= light size, t <= camera size. `test_visibility` false:
// the caller knows the connection segment is unoccluded (a shifted path sharing it).
// `reverse`: the connection's reverse densities if already known (bidir_mis.h).
// `grid`: the rng for the ratio-tracking transmittance of grid media on the connection
// (bidir_media.h); renderers of grid scenes must pass one (null: the deterministic
// stand-in exp(-tau_hat), for MIS-only callers).
bool connect(const scene::Scene& scene, const BidirVertex* light, int s, const BidirVertex* camera, int t,
             const MisConfig& config, Connection& out, bool test_visibility = true,
             const ReversePdfs* reverse = nullptr, GridTracking* grid = nullptr);

}  // namespace dp::pathspace
