// `render --part K/N` in process (issue 17), for every registered integrator that
// supports raw buffers: the raw buffers of 3 parts add up to those of the whole render
// (counts exactly; sums to double rounding, since they are added in another order), each
// part holding a strict share, and finish() of the sum gives render()'s layers bit for
// bit. Integrators without support refuse finish() with one line naming them. Parts of a
// time-budgeted render draw the single render's streams of passes k, n + k, ... (so they
// never share one). The end-to-end run through the CLI and EXR files is
// tests/cli/test_merge.sh.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/error.h"
#include "integrators/integrator.h"
#include "integrators/chain_scheduler.h"
#include "integrators/gradient_passes.h"
#include "integrators/mcmc_raw.h"
#include "integrators/tile_scheduler.h"
#include "scene/bsdf/bsdfs.h"
#include "tests/support/test_scenes.h"

using namespace dp;

namespace {
integrators::RenderOptions options(int part, int parts, bool raw) {
  integrators::RenderOptions opt;
  opt.spp = 6;  // passes of 1, 1, 2, 2 spp
  opt.seed = 5;
  opt.threads = 2;
  opt.max_depth = 5;
  opt.quiet = true;
  opt.part = part;
  opt.parts = parts;
  opt.raw = raw;
  return opt;
}

bool same_layers(const integrators::RenderResult& a, const integrators::RenderResult& b) {
  if (a.layers.size() != b.layers.size()) return false;
  for (size_t l = 0; l < a.layers.size(); ++l) {
    if (a.layers[l].name != b.layers[l].name) return false;
    const auto &pa = a.layers[l].image.pixels(), &pb = b.layers[l].image.pixels();
    for (size_t i = 0; i < pa.size(); ++i)
      if (!(pa[i] == pb[i]).all()) return false;
  }
  return true;
}
}  // namespace

TEST_CASE("integrators: the parts of a render add up to the render", "[render]") {
  // 32 x 32: 2 x 2 tiles, so 3 parts take every third (pass, tile) unit and each pixel's
  // passes are spread over the parts (with 3 x 3 tiles each part would keep its tiles).
  const auto s = test::lit_box(
      scene::make_conductor(0.05f, 0.05f, scene::MicrofacetType::ggx, scene::ConductorFresnel{},
                            scene::constant_texture(Rgb(0.9f, 0.8f, 0.6f))),
      scene::make_diffuse(scene::constant_texture(Rgb(0.5f, 0.5f, 0.5f))), 32);
  int supported = 0;
  for (const std::string& name : integrators::integrator_names()) {
    INFO("integrator " << name);
    integrators::Settings settings;
    // The MCMC integrators split their chains: one chain count for every part (the
    // default depends on the part count, integrators/chain_scheduler.h), and a small
    // bootstrap to keep the test fast.
    if (name == "mlt" || name == "memlt" || name == "gdmlt") {
      settings.set("chains", "6", "test");
      settings.set("bootstrap", "4000", "test");
    }
    auto in = integrators::make_integrator(name, settings);
    if (!in->supports_raw()) {
      CHECK_THROWS_WITH(in->finish(core::RawImage{}, options(0, 1, false)),
                        "integrator " + name + " does not support --partial yet");
      continue;
    }
    ++supported;
    const integrators::RenderResult whole = in->render(*s, options(0, 1, true));
    core::RawImage sum;
    for (int k = 0; k < 3; ++k) {
      const integrators::RenderResult part = in->render(*s, options(k, 3, true));
      CHECK_FALSE(part.partial);
      CHECK(part.max_spp > 0);
      CHECK(part.min_spp < 6);  // a strict share, not the whole render
      if (k == 0) sum = part.raw;
      else sum.add(part.raw);
    }
    REQUIRE(sum.layout_difference(whole.raw).empty());
    for (const auto& [buffer, values] : whole.raw.counts) {
      INFO("count " << buffer);
      CHECK(sum.counts.at(buffer) == values);
    }
    for (const auto& [buffer, values] : whole.raw.sums) {
      INFO("buffer " << buffer);
      double worst = 0;
      for (size_t i = 0; i < values.size(); ++i)
        worst = std::max(worst, ((sum.sums.at(buffer)[i] - values[i]).abs() / (values[i].abs() + 1e-300)).maxCoeff());
      CHECK(worst < 1e-12);  // the same samples; a different sample is off by far more
    }
    const integrators::RenderResult direct = in->render(*s, options(0, 1, false));
    CHECK(same_layers(in->finish(sum, options(0, 1, false)), direct));
    CHECK_FALSE(direct.partial);
  }
  CHECK(supported >= 5);  // path, gpt, ..., mlt, memlt, gdmlt
}

