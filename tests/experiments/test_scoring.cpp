// Scoring: metric discard of the n worst pixels, metric dispatch, error maps, crops and
// CSV quoting.
#include <catch2/catch.hpp>

#include "core/image_io.h"
#include "experiments/results_csv.h"
#include "experiments/scoring.h"

using namespace dp;
using namespace dp::experiments;

namespace {
// A 10x10 reference of 0.5 and an image equal to it except `bad` pixels off by 1 + i.
std::pair<core::Image, core::Image> images_with_outliers(int bad) {
  core::Image ref(10, 10, Rgb::Constant(0.5f));
  core::Image img = ref;
  for (int i = 0; i < bad; ++i) img[size_t(7 * i + 3)] = Rgb::Constant(0.5f + 1.0f + float(i));
  return {img, ref};
}
}  // namespace

TEST_CASE("scoring: discarding the n worst pixels", "[unit]") {
  const auto [img, ref] = images_with_outliers(3);
  // With all three outliers discarded the error is exactly zero.
  CHECK(evaluate_metric(Metric{"relmse", 3}, img, ref) == 0.0);
  CHECK(evaluate_metric(Metric{"mse", 3}, img, ref) == 0.0);
  CHECK(evaluate_metric(Metric{"mape", 5}, img, ref) == 0.0);
  // Discarding two keeps the smallest outlier (error 1^2 over 98 pixels).
  CHECK(evaluate_metric(Metric{"mse", 2}, img, ref) == Approx(1.0 / 98.0));
  CHECK(evaluate_metric(Metric{"relmse", 2}, img, ref) == Approx(1.0 / (0.25 + 1e-3) / 98.0));
  // Nothing discarded: (1 + 4 + 9) / 100.
  CHECK(evaluate_metric(Metric{"mse", 0}, img, ref) == Approx(14.0 / 100.0));
  CHECK(Metric{"mse", 2}.column() == "mse_discard2");
  CHECK(Metric{"mse", 0}.column() == "mse");
}

TEST_CASE("scoring: a metric restricted to a crop sees only that region", "[unit]") {
  const auto [img, ref] = images_with_outliers(3);  // outliers at pixels 3, 10, 17: (3,0), (0,1), (7,1)
  const std::vector<Crop> crops = {{0, 2, 10, 8}, {2, 0, 4, 2}};
  Metric m{"mse", 0};
  m.crop = 0;  // rows 2..9: no outlier
  CHECK(evaluate_metric(m, img, ref, crops) == 0.0);
  CHECK(m.column() == "mse_crop0");
  m.crop = 1;  // x 2..5, y 0..1: only (3,0), error 1 over 8 pixels
  CHECK(evaluate_metric(m, img, ref, crops) == Approx(1.0 / 8.0));
  m.discard = 1;
  CHECK(evaluate_metric(m, img, ref, crops) == 0.0);
  CHECK(m.column() == "mse_discard1_crop1");
}

TEST_CASE("scoring: error map colours", "[unit]") {
  core::Image ref(4, 1, Rgb::Constant(0.5f));
  core::Image img = ref;
  img(1, 0) = Rgb::Constant(100.0f);
  img(2, 0) = Rgb(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);
  const core::Image map = error_map(img, ref);
  for (int c = 0; c < 3; ++c) CHECK(map(0, 0)[c] == Approx(core::srgb_to_linear(error_ramp(0.0)[c])));
  for (int c = 0; c < 3; ++c) CHECK(map(1, 0)[c] == Approx(core::srgb_to_linear(error_ramp(1.0)[c])));
  CHECK((map(2, 0) == Rgb(1.0f, 0.0f, 1.0f)).all());
  CHECK(map.count_nonfinite() == 0);
}

TEST_CASE("scoring: crops are enlarged by pixel replication", "[unit]") {
  core::Image img(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) img(x, y) = Rgb(float(x), float(y), 0.0f);
  const core::Image c = crop_image(img, Crop{2, 3, 4, 2, 0}, 16);
  REQUIRE(c.width() == 16);
  REQUIRE(c.height() == 8);
  CHECK((c(0, 0) == Rgb(2, 3, 0)).all());
  CHECK((c(15, 7) == Rgb(5, 4, 0)).all());
  CHECK((c(4, 4) == Rgb(3, 4, 0)).all());
}

TEST_CASE("results CSV: fields with commas or quotes are quoted", "[unit]") {
  CHECK(csv_field("PT") == "PT");
  CHECK(csv_field("PT, no NEE") == "\"PT, no NEE\"");
  CHECK(csv_field("a \"b\"") == "\"a \"\"b\"\"\"");
}
