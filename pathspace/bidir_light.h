// Emission sampling for light subpaths (bidirectional methods). Supported lights:
//  * area emitters (meshes and spheres): a point uniform by area (Shape::sample_area,
//    pdf_pos = pmf / A), a cosine-weighted direction about the geometric normal
//    (pdf_dir = cos / pi, solid angle); emission only from the front side.
//  * point lights: delta position (pdf_pos = pmf, a discrete probability), a uniform
//    direction (pdf_dir = 1 / (4 pi)); intensity I = power / (4 pi).
//  * spot lights: delta position, a direction uniform in the cutoff cone
//    (pdf_dir = 1 / (2 pi (1 - cos cutoff))); intensity with the smoothstep falloff.
//  * environment and directional lights (at infinity): a direction toward the light
//    (the environment's importance sampling, pdf_dir solid angle; directional: the
//    fixed one, a delta) and a ray origin uniform on a disk of the scene's radius R
//    perpendicular to it, outside the scene (pdf_pos = 1 / (pi R^2), planar). As in
//    pbrt-v3, the origin density of such a vertex is pmf * pdf_dir and the density of
//    the vertex it lights is pdf_pos |cos| there.
// Light selection is the scene's (uniform, Scene::sample_emitter).
#pragma once

#include "pathspace/bidir_vertex.h"

namespace dp::pathspace {

// Density of choosing the light endpoint `v` (kind light, or a surface vertex lying on
// an area emitter): pmf / area for area lights, pmf for point, spot and directional
// lights (discrete), pmf * pdf_dir toward the light for the environment.
float light_pdf_pos(const scene::Scene& scene, const BidirVertex& v);
// Solid-angle density of emitting toward unit world direction w from a finite light
// point v (area, point, spot).
float light_pdf_dir(const BidirVertex& v, const Vec3& w);
// Area density of `next` as the vertex the light endpoint v lights: the direction
// density converted to area (finite lights), pdf_pos |cos at next| (at infinity).
float light_pdf_next(const scene::Scene& scene, const BidirVertex& v, const BidirVertex& next);
// The factor the light endpoint v contributes to a connection toward world direction w
// (away from the light): radiance times the emitter-side |cos| (area lights, 0 on the
// back side), intensity (point, spot), radiance along v's direction (environment),
// irradiance (directional).
Rgb light_emit_cos(const BidirVertex& v, const Vec3& w);
// Origin of a disk ray of a light at infinity: radius R of the scene's bounding sphere.
float infinite_disk_radius(const scene::Scene& scene);

}  // namespace dp::pathspace
