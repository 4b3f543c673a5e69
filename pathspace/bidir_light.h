// Emission sampling for light subpaths (bidirectional methods). Supported lights:
//  * area emitters (meshes and spheres): a point uniform by area (Shape::sample_area,
//    pdf_pos = pmf / A), a cosine-weighted direction about the geometric normal
//    (pdf_dir = cos / pi, solid angle); emission only from the front side.
//  * point lights: delta position (pdf_pos = pmf, a discrete probability), a uniform
//    direction (pdf_dir = 1 / (4 pi)); intensity I = power / (4 pi).
//  * spot lights: delta position, a direction uniform in the cutoff cone
//    (pdf_dir = 1 / (2 pi (1 - cos cutoff))); intensity with the smoothstep falloff.
// Directional and environment emitters are refused (check_bidir_emitters throws
// a ValueError naming the emitter type): the scene layer has no emission sampling for
// them yet. Light selection is the scene's (uniform, Scene::sample_emitter).
#pragma once

#include "pathspace/bidir_vertex.h"

namespace dp::pathspace {

// Throws dp::ValueError if the scene holds an emitter kind the bidirectional code
// cannot sample (or no emitter at all is fine: every light strategy then returns 0).
void check_bidir_emitters(const scene::Scene& scene, const std::string& integrator);

// Density of choosing the light endpoint `v` (kind light, or a surface vertex lying on
// an area emitter): pmf * (1 / area) for area lights, pmf for point lights.
float light_pdf_pos(const scene::Scene& scene, const BidirVertex& v);
// Solid-angle density of emitting toward unit world direction w from light point v.
float light_pdf_dir(const BidirVertex& v, const Vec3& w);
// Emitted radiance (area) or intensity (point) from light point v toward w, times the
// emitter-side cosine |cos theta| for area lights (0 on the back side): the factor the
// light endpoint contributes to a connection.
Rgb light_emit_cos(const BidirVertex& v, const Vec3& w);

}  // namespace dp::pathspace
