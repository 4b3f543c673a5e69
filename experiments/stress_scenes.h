// Randomized scenes for `deltapath stress`, built in code through the Scene API. Each
// family targets one numerically hard configuration; `variant` re-randomizes offsets,
// sizes, angles and roughness (reproducibly, from (seed, family, variant)):
//   coincident     coplanar quads offset by 1e-6..1e-4, a sliver triangle with vertices
//                  1e-7 apart, a sphere touching the floor, a light a hair above a wall
//   grazing        camera and light within a degree of a large plane (diffuse + glossy)
//   concave        a narrow V-groove (2..10 degrees) and a cove light behind a lip
//   tiny_emitter   sphere lights of radius 1e-4..1e-3 with radiance up to ~1e8 plus a
//                  point light almost touching a wall
//   huge_emitter   the camera inside an emissive sphere of radius 1e4 and a quad light
//                  larger than the scene
//   specular_chain parallel mirrors facing each other, a glass sphere and slab (long
//                  delta chains; max_depth 32)
//   roughness      rough conductors/dielectrics/plastics with alpha from 0.001 to 1 and
//                  Phong exponents from 1 to 1e4
//   media          homogeneous media from 1e-4 to 1e3 per unit length, |g| up to 0.99,
//                  nested index-matched boundaries, a filled glass ball, an unbounded fog
//                  (max_depth 16); integrators without media support ignore them
//   grid_media     8^3 random density grids (empty cells, 50x spikes, scale 1e-2..30) in
//                  an index-matched ball and a glass ball (max_depth 16); only the
//                  integrators that render grid media run it
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace dp::experiments {

struct StressScene {
  std::string family;
  int variant = 0;
  int max_depth = 8;
  std::unique_ptr<scene::Scene> scene;
};

std::vector<std::string> stress_families();
StressScene make_stress_scene(const std::string& family, int variant, uint64_t seed, int resolution);

}  // namespace dp::experiments
