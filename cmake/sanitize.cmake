# DP_SANITIZE=ON: AddressSanitizer + UndefinedBehaviorSanitizer on every target (compile
# and link), for scripts/test_sanitize.sh and the `sanitize` ctest label. Any UB report
# aborts (-fno-sanitize-recover). -O1 -g0 (appended after CMAKE_CXX_FLAGS_<CONFIG>, so
# it wins over Release's -O3): compiles faster than -O2/-O3 while the Eigen-heavy tests
# still run far faster than at -O0; without -g the reports still name functions
# (symbolized from the symbol table). NDEBUG stays as the build type sets it.
# GCC's -Wmaybe-uninitialized gives false positives under the sanitizers (seen in
# libstdc++'s <regex>), so it is off in this build only.
option(DP_SANITIZE "Build everything with -fsanitize=address,undefined" OFF)
if(DP_SANITIZE)
  set(DP_SANITIZE_FLAGS -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_compile_options(${DP_SANITIZE_FLAGS} -O1 -g0 -Wno-maybe-uninitialized)
  add_link_options(${DP_SANITIZE_FLAGS})
endif()
