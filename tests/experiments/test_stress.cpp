// The stress harness: every scene family builds, renders lit images with the path
// tracer, and the report and CSV cover every (family, integrator).
#include <catch2/catch.hpp>

#include <sstream>

#include "experiments/stress.h"
#include "experiments/stress_scenes.h"

using namespace dp;
using namespace dp::experiments;

TEST_CASE("stress: every family renders with PT, finite and lit", "[render]") {
  StressOptions o;
  o.quick = true;
  o.threads = 2;
  o.integrators = {"path"};
  const StressReport r = run_stress(o);
  REQUIRE(r.cases.size() == stress_families().size());
  for (const auto& c : r.cases) {
    INFO(c.family);
    CHECK(c.integrator == "path");
    CHECK(c.renders == 2);
    CHECK(c.nonfinite_pixels == 0);
    CHECK(c.max_value > 0);  // the scene is lit and visible
  }
  CHECK(r.nonfinite_pixels() == 0);
  const std::string text = format_stress_report(r);
  CHECK(text.find("specular_chain") != std::string::npos);
  std::istringstream csv(stress_csv(r));
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  CHECK(lines == int(r.cases.size()) + 1);
}

TEST_CASE("stress: scenes are reproducible and variants differ", "[unit]") {
  const StressScene a = make_stress_scene("grazing", 0, 7, 8);
  const StressScene b = make_stress_scene("grazing", 0, 7, 8);
  const StressScene c = make_stress_scene("grazing", 1, 7, 8);
  CHECK(a.scene->camera().position() == b.scene->camera().position());
  CHECK(a.scene->camera().position() != c.scene->camera().position());
  CHECK(make_stress_scene("specular_chain", 0, 1, 8).max_depth == 32);
  CHECK_THROWS(make_stress_scene("nope", 0, 1, 8));
}
