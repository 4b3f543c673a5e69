// The fuzzed entry points (issue 18): each takes arbitrary bytes and must return without
// a crash, a sanitizer report, a hang or an uncaught exception. Bad input is expected to
// end in a dp::Error (the one-line `file:line: problem` messages); those are caught here.
// Shared by the libFuzzer executables (fuzz_target.cpp, `DP_FUZZ=ON`, clang only;
// scripts/fuzz.sh) and by the regression test that replays every input once found to
// crash (test_fuzz_regressions.cpp, every build).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dp::fuzz {

using Entry = int (*)(const uint8_t* data, size_t size);

struct Target {
  const char* name;  // fuzz target name = folder of its regression inputs
  Entry entry;
};

int yaml_scene(const uint8_t* data, size_t size);     // scene::load_scene_yaml_string
int mitsuba_scene(const uint8_t* data, size_t size);  // scene::load_scene_mitsuba_string
int ply_mesh(const uint8_t* data, size_t size);       // scene::load_ply (bytes written to a temporary file)
int obj_mesh(const uint8_t* data, size_t size);       // scene::load_obj (likewise)
int experiment_file(const uint8_t* data, size_t size);  // experiments::parse_experiment_string

const std::vector<Target>& targets();

}  // namespace dp::fuzz
