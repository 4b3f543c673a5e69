// Every registered integrator, stopped in-process (the Ctrl-C flag set by another thread
// while it renders), in --spp and --time mode: the result says `partial`, every layer is
// there and finite, and an interrupted --spp render is the whole image at fewer samples
// (every pixel sampled, none black), not a finished part and a black rest. An
// uninterrupted render is not partial. Watched failing before the progressive passes:
// the --spp case rendered tiles to full spp one after another (min_spp 0, most pixels
// black) and `mlt --time` wrote partial = false.
#include <catch2/catch.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "integrators/integrator.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
constexpr int kRes = 32;  // 4 tiles

integrators::RenderResult render(const scene::Scene& s, const std::string& name, int spp, double seconds,
                                 const std::atomic<bool>* stop) {
  integrators::Settings settings;
  if (name == "mlt" || name == "gdmlt" || name == "memlt") settings.set("bootstrap", "2000");  // chains start at once
  auto in = integrators::make_integrator(name, settings);
  integrators::RenderOptions opt;
  opt.spp = spp;
  opt.time_budget = seconds;
  opt.seed = 3;
  opt.threads = 2;
  opt.max_depth = 5;
  opt.quiet = true;
  opt.stop = stop;
  return in->render(s, opt);
}

integrators::RenderResult interrupted(const scene::Scene& s, const std::string& name, int spp, double seconds) {
  std::atomic<bool> stop{false};
  std::thread setter([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
    stop.store(true);
  });
  auto r = render(s, name, spp, seconds, &stop);
  setter.join();
  return r;
}

// Pixels of the final image with a positive value; every layer finite.
int64_t lit_pixels(const integrators::RenderResult& r) {
  int64_t lit = 0;
  for (const auto& layer : r.layers)
    for (int y = 0; y < layer.image.height(); ++y)
      for (int x = 0; x < layer.image.width(); ++x) REQUIRE(layer.image(x, y).allFinite());
  const core::Image& img = r.layers[0].image;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) lit += img(x, y).sum() > 0.0f ? 1 : 0;
  return lit;
}
// The full render's layers, plus, for tile-scheduled integrators, a trailing "spp" layer
// whose per-pixel counts span exactly [min_spp, max_spp] (which pixels the image lacks).
bool same_layers_plus_counts(const integrators::RenderResult& r, const integrators::RenderResult& full) {
  size_t n = r.layers.size();
  if (n == full.layers.size() + 1 && r.layers.back().name == "spp") {
    const core::Image& c = r.layers.back().image;
    float lo = c[0].x(), hi = lo;
    for (size_t i = 0; i < c.size(); ++i) {
      lo = std::min(lo, c[i].x());
      hi = std::max(hi, c[i].x());
    }
    if (!(lo == float(r.min_spp) && hi == float(r.max_spp))) return false;
    --n;
  }
  if (n != full.layers.size()) return false;
  for (size_t i = 0; i < n; ++i)
    if (r.layers[i].name != full.layers[i].name) return false;
  return true;
}
}  // namespace

TEST_CASE("integrators: an in-process stop is reported and keeps a whole image", "[render]") {
  const auto s = test::lit_box(nullptr, nullptr, kRes);
  for (const std::string& name : integrators::integrator_names()) {
    INFO("integrator " << name);
    const auto full = render(*s, name, 16, 0, nullptr);
    CHECK_FALSE(full.partial);
    const int64_t lit_full = lit_pixels(full);
    REQUIRE(lit_full > kRes * kRes / 2);  // the box is lit: most pixels see light

    // --spp far beyond what 0.4 s can render (but finite: the old scheduler finished its
    // tiles in flight at full spp before it saw the stop).
    const auto a = interrupted(*s, name, 1 << 15, 0);
    INFO("spp mode: min_spp " << a.min_spp << ", max_spp " << a.max_spp);
    CHECK(a.partial);
    CHECK(same_layers_plus_counts(a, full));
    CHECK(a.min_spp >= 1);
    CHECK(a.max_spp < (1 << 15));
    CHECK(lit_pixels(a) >= lit_full * 9 / 10);

    // --time far beyond the stop: returns soon after it, marked partial.
    const auto t0 = std::chrono::steady_clock::now();
    const auto b = interrupted(*s, name, 0, 600.0);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    INFO("time mode: " << secs << " s, min_spp " << b.min_spp);
    CHECK(b.partial);
    CHECK(secs < 60.0);
    CHECK(same_layers_plus_counts(b, full));
    CHECK(lit_pixels(b) >= lit_full * 9 / 10);
  }
}
