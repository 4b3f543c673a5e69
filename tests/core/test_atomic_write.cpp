// core/atomic_write.h: the file appears complete or not at all; a failed write leaves the
// previous file untouched and no temporary behind.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/image_io.h"

namespace fs = std::filesystem;
using namespace dp;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}
size_t temporaries(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp-") != std::string::npos) ++n;
  return n;
}
struct TempDir {
  fs::path path = fs::temp_directory_path() / ("dp_atomic_write_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};
}  // namespace

TEST_CASE("atomic write: temporary name beside the file, replaced in one step", "[unit]") {
  TempDir dir;
  const std::string file = (dir.path / "a.json").string();
  CHECK(core::temp_path(file) == file + ".tmp-" + std::to_string(::getpid()));
  core::write_file_atomically(file, "first");
  core::write_file_atomically(file, "second");
  CHECK(slurp(file) == "second");
  CHECK(temporaries(dir.path) == 0);
}

TEST_CASE("atomic write: a failing writer leaves the old file and no temporary", "[unit]") {
  TempDir dir;
  const std::string file = (dir.path / "b.exr").string();
  core::write_file_atomically(file, "old");
  CHECK_THROWS_AS(core::write_atomically(file,
                                         [](const std::string& tmp) {
                                           std::ofstream(tmp) << "half";
                                           throw std::runtime_error("killed half-way");
                                         }),
                  std::runtime_error);
  CHECK(slurp(file) == "old");
  CHECK(temporaries(dir.path) == 0);
  // The pending temporary is registered for the signal handler only while it is written.
  std::ofstream(core::temp_path(file)) << "stale";
  core::remove_pending_temp_files();
  CHECK(temporaries(dir.path) == 1);
}

TEST_CASE("atomic write: remove_pending_temp_files unlinks the file being written", "[unit]") {
  TempDir dir;
  const std::string file = (dir.path / "c.png").string();
  core::write_atomically(file, [&](const std::string& tmp) {
    std::ofstream(tmp) << "partial";
    core::remove_pending_temp_files();  // what the second-signal handler does before _exit
    CHECK_FALSE(fs::exists(tmp));
    std::ofstream(tmp) << "complete";  // (the process would be gone; finish the test cleanly)
  });
  CHECK(slurp(file) == "complete");
}

TEST_CASE("atomic write: EXR and PNG writers go through it", "[unit]") {
  TempDir dir;
  core::Image img(4, 3);
  const std::string exr = (dir.path / "d.exr").string(), png = (dir.path / "d.png").string();
  core::write_exr(exr, img);
  core::write_png(png, img);
  CHECK(core::read_exr(exr).width() == 4);
  CHECK(core::read_image(png).height() == 3);
  CHECK(temporaries(dir.path) == 0);
  CHECK_THROWS_AS(core::write_exr((dir.path / "missing" / "e.exr").string(), img), IoError);
  CHECK(temporaries(dir.path) == 0);
}