TEST_CASE("tile scheduler: every work unit belongs to exactly one part", "[unit]") {
  for (int parts : {1, 2, 3, 7})
    for (int64_t pass = 0; pass < 9; ++pass)
      for (int tile = 0; tile < 10; ++tile) {
        int owners = 0;
        for (int k = 0; k < parts; ++k)
          owners += integrators::owns_unit(options(k, parts, true), pass, tile, 10) ? 1 : 0;
        CHECK(owners == 1);
      }
  CHECK(integrators::work_units(40, 40, 6) == 4 * 9);
  CHECK_THROWS_WITH(integrators::check_parts(40, 40, options(0, 37, true)),
                    "part 1/37: --spp 6 at 40x40 has only 36 work units (passes x 16x16 tiles); use at most 36 parts");
  CHECK_NOTHROW(integrators::check_parts(40, 40, options(35, 36, true)));
  integrators::RenderOptions timed = options(99, 100, true);
  timed.time_budget = 1;  // a time-budgeted part has no unit limit
  CHECK_NOTHROW(integrators::check_parts(40, 40, timed));
}

TEST_CASE("chain scheduler: each chain runs in exactly one part, with the whole render's quota", "[unit]") {
  // 7 chains, 3 parts: the parts' runs (chains and mutations) add up to the single run's.
  integrators::ChainSchedule sc;
  sc.chains = 7;
  sc.total = 1000;  // 1000 % 7 = 6: the first 6 chains take one more
  sc.round = 60;
  sc.pixels = 1;
  auto run = [&](int part, int parts) {
    integrators::ChainSchedule s = sc;
    s.part = part;
    s.parts = parts;
    return integrators::run_chains(s, options(part, parts, true), "test",
                                   [](int c, int64_t n, integrators::SplatList& out, int) {
                                     out.add(0, 0, Rgbd::Constant(double(c + 1) * double(n)));
                                   });
  };
  const integrators::ChainRunResult whole = run(0, 1);
  std::vector<int64_t> mutations(7, 0);
  int64_t total = 0;
  for (int k = 0; k < 3; ++k) {
    const integrators::ChainRunResult part = run(k, 3);
    CHECK_FALSE(part.partial);  // complete for its own chains
    for (int c = 0; c < 7; ++c) {
      CHECK((part.mutations[size_t(c)] > 0) == (c % 3 == k));
      mutations[size_t(c)] += part.mutations[size_t(c)];
    }
    total += part.total_mutations;
    CHECK(part.rounds <= integrators::whole_rounds(sc));
  }
  CHECK(mutations == whole.mutations);
  CHECK(total == 1000);
  CHECK(whole.rounds == integrators::whole_rounds(sc));  // ceil(143 / 60) = 3
  CHECK(whole.rounds == 3);
}

TEST_CASE("MCMC normalisation: write/read round trip, summed shares give one b", "[unit]") {
  for (int w : {1, 4}) {
    integrators::McmcNorm a, b;
    a.b = {3.0, 10, 0};
    a.factor = {1.5, 4, 0};
    a.mutations = 123;
    b.b = {1.0, 6, 0};
    b.factor = {0.5, 4, 0};
    b.mutations = 77;
    core::RawImage ra = integrators::empty_raw(w, 1), rb = integrators::empty_raw(w, 1);
    a.write(ra);
    b.write(rb);
    ra.add(rb);
    const integrators::McmcNorm m = integrators::McmcNorm::read(ra);
    CHECK(m.b.n == 16);
    CHECK(m.factor.n == 8);
    CHECK(m.mutations == 200);
    CHECK(m.value() == Approx((4.0 / 16.0) * (2.0 / 8.0)));  // (sum b / n) (sum factor / n)
    CHECK(m.scale(w) == Approx(m.value() * w / 200.0));
  }
}

