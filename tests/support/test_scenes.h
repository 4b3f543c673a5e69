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

// A caustic-only box: the box of lit_box with black walls and ceiling and a white floor;
// a black shelf at y = 0.3 closes the upper part except a 0.5 x 0.5 opening under the
// ceiling light, and a smooth glass sphere (eta 1.5, radius 0.4) centred in the opening
// fills it, so every light path that reaches the floor passes through the glass (L S+ D):
// the floor is lit by a caustic only. The camera looks down at the floor.
// `fog`: a thin isotropic fog (sigma_s 0.4, sigma_a 0.05) fills the box (the camera's
// medium), so the caustic is also volumetric.
std::unique_ptr<scene::Scene> caustic_box(int resolution, bool fog = false);

// An open scene lit only by a textured environment (a 32x16 lat-long checkerboard held in
// memory: cells of 4x4 texels alternating warm bright (1.6, 1.4, 1.0) and dark blue
// (0.15, 0.2, 0.3)) over a diffuse floor (albedo 0.5, y = -1), with a sphere of BSDF
// `sphere` (null = diffuse; radius 0.6) filling the middle of the view and a small
// diffuse sphere beside it that the big one reflects. Built for G-PT's half-vector copy
// through glossy vertices: with a rough conductor below the shift threshold most camera
// paths are camera -> glossy -> environment (or -> floor / small sphere).
// `sun` > 0 adds a directional light of that irradiance from above-left-front (two
// lights at infinity).
std::unique_ptr<scene::Scene> env_glossy(scene::BsdfPtr sphere, int resolution, float sun = 0.0f);

// The volumetric furnace (issue 15): a sphere of radius 1 at the origin behind an
// index-matched boundary (`material: none`) whose interior is `medium`, under a constant
// environment of radiance `env` and nothing else. With an albedo-1 medium (sigma_a = 0)
// every path escapes unchanged in expectation: every pixel's expected value is `env`.
// camera_inside: the camera sits inside the sphere (the scene's camera medium; the ball
// then names a clear medium, sigma = 0, as its exterior).
std::unique_ptr<scene::Scene> medium_furnace(const scene::HomogeneousMedium& medium, const Rgb& env, bool camera_inside,
                                             int resolution);

// lit_box with media: sphere a an index-matched ball of forward-scattering smoke
// (sigma_s (1.5, 2.5, 3.5), sigma_a 0.2, HG g = 0.5), sphere b a glass ball (eta 1.5)
// filled with an absorbing, weakly scattering tinted medium (isotropic). `fog`: the
// camera's medium is a thin fog (sigma_s 0.15, sigma_a 0.05, g = -0.3) filling the
// closed box, around and between the balls. `glass` false: sphere b is diffuse and
// holds no medium (no caustics; the smoke ball is the only medium besides the fog).
// `point_light`: also a point light in the fog between the balls (equiangular NEE's
// Dirac case).
std::unique_ptr<scene::Scene> media_box(bool fog, int resolution, bool glass = true, bool point_light = false);

// media_box (fog, glass ball) with grid media (scene/media/grid_tracking.h): the smoke
// ball's medium a grid over the ball's box whose density ramps 0 .. 2 along x (sigma_t 2
// at density 1, albedo (0.9, 0.7, 0.5), HG g = 0.5), the fog a 5^3 grid over the whole box
// with densities 0.5 .. 1.5 varying on every axis (sigma_t 0.2, albedo 0.75, g = -0.3);
// the glass ball's tinted medium stays homogeneous.
std::unique_ptr<scene::Scene> grid_media_box(int resolution);

}  // namespace dp::test
