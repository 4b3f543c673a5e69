# DP_FUZZ=ON (clang only; scripts/fuzz.sh): every target compiled with libFuzzer's
# coverage instrumentation plus AddressSanitizer and UBSan (a UB report aborts, so the
# fuzzer records it as a crash), -O1 -g for readable reports; tests/fuzz/ adds one
# libFuzzer executable per fuzzed entry point.
option(DP_FUZZ "Build the libFuzzer targets (clang)" OFF)
if(DP_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "DP_FUZZ needs clang (libFuzzer): configure with CXX=clang++ (scripts/fuzz.sh does)")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer -O1 -g)
  add_link_options(-fsanitize=address,undefined)
endif()
