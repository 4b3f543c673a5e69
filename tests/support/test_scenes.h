// Small scenes built in code for integrator tests (no files needed).
#pragma once

#include <memory>

#include "scene/scene.h"

namespace dp::test {

// Camera inside a closed sphere (radius 1 at the origin, normals facing inward) with a
// diffuse albedo `albedo` and emitted radiance `emission`, optionally a point light of
// intensity `point_intensity` at the centre. Exact radiance seen everywhere:
//   L = emission / (1 - albedo) + albedo * I / (pi R^2 (1 - albedo)).
std::unique_ptr<scene::Scene> furnace_sphere(float albedo, float emission, float point_intensity, int resolution);
double furnace_radiance(float albedo, float emission, float point_intensity);

// A closed box [-1,1]^3 with a quad light in the ceiling, a diffuse floor/walls and
// two spheres with the given BSDFs (either may be null = diffuse).
std::unique_ptr<scene::Scene> lit_box(scene::BsdfPtr sphere_a, scene::BsdfPtr sphere_b, int resolution);

}  // namespace dp::test
