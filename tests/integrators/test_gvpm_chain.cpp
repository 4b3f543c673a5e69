// G-VPM's photons behind a specular chain (gradients/volume_photon_chain.h; Gruson et al.
// 2018, Sec. 4.3): a spot light above a glass ball in fog (a small SPOTLIGHT), where every
// photon of the focused cone has the ball's two refractions as its parent chain.
// With the manifold walk (exact acceptance) and without it (those shifts fail: the T_0
// fallback, unbiased and noisier) G-VPM estimates the same gradients of the same
// kernel-blurred image: the image mean of the L2 reconstruction and the 4x4-block means
// of dx and dy (plus the `direct` layer's differences) agree by Welch tests (Sidak,
// family-wise 1%) over 8 runs each. The planted defect ChainFault::direct_distance (the
// chain's density factor D replaced by 1 / |b - s_m|^2) is rejected by the same test.
// Also: the walks run (counters) and the relaxed default reconnects at least as many.
#include <catch2/catch.hpp>
#include <cstdio>

#include "integrators/gvpm/gvpm_integrator.h"
#include "scene/loaders/loader.h"
#include "tests/integrators/media_furnace_support.h"
#include "tests/support/welch.h"

using namespace dp;

namespace {

constexpr int kRes = 16, kBlock = 4, kRuns = 8, kIterations = 12, kDepth = 4;

std::unique_ptr<scene::Scene> lens_fog() {
  const std::string text =
      "version: 1\n"
      "camera: {position: [0, -0.1, -2.6], look_at: [0, -0.2, 0], fov: 40, resolution: [16, 16]}\n"
      "materials: {glass: {type: dielectric, ior: 1.5, ext_ior: 1.0}}\n"
      "media: {fog: {type: homogeneous, sigma_a: [0.02, 0.02, 0.02], sigma_s: [0.4, 0.5, 0.6], phase: {type: hg, g: 0.3}}}\n"
      "shapes:\n"
      "  - {type: sphere, center: [0, 0.45, 0], radius: 0.3, material: glass, exterior: fog}\n"
      "  - {type: sphere, center: [0, 0, 0], radius: 1, material: none, interior: fog}\n"
      "lights: [{type: spot, position: [0, 0.95, 0], direction: [0, -1, 0], intensity: [30, 30, 30], cutoff: 15, "
      "falloff_start: 13}]\n";
  return scene::load_scene_yaml_string(text, "lens_fog.yaml");
}

const core::Image& layer(const integrators::RenderResult& r, const std::string& name) {
  for (const auto& l : r.layers)
    if (l.name == name) return l.image;
  FAIL("no layer " << name);
  return r.layers[0].image;
}

struct Variant {
  bool manifold = true, relaxed = false;
  gradients::ChainFault fault = gradients::ChainFault::none;
};

test::Runs runs_of(const scene::Scene& s, const Variant& v, int64_t* reconnected = nullptr) {
  test::Runs runs;
  for (int k = 0; k < kRuns; ++k) {
    integrators::GvpmSettings g;
    g.photons = 4000;
    g.radius_scale = 0.02;
    g.radius_alpha = 1.0;
    g.distance_samples = 4;
    g.manifold = v.manifold;
    g.manifold_relaxed = v.relaxed;
    g.manifold_iterations = v.relaxed ? 5 : 20;
    g.chain_fault = v.fault;
    const auto r = integrators::GvpmIntegrator(g).render(s, test::quiet_options(kIterations, 900 + uint64_t(k), kDepth));
    if (reconnected) *reconnected += r.stats.get("gvpm.shift.chain_reconnections");
    test::add_run(runs, test::gradient_blocks(layer(r, "recon_l2"), &layer(r, "dx"), &layer(r, "dy"),
                                              &layer(r, "direct"), kBlock));
  }
  return runs;
}

}  // namespace

TEST_CASE("gvpm: photons behind a glass ball, walked or not, give the same gradients", "[stat]") {
  const auto s = lens_fog();
  int64_t walked = 0, relaxed = 0, none = 0;
  const test::Runs off = runs_of(*s, Variant{false}, &none);
  const test::Runs exact = runs_of(*s, Variant{true}, &walked);
  const double ok = test::worst_welch(exact, off, 0.01);
  Variant bad;
  bad.fault = gradients::ChainFault::direct_distance;
  const double rejected = test::worst_welch(runs_of(*s, bad), off, 0.01);
  runs_of(*s, Variant{true, true}, &relaxed);
  std::printf("[gvpm chain] L2 mean %.4f (walk) vs %.4f (no walk); worst |t|/crit %.2f; direct_distance defect %.2f; "
              "chain reconnections: exact %lld, relaxed %lld, without walk %lld\n",
              test::moments(exact[0]).mean, test::moments(off[0]).mean, ok, rejected, (long long)walked,
              (long long)relaxed, (long long)none);
  CHECK(none == 0);
  CHECK(walked > 1000);
  CHECK(relaxed >= walked);
  CHECK(ok < 1.0);
  CHECK(rejected > 1.0);
}
