// Every input a fuzz run once found to crash (tests/fuzz/regressions/<target>/, written
// by scripts/fuzz.sh) is replayed through its entry point (fuzz_entries.h): it must now
// end in a dp::Error or load, never crash. The seed corpus (the repository's scenes,
// meshes and experiment files) is replayed too, so the entries themselves are exercised
// in every build.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <catch2/catch.hpp>

#include "tests/fuzz/fuzz_entries.h"

namespace fs = std::filesystem;

namespace {
std::vector<uint8_t> bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST_CASE("fuzz regressions: every recorded crash input (and every hand-written seed) is now handled", "[unit]") {
  int replayed = 0;
  for (const char* kind : {"regressions", "seeds"})
  for (const auto& t : dp::fuzz::targets()) {
    const fs::path dir = fs::path(DP_SOURCE_DIR) / "tests/fuzz" / kind / t.name;
    if (!fs::is_directory(dir)) continue;
    for (const auto& f : fs::directory_iterator(dir)) {
      INFO(t.name << ": " << f.path().filename().string());
      const std::vector<uint8_t> b = bytes_of(f.path());
      CHECK(t.entry(b.data(), b.size()) == 0);
      ++replayed;
    }
  }
  CHECK(replayed >= 3);  // the hand-written seeds at least
}

TEST_CASE("fuzz entries: the seed corpus goes through every entry point", "[unit]") {
  const fs::path src(DP_SOURCE_DIR);
  std::map<std::string, std::vector<fs::path>> seeds;
  for (const auto& f : fs::recursive_directory_iterator(src / "scenes")) {
    const std::string ext = f.path().extension().string();
    if (ext == ".yaml") seeds["yaml_scene"].push_back(f.path());
    if (ext == ".ply") seeds["ply_mesh"].push_back(f.path());
    if (ext == ".obj") seeds["obj_mesh"].push_back(f.path());
  }
  for (const auto& f : fs::directory_iterator(src / "experiments/figures"))
    if (f.path().extension() == ".yaml") seeds["experiment_file"].push_back(f.path());
  for (const auto& t : dp::fuzz::targets())
    for (const fs::path& p : seeds[t.name]) {
      INFO(t.name << ": " << p.string());
      const std::vector<uint8_t> b = bytes_of(p);
      CHECK(t.entry(b.data(), b.size()) == 0);
    }
  CHECK(seeds["yaml_scene"].size() >= 5);
  CHECK(seeds["experiment_file"].size() >= 5);
}
