#include "tests/fuzz/fuzz_entries.h"

#include <cstdio>
#include <fstream>
#include <unistd.h>

#include "core/error.h"
#include "core/log.h"
#include "experiments/config.h"
#include "scene/loaders/loader.h"
#include "scene/loaders/mesh_io.h"
#include "scene/loaders/mitsuba/mitsuba_loader.h"

namespace dp::fuzz {

namespace {

// Runs f; a dp::Error is the expected outcome of bad input. Any other exception escapes
// (the fuzzer reports it as a crash): a raw std:: message is not the one-line error the
// loaders promise.
template <class F>
int guarded(F&& f) {
  log::set_level(log::Level::quiet);
  try {
    f();
  } catch (const Error&) {
  }
  return 0;
}

std::string text_of(const uint8_t* data, size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

// The bytes as a file of this process (the mesh readers take paths).
std::string temp_file(const uint8_t* data, size_t size, const char* ext) {
  const std::string path = "/tmp/dp-fuzz-" + std::to_string(getpid()) + ext;
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

}  // namespace

int yaml_scene(const uint8_t* data, size_t size) {
  return guarded([&] { scene::load_scene_yaml_string(text_of(data, size), "fuzz/scene.yaml"); });
}

int mitsuba_scene(const uint8_t* data, size_t size) {
  return guarded([&] {
    std::vector<std::string> warnings;
    scene::MitsubaOptions opt;
    opt.warnings = &warnings;
    scene::load_scene_mitsuba_string(text_of(data, size), "fuzz/scene.xml", opt);
  });
}

int ply_mesh(const uint8_t* data, size_t size) {
  const std::string path = temp_file(data, size, ".ply");
  const int r = guarded([&] { scene::load_ply(path); });
  std::remove(path.c_str());
  return r;
}

int obj_mesh(const uint8_t* data, size_t size) {
  const std::string path = temp_file(data, size, ".obj");
  const int r = guarded([&] { scene::load_obj(path); });
  std::remove(path.c_str());
  return r;
}

int experiment_file(const uint8_t* data, size_t size) {
  return guarded([&] { experiments::parse_experiment_string(text_of(data, size), "fuzz/experiment.yaml"); });
}

const std::vector<Target>& targets() {
  static const std::vector<Target> t = {{"yaml_scene", yaml_scene},
                                        {"mitsuba_scene", mitsuba_scene},
                                        {"ply_mesh", ply_mesh},
                                        {"obj_mesh", obj_mesh},
                                        {"experiment_file", experiment_file}};
  return t;
}

}  // namespace dp::fuzz
