// Pair-gradient layers (reconstruct/pair_layers.h) and gradient renders read from EXR
// (render_io.h): the pair list survives a file round trip exactly, malformed offset
// layers are rejected with the layer and pixel named, and a render's `primal` layer
// (indirect + direct) is solved without its direct part.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>

#include "core/error.h"
#include "core/image_io.h"
#include "helpers.h"
#include "reconstruct/pair_layers.h"
#include "reconstruct/render_io.h"
#include "reconstruct/solve.h"

using namespace dp;
using namespace dp::reconstruct;
using namespace dp::reconstruct::test;

namespace {

// Pairs of mixed reach (up to 2 pixels, both directions, a duplicate reversed pair) as an
// adaptive kernel makes them.
Kernel odd_kernel(int w, int h) {
  std::vector<PixelPair> pairs;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      if (x + 2 < w) pairs.push_back({p + 2, p});
      if (y + 1 < h) pairs.push_back({p, p + w});
      if (x + 1 < w && y + 1 < h && (x + y) % 3 == 0) {
        pairs.push_back({p, p + w + 1});
        pairs.push_back({p + w + 1, p});
      }
    }
  return Kernel(w, h, std::move(pairs));
}

std::filesystem::path temp_dir() {
  const auto dir = std::filesystem::temp_directory_path() / "dp_test_pair_layers";
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace

TEST_CASE("pair layers: a kernel and its values survive an EXR round trip and give the same solve", "[unit]") {
  const int w = 11, h = 7;
  const core::Image truth = test_image(w, h);
  const Kernel kernel = odd_kernel(w, h);
  const std::vector<Rgb> b = apply_kernel(kernel, truth);
  const auto path = (temp_dir() / "pairs.exr").string();
  std::vector<core::NamedLayer> layers{{"primal", truth}};
  append_pair_layers(encode_pair_layers(kernel, b), layers);
  core::write_exr(path, layers);

  const GradientImages g = read_gradient_render(path);
  REQUIRE(g.pairs.values.size() == 3);  // at most 3 rows end at one pixel here
  Problem decoded = make_render_problem(g, 0.2f, path);
  REQUIRE(decoded.kernel.rows() == kernel.rows());
  // Same multiset of (pair, value): compare sorted.
  auto sorted = [](const Kernel& k, const std::vector<Rgb>& v) {
    std::vector<std::tuple<int, int, float, float, float>> rows;
    for (size_t r = 0; r < k.rows(); ++r) rows.emplace_back(k.pairs()[r].i, k.pairs()[r].j, v[r].x(), v[r].y(), v[r].z());
    std::sort(rows.begin(), rows.end());
    return rows;
  };
  CHECK(sorted(decoded.kernel, decoded.b) == sorted(kernel, b));
  // Exact gradients and primal: the L2 solve returns the image.
  const core::Image solved = solve_l2(decoded).image;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) CHECK((solved(x, y) - truth(x, y)).abs().maxCoeff() < 1e-4f);
}

TEST_CASE("pair layers: malformed offsets are rejected naming the layer and pixel", "[unit]") {
  const int w = 5, h = 4;
  const Kernel kernel = odd_kernel(w, h);
  PairLayers layers = encode_pair_layers(kernel, std::vector<Rgb>(kernel.rows(), Rgb::Ones()));
  Kernel k;
  std::vector<Rgb> b;
  REQUIRE_NOTHROW(decode_pair_layers(layers, k, b, "x.exr"));
  auto expect = [&](PairLayers bad, const std::string& what) {
    try {
      decode_pair_layers(bad, k, b, "x.exr");
      FAIL("accepted: " << what);
    } catch (const ValueError& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(msg.find("pairs.0.offset at pixel (2, 1)") != std::string::npos);
      CHECK(msg.find("x.exr") != std::string::npos);
    }
  };
  PairLayers half = layers;
  half.offsets[0](2, 1).x() = 0.5f;
  expect(half, "half-pixel offset");
  PairLayers self = layers;
  self.offsets[0](2, 1) = Rgb(0, 0, 1);
  expect(self, "pair to itself");
  PairLayers outside = layers;
  outside.offsets[0](2, 1) = Rgb(5, 0, 1);
  expect(outside, "partner outside");
  PairLayers flag = layers;
  flag.offsets[0](2, 1).z() = 0.5f;
  expect(flag, "existence flag not 0/1");
  PairLayers missing = layers;
  missing.offsets.pop_back();
  CHECK_THROWS_AS(decode_pair_layers(missing, k, b, "x.exr"), ValueError);
}

