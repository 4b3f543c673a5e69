// Every registered integrator either renders participating media or refuses a scene with
// media (check_scene_support: a one-line error naming the integrators that can), never
// renders the media as vacuum silently, which bdpt, gpt and the others did before this
// check (an image of the same scene without its smoke). On a scene without media every
// integrator is accepted. The media-capable set is pinned: an integrator that gains media
// support must say so here (and in the README's table); so is the grid-media-capable set
// (test::grid_media_box).
#include <catch2/catch.hpp>
#include <set>
#include <string>

#include "core/error.h"
#include "integrators/integrator.h"
#include "tests/support/test_scenes.h"

using namespace dp;

TEST_CASE("integrators without media support refuse a scene with media", "[unit]") {
  const auto media = test::media_box(true, 8);
  const auto vacuum = test::lit_box(nullptr, nullptr, 8);
  REQUIRE(media->caps().has_media);
  REQUIRE_FALSE(vacuum->caps().has_media);
  std::set<std::string> capable;
  for (const auto& name : integrators::integrator_names()) {
    integrators::Settings s;
    const auto in = integrators::make_integrator(name, s);
    CHECK_NOTHROW(integrators::check_scene_support(*in, *vacuum));
    if (in->renders_media()) {
      capable.insert(name);
      CHECK_NOTHROW(integrators::check_scene_support(*in, *media));
      continue;
    }
    try {
      integrators::check_scene_support(*in, *media);
      FAIL("integrator " << name << " accepted a scene with media");
    } catch (const ValueError& e) {
      const std::string msg = e.what();
      CHECK(msg.find("integrator " + name + " does not render participating media") != std::string::npos);
      CHECK(msg.find("volpath") != std::string::npos);
      CHECK(msg.find('\n') == std::string::npos);
    }
  }
  CHECK(capable == std::set<std::string>{"path", "volpath", "bdpt", "vpm", "bre", "beam", "plane", "gvpm", "gbre",
                                          "gbeam", "gplane", "gpt"});
}

TEST_CASE("integrators without grid media support refuse a scene with grid media", "[unit]") {
  const auto grid = test::grid_media_box(8);
  std::set<std::string> capable;
  for (const auto& name : integrators::integrator_names()) {
    integrators::Settings s;
    const auto in = integrators::make_integrator(name, s);
    if (in->renders_grid_media()) {
      capable.insert(name);
      CHECK_NOTHROW(integrators::check_scene_support(*in, *grid));
      continue;
    }
    try {
      integrators::check_scene_support(*in, *grid);
      FAIL("integrator " << name << " accepted a scene with grid media");
    } catch (const ValueError& e) {
      const std::string msg = e.what();
      CHECK(msg.find("integrator " + name) != std::string::npos);
      CHECK(msg.find("bdpt") != std::string::npos);
      CHECK(msg.find('\n') == std::string::npos);
    }
  }
  CHECK(capable == std::set<std::string>{"path", "volpath", "bdpt", "vpm", "bre", "beam", "plane"});
}
