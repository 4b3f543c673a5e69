// PrimarySampleStream: building a path, then replaying its recorded primary samples,
// gives the identical path; a mutated coordinate gives a different one (so the
// comparison can fail). Also checks the path convention (camera first) and that the
// walk's f/p matches the contribution helpers.
#include <catch2/catch.hpp>

#include "pathspace/measure.h"
#include "pathspace/path_builder.h"
#include "scene/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
bool same_path(const pathspace::Path& a, const pathspace::Path& b) {
  if (a.size() != b.size() || !(a.raster == b.raster)) return false;
  for (int k = 0; k < a.size(); ++k) {
    if (a[k].kind != b[k].kind || !(a[k].p() == b[k].p()) || a[k].lobe != b[k].lobe || a[k].pdf != b[k].pdf ||
        !(a[k].f_cos == b[k].f_cos).all())
      return false;
    const auto &la = a.nee[size_t(k)], &lb = b.nee[size_t(k)];
    if (la.valid != lb.valid || !(la.p == lb.p) || la.pdf != lb.pdf || la.visible != lb.visible) return false;
  }
  return true;
}
}  // namespace

TEST_CASE("pathspace: replaying recorded primary samples rebuilds the identical path", "[unit]") {
  const auto s = test::lit_box(scene::make_two_sided(scene::make_conductor(0.1f, 0.1f, scene::MicrofacetType::ggx,
                                                                          scene::ConductorFresnel{})),
                               scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), 16);
  pathspace::WalkOptions opt;
  opt.max_depth = 12;
  opt.rr_depth = 3;
  const pathspace::PathBuilder builder(*s, opt);
  core::Rng rng(5, 1);
  int compared = 0, long_paths = 0, mutated_differs = 0;
  for (int i = 0; i < 200; ++i) {
    pathspace::PrimarySampleStream pss(rng);
    pathspace::Path a, b, c;
    builder.build(i % 16, (i / 16) % 16, pss, a);
    REQUIRE(a[0].kind == pathspace::VertexKind::camera);  // camera end first
    const size_t used = pss.used();
    pss.rewind();
    builder.build(i % 16, (i / 16) % 16, pss, b);
    REQUIRE(pss.used() == used);
    REQUIRE(same_path(a, b));
    ++compared;
    long_paths += a.size() > 3;
    // Mutating the first BSDF coordinate of x_1 changes the path (the test can fail).
    if (a.size() > 2 && a[1].continued() && !a[1].delta_lobe() && pss.samples().size() > 6) {
      pss.mutable_samples()[6] = std::fmod(pss.samples()[6] + 0.37f, 1.0f);
      pss.rewind();
      builder.build(i % 16, (i / 16) % 16, pss, c);
      mutated_differs += !same_path(a, c);
    }
  }
  INFO("compared " << compared << ", long " << long_paths << ", mutated & different " << mutated_differs);
  REQUIRE(long_paths > 20);
  REQUIRE(mutated_differs > 20);
}

TEST_CASE("pathspace: geometry term and area pdf follow their definitions", "[unit]") {
  pathspace::Vertex a, b;
  a.hit.p = Vec3(0, 0, 0);
  a.hit.ng = Vec3(0, 0, 1);
  b.hit.p = Vec3(0, 0, 2);
  b.hit.ng = Vec3(0, 0, -1);
  REQUIRE(pathspace::geometry_term(a, b) == Approx(0.25));
  b.hit.ng = Vec3(0, 1, 0);
  REQUIRE(pathspace::geometry_term(a, b) == Approx(0.0).margin(1e-12));
  pathspace::Path p;
  p.append(a).pdf = 2.0;
  b.hit.ng = Vec3(0, 0, -1);
  p.append(b);
  REQUIRE(pathspace::pdf_area(p, 0) == Approx(2.0 * 1.0 / 4.0));
}
