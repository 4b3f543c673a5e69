// One libFuzzer executable per entry of fuzz_entries.h: DP_FUZZ_ENTRY names the function
// (set per target by tests/fuzz/CMakeLists.txt).
#include "tests/fuzz/fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return dp::fuzz::DP_FUZZ_ENTRY(data, size); }