TEST_CASE("tile scheduler: time-budgeted parts take passes k, n + k, 2n + k, ... of the single render", "[unit]") {
  // The first random word of every 1-spp pass of a one-tile image, as many passes as fit.
  auto first_words = [](int part, int parts, double seconds) {
    integrators::RenderOptions opt = options(part, parts, true);
    opt.time_budget = seconds;
    opt.threads = 1;
    std::vector<uint32_t> words;
    integrators::run_tiles(16, 16, opt, "t",
                           [&](const integrators::Tile&, int, core::Rng& rng, int) { words.push_back(rng.next_u32()); });
    return words;
  };
  const std::vector<uint32_t> single = first_words(0, 1, 0.1);
  for (int k = 0; k < 3; ++k) {
    const std::vector<uint32_t> part = first_words(k, 3, 0.01);
    size_t compared = 0;
    for (size_t p = 0; p < part.size() && 3 * p + size_t(k) < single.size(); ++p, ++compared)
      CHECK(part[p] == single[3 * p + size_t(k)]);
    CHECK(compared >= 10);
  }
  // G-PT's time-budgeted passes are whole renders seeded per pass: the same mapping.
  for (int k = 0; k < 3; ++k)
    for (int64_t p = 0; p < 10; ++p) {
      integrators::RenderOptions single_opt = options(0, 1, true), part_opt = options(k, 3, true);
      single_opt.time_budget = part_opt.time_budget = 1;
      CHECK(integrators::timed_pass_seed(part_opt, p) == integrators::timed_pass_seed(single_opt, 3 * p + k));
    }
}

TEST_CASE("integrators: merged time-budgeted parts of path are unbiased (z-test against an independent render)",
          "[render]") {
  // Timed parts stop at passes that depend on the machine, so this is statistical: the
  // merged image minus an independent 64-spp render, per pixel (pixels are independent
  // in `path`), has mean 0 within 4.5 standard errors estimated from the differences
  // themselves (two-sided false alarm 7e-6). Counts not summed (3x too bright) fail it.
  const auto s = test::lit_box(scene::make_diffuse(scene::constant_texture(Rgb(0.7f, 0.7f, 0.7f))),
                               scene::make_diffuse(scene::constant_texture(Rgb(0.3f, 0.5f, 0.7f))), 32);
  integrators::Settings settings;
  auto in = integrators::make_integrator("path", settings);
  core::RawImage sum;
  for (int k = 0; k < 3; ++k) {
    integrators::RenderOptions opt = options(k, 3, true);
    opt.time_budget = 0.1;
    opt.seed = 21;
    const integrators::RenderResult part = in->render(*s, opt);
    REQUIRE(part.min_spp >= 1);
    if (k == 0) sum = part.raw;
    else sum.add(part.raw);
  }
  integrators::RenderOptions merged_opt = options(0, 1, false);
  merged_opt.spp = 0;  // no spp target, as `merge` of --time parts
  const core::Image merged = in->finish(sum, merged_opt).layers.at(0).image;
  integrators::RenderOptions ref_opt = options(0, 1, false);
  ref_opt.spp = 64;
  ref_opt.seed = 99;
  const core::Image ref = in->render(*s, ref_opt).layers.at(0).image;
  double mean = 0, sq = 0;
  const double n = double(ref.size());
  for (size_t i = 0; i < ref.size(); ++i) {
    const double d = double(merged[i].mean()) - double(ref[i].mean());
    mean += d / n;
    sq += d * d / n;
  }
  const double stderr_mean = std::sqrt(std::max(sq - mean * mean, 1e-30) / (n - 1));
  INFO("mean difference " << mean << ", standard error " << stderr_mean);
  CHECK(std::abs(mean) < 4.5 * stderr_mean);
}
