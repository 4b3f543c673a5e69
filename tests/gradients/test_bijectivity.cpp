// Bijectivity of the G-PT shift on real scenes: for every base walk x in pixel i and its
// offset y = T(x) in pixel i+1 (the alive prefix), the reverse shift T^-1(y) must exist
// for the whole prefix, reproduce x's vertices and light points, and the Jacobians of
// the two directions must multiply to 1. Scenes: diffuse, glossy (rough conductor
// below the threshold), mirror, glass, and mixed. Also: IdentityShift is exact.
#include <catch2/catch.hpp>
#include <cstdio>

#include "gradients/reconnection_shift.h"
#include "pathspace/path_builder.h"
#include "scene/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
struct Counts {
  int checked = 0, reverse_ok = 0, half_vector = 0, dirac = 0, reconnect = 0, nee = 0;
  double worst_pos = 0, worst_jac = 0;
};

Counts roundtrip(const scene::Scene& s, float threshold, int samples) {
  pathspace::WalkOptions wo;
  wo.max_depth = 8;
  wo.shift_threshold = threshold;
  const pathspace::PathBuilder builder(s, wo);
  const gradients::ReconnectionShift shift(s, {threshold, true});
  core::Rng rng(3, 9);
  pathspace::IndependentStream stream(rng);
  pathspace::Path x, y;
  gradients::ShiftResult fwd, rev;
  Counts c;
  const int res = s.camera().width();
  for (int i = 0; i < samples; ++i) {
    builder.build(i % (res - 1), (i / (res - 1)) % res, stream, x);
    shift.shift(x, Vec2(1, 0), fwd);
    if (fwd.alive < 2) continue;
    y = fwd.path;
    y.vertices.resize(size_t(fwd.alive));
    y.nee.resize(size_t(fwd.alive));
    for (int k = 0; k < fwd.alive; ++k)
      if (!fwd.nee_ok(k) || !(y.nee[size_t(k)].pdf > 0.0)) y.nee[size_t(k)].valid = false;  // not an NEE sample of pixel j
    shift.shift(y, Vec2(-1, 0), rev);
    ++c.checked;
    if (rev.alive != y.size()) continue;
    ++c.reverse_ok;
    for (int k = 0; k < y.size(); ++k) {
      c.worst_pos = std::max(c.worst_pos, double((rev.path[k].p() - x[k].p()).norm()));
      if (k + 1 < y.size()) {
        const auto st = fwd.step[size_t(k)];
        c.half_vector += st == gradients::StepKind::half_vector;
        c.dirac += st == gradients::StepKind::dirac;
        c.reconnect += st == gradients::StepKind::reconnect;
      }
      if (y.nee[size_t(k)].valid && rev.nee_ok(k)) {
        ++c.nee;
        c.worst_pos = std::max(c.worst_pos, double((rev.path.nee[size_t(k)].p - x.nee[size_t(k)].p).norm()));
        c.worst_jac = std::max(c.worst_jac, std::abs(fwd.nee_jacobian[size_t(k)] * rev.nee_jacobian[size_t(k)] - 1.0));
      } else if (y.nee[size_t(k)].valid && !x.nee[size_t(k)].infinite) {
        c.worst_pos = std::max(c.worst_pos, 1.0);  // forward NEE shift exists, reverse does not
      }
    }
    c.worst_jac = std::max(c.worst_jac, std::abs(fwd.prefix_jacobian(y.size() - 1) * rev.prefix_jacobian(y.size() - 1) - 1.0));
  }
  return c;
}

void report(const char* name, const Counts& c) {
  std::printf("bijectivity %-8s checked %d reverse-ok %d  steps: reconnect %d half-vector %d dirac %d, nee %d  "
              "worst |dx| %.2e worst |J J^-1 - 1| %.2e\n",
              name, c.checked, c.reverse_ok, c.reconnect, c.half_vector, c.dirac, c.nee, c.worst_pos, c.worst_jac);
}

scene::BsdfPtr glossy() {
  return scene::make_two_sided(scene::make_conductor(0.05f, 0.05f, scene::MicrofacetType::ggx, scene::ConductorFresnel{}));
}
scene::BsdfPtr mirror() { return scene::make_mirror(scene::constant_texture(Rgb::Constant(0.9f))); }
scene::BsdfPtr glass() { return scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx); }
}  // namespace

TEST_CASE("shift bijectivity T^-1(T(x)) = x on diffuse, glossy, mirror, glass and mixed scenes", "[unit]") {
  struct Case {
    const char* name;
    scene::BsdfPtr a, b;
    float threshold;
  };
  const Case cases[] = {{"diffuse", nullptr, nullptr, 0.001f},
                        {"glossy", glossy(), glossy(), 0.1f},
                        {"mirror", mirror(), nullptr, 0.001f},
                        {"glass", glass(), nullptr, 0.001f},
                        {"mixed", glossy(), glass(), 0.1f}};
  for (const auto& cs : cases) {
    const auto s = test::lit_box(cs.a, cs.b, 24);
    const Counts c = roundtrip(*s, cs.threshold, 3000);
    report(cs.name, c);
    INFO(cs.name);
    REQUIRE(c.checked > 1000);
    REQUIRE(c.reverse_ok == c.checked);
    REQUIRE(c.worst_pos < 2e-3);
    REQUIRE(c.worst_jac < 2e-2);
    REQUIRE(c.reconnect > 100);
    if (std::string(cs.name) == "glossy" || std::string(cs.name) == "mixed") REQUIRE(c.half_vector > 10);
    if (std::string(cs.name) == "mirror" || std::string(cs.name) == "glass") REQUIRE(c.dirac > 10);
  }
}

TEST_CASE("IdentityShift returns the base path with Jacobian 1", "[unit]") {
  const auto s = test::lit_box(nullptr, nullptr, 8);
  const pathspace::PathBuilder builder(*s, {});
  core::Rng rng(1, 1);
  pathspace::IndependentStream stream(rng);
  pathspace::Path x;
  gradients::ShiftResult r;
  builder.build(3, 3, stream, x);
  gradients::IdentityShift().shift(x, Vec2(1, 0), r);
  REQUIRE(r.alive == x.size());
  REQUIRE(r.total_jacobian() == 1.0);
  for (int k = 0; k < x.size(); ++k) REQUIRE(r.path[k].p() == x[k].p());
}
