// Every registered integrator gives bit-identical layers at 1, 2 and 3 threads for a
// fixed seed (and, for `mlt`, a fixed chain count: its default chain count is 4 per
// thread). The comparison can fail: another seed must change the image, and a variant
// of `mlt` that drew its chains' start states from the thread index instead of the chain
// index was watched failing here (at 48x48; at 24x24 one thread took every chain of the
// first round and the variant went unnoticed, hence the size). Sums of doubles formed in
// a thread-dependent order would usually not show after the cast to float: the
// schedulers fix the order anyway (tile_scheduler.h, chain_scheduler.h).
#include <catch2/catch.hpp>

#include "integrators/integrator.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
integrators::RenderResult render(const scene::Scene& s, const std::string& name, int threads, uint64_t seed) {
  integrators::Settings settings;
  if (name == "mlt" || name == "gdmlt" || name == "memlt") {
    settings.set("chains", "5");
    settings.set("bootstrap", "5000");
  }
  auto in = integrators::make_integrator(name, settings);
  integrators::RenderOptions opt;
  opt.spp = 6;  // three progressive passes (1 + 1 + 2) and a remainder of 2
  opt.seed = seed;
  opt.threads = threads;
  opt.max_depth = 6;
  opt.quiet = true;
  return in->render(s, opt);
}

bool identical(const integrators::RenderResult& a, const integrators::RenderResult& b) {
  if (a.layers.size() != b.layers.size()) return false;
  for (size_t l = 0; l < a.layers.size(); ++l) {
    const core::Image &ia = a.layers[l].image, &ib = b.layers[l].image;
    for (int y = 0; y < ia.height(); ++y)
      for (int x = 0; x < ia.width(); ++x)
        if (!(ia(x, y) == ib(x, y)).all()) return false;
  }
  return true;
}
}  // namespace

TEST_CASE("integrators: images do not depend on the thread count", "[render]") {
  // Glossy and glass spheres, so G-PT's half-vector copies and manifold code paths run.
  const auto s = test::lit_box(
      scene::make_conductor(0.02f, 0.02f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                            scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))),
      scene::make_dielectric(1.5f, 1.0f, 0.0f, scene::MicrofacetType::ggx), 48);
  for (const std::string& name : integrators::integrator_names()) {
    INFO("integrator " << name);
    const auto one = render(*s, name, 1, 11);
    CHECK(identical(one, render(*s, name, 2, 11)));
    CHECK(identical(one, render(*s, name, 3, 11)));
    CHECK_FALSE(identical(one, render(*s, name, 2, 12)));
  }
}