TEST_CASE("gradient render: the primal layer's direct part is not counted twice", "[unit]") {
  // The integrators write primal = indirect + direct and gradients of the indirect part;
  // the reconstruction (then + direct) of exact data must return indirect + direct.
  const int w = 9, h = 6;
  const core::Image indirect = test_image(w, h);
  core::Image direct(w, h, Rgb(0.25f, 0.5f, 1.0f)), full = indirect;
  full += direct;
  const Kernel grid = Kernel::forward_differences(w, h);
  const std::vector<Rgb> b = apply_kernel(grid, indirect);
  core::Image dx(w, h), dy(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) dx(x, y) = b[grid.grid_dx_row(x, y)];
      if (y + 1 < h) dy(x, y) = b[grid.grid_dy_row(x, y)];
    }
  const auto path = (temp_dir() / "render.exr").string();
  core::write_exr(path, {{"primal", full}, {"dx", dx}, {"dy", dy}, {"direct", direct}});
  GradientImages g = read_gradient_render(path);
  REQUIRE(g.direct);
  const core::Image d = *g.direct;
  core::Image out = solve_l2(make_render_problem(std::move(g), 0.2f, path)).image;
  out += d;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) CHECK((out(x, y) - full(x, y)).abs().maxCoeff() < 1e-4f);
}

TEST_CASE("symmetric pairs as two rows of 2 Delta: weight 1/2 per row solves like one row of Delta_i + Delta_j",
          "[unit]") {
  // Manzi 2014, Algorithm 1 writes a symmetric pair as I_i - I_j = 2 Delta^i and
  // I_j - I_i = 2 Delta^j_ji. In least squares that is one row of weight 2; with
  // reversed_pair_weights(0.5) the L2 solve equals the one-row kernel's exactly, and
  // without it it does not (the screening is effectively alpha / sqrt 2).
  const int w = 10, h = 8;
  const core::Image primal = test_image(w, h);
  const Kernel grid = Kernel::forward_differences(w, h);
  std::vector<Rgb> one(grid.rows()), split_values;
  std::vector<PixelPair> split_pairs;
  for (size_t r = 0; r < grid.rows(); ++r) {
    const PixelPair& p = grid.pairs()[r];
    // Noisy halves: Delta^i (part of I_j - I_i seen from i) and Delta^j.
    const Rgb di = Rgb::Constant(0.01f * float(r % 7) - 0.02f), dj = Rgb::Constant(0.015f * float(r % 5) - 0.03f);
    one[r] = di + dj;
    split_pairs.push_back({p.i, p.j});
    split_values.push_back(2.0f * di);
    split_pairs.push_back({p.j, p.i});
    split_values.push_back(-2.0f * dj);
  }
  Problem a;
  a.primal = primal;
  a.kernel = grid;
  a.b = one;
  Problem b;
  b.primal = primal;
  b.kernel = Kernel(w, h, split_pairs);
  b.b = split_values;
  SolveOptions o;
  o.method = L2Method::cg;
  o.cg_tolerance = 1e-9;
  const core::Image ia = solve_l2(a, o).image;
  const core::Image unweighted = solve_l2(b, o).image;
  b.row_weights = reversed_pair_weights(b.kernel, 0.5f);
  REQUIRE(std::count(b.row_weights.begin(), b.row_weights.end(), 0.5f) == long(b.kernel.rows()));
  const core::Image weighted = solve_l2(b, o).image;
  float worst_w = 0, worst_u = 0;
  for (size_t i = 0; i < ia.size(); ++i) {
    worst_w = std::max(worst_w, (weighted[i] - ia[i]).abs().maxCoeff());
    worst_u = std::max(worst_u, (unweighted[i] - ia[i]).abs().maxCoeff());
  }
  INFO("weighted " << worst_w << ", unweighted " << worst_u);
  CHECK(worst_w < 1e-4f);
  CHECK(worst_u > 1e-3f);
  // Rows without a reversed twin keep weight 1.
  const std::vector<float> g = reversed_pair_weights(grid, 0.5f);
  CHECK(std::all_of(g.begin(), g.end(), [](float x) { return x == 1.0f; }));
}
