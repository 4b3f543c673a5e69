// core/image_io_raw.h: raw sums and counts survive an EXR round trip bit for bit (the
// values a float EXR would round: 1/3, denormals, -0, huge, int64 counts above 2^32),
// facts come back as written, and a plain float EXR is refused naming the file.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "core/image_io.h"
#include "core/image_io_raw.h"
#include "core/raw_bytes.h"

using namespace dp;
using namespace dp::core;

namespace {
std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("dp_test_" + name)).string();
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
}  // namespace

TEST_CASE("raw EXR keeps every double and count bit for bit", "[unit]") {
  RawImage raw;
  raw.width = 5;
  raw.height = 3;
  const double special[] = {1.0 / 3.0, -0.0, 5e-324, 1e300, -2.5e-10, 0.1};
  for (const char* name : {"primal", "dx"}) {
    auto& v = raw.sums[name];
    for (size_t i = 0; i < raw.pixels(); ++i)
      v.push_back(Rgbd(special[i % 6], special[(i + 1) % 6] * double(i), double(name[1]) + 1.0 / double(i + 7)));
  }
  auto& n = raw.counts["spp"];
  for (size_t i = 0; i < raw.pixels(); ++i) n.push_back(int64_t(i) * 3000000000ll + 1);
  const std::string path = temp_path("raw.exr");
  write_raw_exr(path, raw, {{"integrator", "gpt"}, {"setting.alpha", "0.2"}});
  Facts facts;
  const RawImage back = read_raw_exr(path, facts);
  CHECK(facts == Facts{{"integrator", "gpt"}, {"setting.alpha", "0.2"}});
  REQUIRE(back.layout_difference(raw).empty());
  CHECK(back.counts.at("spp") == n);
  for (const auto& [name, v] : raw.sums)
    for (size_t i = 0; i < v.size(); ++i)
      for (int c = 0; c < 3; ++c) CHECK(same_bits(back.sums.at(name)[i][c], v[i][c]));
  std::filesystem::remove(path);
}

TEST_CASE("raw EXR refuses a float EXR and names the file", "[unit]") {
  const std::string path = temp_path("plain.exr");
  write_exr(path, Image(4, 4, Rgb::Constant(0.5f)));
  Facts facts;
  CHECK_THROWS_WITH(read_raw_exr(path, facts), Catch::Contains("plain.exr") && Catch::Contains("not a --partial file"));
  std::filesystem::remove(path);
}

TEST_CASE("raw images add buffer by buffer and report layout differences", "[unit]") {
  RawImage a;
  a.width = 2;
  a.height = 1;
  a.sums["radiance"] = {Rgbd(1, 2, 3), Rgbd(4, 5, 6)};
  a.counts["spp"] = {1, 2};
  RawImage b = a;
  b.add(a);
  CHECK((b.sums["radiance"][1] == Rgbd(8, 10, 12)).all());
  CHECK(b.counts["spp"] == std::vector<int64_t>{2, 4});
  RawImage c = a;
  c.sums["dx"] = a.sums["radiance"];
  CHECK(a.layout_difference(c) == "sum buffers (radiance) vs (dx, radiance)");
  c = a;
  c.width = 1;
  CHECK(a.layout_difference(c) == "size 2x1 vs 1x1");
}

// The in-memory form `render --mpi` sends between ranks (core/raw_bytes.h).
TEST_CASE("raw bytes keep every double, count and fact; truncation is an error", "[unit]") {
  RawImage raw;
  raw.width = 4;
  raw.height = 2;
  for (size_t i = 0; i < raw.pixels(); ++i) {
    raw.sums["primal"].push_back(Rgbd(1.0 / double(i + 3), -0.0, 1e300 * double(i)));
    raw.counts["spp"].push_back(int64_t(i) * 5000000000ll);
  }
  const std::map<std::string, std::string> facts{{"counter.rays", "12"}, {"wall_seconds", "0.5"}};
  const std::vector<uint8_t> bytes = raw_to_bytes(raw, facts);
  std::map<std::string, std::string> f;
  const RawImage back = raw_from_bytes(bytes, f);
  CHECK(f == facts);
  REQUIRE(back.layout_difference(raw).empty());
  CHECK(back.counts.at("spp") == raw.counts.at("spp"));
  for (size_t i = 0; i < raw.pixels(); ++i)
    for (int c = 0; c < 3; ++c) CHECK(same_bits(back.sums.at("primal")[i][c], raw.sums.at("primal")[i][c]));
  for (size_t cut : {size_t(0), size_t(7), bytes.size() / 2, bytes.size() - 1}) {
    const std::vector<uint8_t> head(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut));
    CHECK_THROWS_AS(raw_from_bytes(head, f), ValueError);
  }
}
