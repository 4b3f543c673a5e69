// Vertex classification defaults (SCENE_FORMAT.md: "roughness < 0.05 or phong exponent >
// 100 is not connectable"), through the two-sided wrapper the YAML loader applies.
#include <catch2/catch.hpp>

#include "pathspace/classify.h"
#include "scene/bsdf/bsdfs.h"

using namespace dp;
using namespace dp::scene;

TEST_CASE("classification follows the scene-format defaults", "[unit]") {
  const float t = pathspace::kDefaultShiftThreshold;
  REQUIRE(t == 0.05f);
  auto grey = constant_texture(Rgb::Constant(0.5f));
  auto conductor = [](float a) {
    return make_two_sided(make_conductor(a, a, MicrofacetType::ggx, ConductorFresnel{}));
  };
  CHECK(pathspace::is_connectable(make_two_sided(make_diffuse(grey)).get(), t));
  CHECK_FALSE(pathspace::is_connectable(make_two_sided(make_mirror(grey)).get(), t));
  CHECK_FALSE(pathspace::is_connectable(make_dielectric(1.5f, 1.0f, 0.0f, MicrofacetType::ggx).get(), t));
  CHECK_FALSE(pathspace::is_connectable(conductor(0.049f).get(), t));
  CHECK(pathspace::is_connectable(conductor(0.05f).get(), t));
  CHECK(pathspace::is_connectable(conductor(0.3f).get(), t));
  CHECK(pathspace::is_connectable(make_two_sided(make_phong(grey, grey, 100.0f)).get(), t));
  CHECK_FALSE(pathspace::is_connectable(make_two_sided(make_phong(grey, grey, 101.0f)).get(), t));
  // A purely diffuse Phong (no specular) is connectable whatever its exponent.
  CHECK(pathspace::is_connectable(make_two_sided(make_phong(grey, constant_texture(Rgb::Zero()), 1000.0f)).get(), t));
  CHECK(pathspace::is_connectable(nullptr, t));
}
