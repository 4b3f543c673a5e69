// Renders for the ASan + UBSan build (scripts/test_sanitize.sh, ctest label `sanitize`):
// every registered integrator (integrator_names(), so a new one is covered without
// editing this file) on tiny scenes at 1, 2 and 3 threads, plus the settings that
// change memory layout or scheduling: G-PT with shift=manifold and MLT with explicit
// chain counts (fewer, as many as and more chains than threads). What fails here is
// mostly the sanitizer aborting the process; the assertions add that every layer is
// finite and the image is not black (so a render that silently did nothing fails too).
// Also built and run without sanitizers, where it is a quick smoke test.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "integrators/integrator.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
constexpr int kRes = 16, kSpp = 2, kDepth = 6;
using KeyValues = std::vector<std::pair<std::string, std::string>>;

// Lit box with a rough gold-like conductor and a smooth glass sphere: diffuse, glossy
// and specular vertices, caustics for the manifold shift.
std::unique_ptr<scene::Scene> box() {
  auto glossy = scene::make_two_sided(scene::make_conductor(0.2f, 0.2f, scene::MicrofacetType::ggx,
                                                            scene::ConductorFresnel{},
                                                            scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))));
  auto glass = scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx);
  return test::lit_box(glossy, glass, kRes);
}

// Diffuse furnace sphere with an emissive wall and a point light at the centre.
std::unique_ptr<scene::Scene> furnace() { return test::furnace_sphere(0.5f, 0.5f, 1.0f, kRes); }

// Renders and checks every layer: the right size, all channels finite, the main image
// not black (both scenes are lit everywhere the camera looks).
void render_and_check(const scene::Scene& s, const std::string& name, const KeyValues& set, int threads) {
  integrators::Settings settings;
  for (const auto& [key, value] : set) settings.set(key, value);
  auto integrator = integrators::make_integrator(name, settings);
  integrators::RenderOptions opt;
  opt.spp = kSpp;
  opt.seed = 11;
  opt.threads = threads;
  opt.max_depth = kDepth;
  opt.quiet = true;
  const integrators::RenderResult r = integrator->render(s, opt);
  REQUIRE_FALSE(r.layers.empty());
  for (const auto& layer : r.layers) {
    INFO("layer '" << layer.name << "'");
    CHECK(layer.image.width() == kRes);
    CHECK(layer.image.height() == kRes);
    CHECK(layer.image.count_nonfinite() == 0);
  }
  const Rgbd mean = r.layers[0].image.mean();
  CHECK(std::isfinite(mean.sum()));
  CHECK(mean.sum() > 0.0);
}

// Keys that only set how much preparatory work an integrator does (MLT's default
// bootstrap of 100k paths is most of a 16x16 render's time under ASan), lowered for
// every integrator whose settings listing shows it reads them.
const KeyValues kEffort = {{"bootstrap", "2000"}};

KeyValues with_low_effort(const std::string& name, KeyValues set) {
  integrators::Settings probe;
  integrators::make_integrator(name, probe);
  const std::string listing = "\n" + probe.describe();  // "  key = default  : doc" lines
  for (const auto& [key, value] : kEffort) {
    const bool read = listing.find("\n  " + key + " = ") != std::string::npos;
    const bool given = std::any_of(set.begin(), set.end(), [&](const auto& kv) { return kv.first == key; });
    if (read && !given) set.emplace_back(key, value);
  }
  return set;
}

void render_all_threads(const std::string& name, const KeyValues& given) {
  const KeyValues set = with_low_effort(name, given);
  std::vector<std::pair<std::string, std::unique_ptr<scene::Scene>>> scenes;
  scenes.emplace_back("lit box", box());
  scenes.emplace_back("furnace", furnace());
  for (const auto& [scene_name, s] : scenes)
    for (int threads = 1; threads <= 3; ++threads) {
      std::string what = name;
      for (const auto& [key, value] : set) what += " " + key + "=" + value;
      INFO(what << ", " << scene_name << ", " << threads << " thread(s)");
      render_and_check(*s, name, set, threads);
    }
}
}  // namespace

TEST_CASE("sanitize: every registered integrator renders finite images at 1, 2 and 3 threads", "[sanitize]") {
  const std::vector<std::string> names = integrators::integrator_names();
  REQUIRE(names.size() >= 3);  // path, gpt, mlt at least: the registry was read
  for (const auto& name : names) render_all_threads(name, {});
}

TEST_CASE("sanitize: G-PT with the manifold shift", "[sanitize]") {
  render_all_threads("gpt", {{"shift", "manifold"}});
}

TEST_CASE("sanitize: MLT with 1, 3 and 5 chains", "[sanitize]") {
  REQUIRE(with_low_effort("mlt", {}).size() == 1);  // the bootstrap key was found and lowered
  for (const char* chains : {"1", "3", "5"}) render_all_threads("mlt", {{"chains", chains}});
}
