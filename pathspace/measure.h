// Measurement contribution, pdfs and geometry terms of paths (Veach 1997, Ch. 8).
// Path convention: path.h (camera first). Estimates are returned as f(x) / p(x) where
// p is the walk's density in the product of solid-angle measures (the primary sample is
// uniform in the pixel, so W_e / p of the raster position is 1). Area-measure densities
// convert with dA = d^2 / |cos| dω (Veach 1997, Eq. 8.10).
#pragma once

#include "pathspace/path.h"

namespace dp::pathspace {

// G(a <-> b) = |cos θ_a| |cos θ_b| / |a - b|^2 with geometric normals, no visibility.
double geometry_term(const Vertex& a, const Vertex& b);
// Solid-angle -> area factor at `to` for a direction sampled at `from`: |cos θ_to| / d^2.
double solid_angle_to_area(const Vertex& from, const Vertex& to);
// Area-measure density of x_{k+1} when the walk samples it from x_k (BSDF strategy).
// For an environment vertex it stays in solid angle.
double pdf_area(const Path& path, int k);
// f / p of the prefix x_0..x_k (the walk's throughput on arrival at x_k, RR included).
Rgb throughput(const Path& path, int k);
// f / p of the NEE path (x_0..x_k, nee[k]) without MIS (0 if invalid or occluded).
Rgb nee_estimate(const Path& path, int k);
// f / p of the BSDF path (x_0..x_k), emission of x_k toward x_{k-1}, without MIS.
Rgb emission_estimate(const Path& path, int k);

}  // namespace dp::pathspace
