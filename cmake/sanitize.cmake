# DP_SANITIZE=ON: AddressSanitizer + UndefinedBehaviorSanitizer on every target (compile
# and link), for scripts/test_sanitize.sh and the `sanitize` ctest label. Any UB report
# aborts (-fno-sanitize-recover). Instrumented targets get -O1 -g0 (target options come
# after CMAKE_CXX_FLAGS_<CONFIG>, so it wins over Release's -O3): compiles faster than -O2/-O3 while the Eigen-heavy tests
# still run far faster than at -O0; without -g the reports still name functions
# (symbolized from the symbol table). NDEBUG stays as the build type sets it.
# GCC's -Wmaybe-uninitialized gives false positives under the sanitizers (seen in
# libstdc++'s <regex>), so it is off in this build only.
#
# DP_SANITIZE_DIRS: the top-level folders whose targets are instrumented ("all" = every
# one). The CI default instruments the code that owns and moves path and chain state
# (core, pathspace, mcmc, integrators) and the tests; scene, reconstruct, gradients,
# manifold, kernels_adaptive and experiments are compiled without instrumentation (their
# memory errors are then not seen) to keep CI within its budget: instrumenting them
# roughly doubles the stage's compile time. They keep the main build's exact flags
# (Release, -Werror as configured), so after scripts/build.sh their objects come from
# ccache instead of being compiled again. Every executable links the sanitizer runtimes.
option(DP_SANITIZE "Build with -fsanitize=address,undefined" OFF)
set(DP_SANITIZE_DIRS "core;pathspace;mcmc;integrators;tests;apps" CACHE STRING
    "top-level folders instrumented by DP_SANITIZE (all = every folder)")
if(DP_SANITIZE)
  set(DP_SANITIZE_FLAGS -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
      -O1 -g0 -Wno-maybe-uninitialized)
  add_link_options(-fsanitize=address,undefined)
endif()

# Called by dp_add_library / dp_add_test (and for other targets by their folders).
function(dp_sanitize_target name)
  if(NOT DP_SANITIZE)
    return()
  endif()
  file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  string(REGEX REPLACE "/.*" "" top "${rel}")
  if(DP_SANITIZE_DIRS STREQUAL "all" OR top IN_LIST DP_SANITIZE_DIRS)
    target_compile_options(${name} PRIVATE ${DP_SANITIZE_FLAGS})
  endif()
endfunction()
