// Merging-kernel radii from the pixel footprint (Sun et al. 2017, Sec. 6: the kernel at the
// first connectable camera vertex about as large as a pixel's footprint, so that the
// kernel's blur and the gradient reconstruction's smoothing do not compound). Used by
// `gpm` (per camera path) and `gvcm` (the median, as the iteration's global radius).
#pragma once

#include "pathspace/bidir_vertex.h"
#include "scene/scene.h"

namespace dp::integrators {

// Radius of the disk at camera vertex z_k whose projection covers one pixel's solid angle:
// pi r^2 |cos_k| / D^2 = Omega_px, D = the prefix's length z_0 .. z_k (exact through planar
// mirrors), Omega_px = 1 / (p_dir(w_0) W H) (the camera's whole-image direction density);
// |cos_k| clamped at 0.1 (a grazing kernel would span the scene).
double footprint_radius(const scene::Scene& scene, const pathspace::BidirVertex* path, int k);

// The median of footprint_radius at the first vertex a camera walk reaches through Dirac
// lobes only (z_b) over a sparse set of pixel centres; 0 if no camera path reaches a
// mergeable vertex.
double median_footprint(const scene::Scene& scene, int max_depth, int rr_depth);
// The first iteration's reference radius: `scale` x median_footprint, or x 0.3% of the
// scene's bounding radius when no camera path reaches a mergeable vertex.
double first_radius(const scene::Scene& scene, int max_depth, int rr_depth, double scale);

}  // namespace dp::integrators
