#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run (CI, after scripts/test.sh):
# configures build-asan/ with -DDP_SANITIZE=ON (cmake/sanitize.cmake), builds only the
# test executables below and runs ctest's `sanitize` label (every registered integrator
# rendering tiny scenes at 1-3 threads, tests/sanitize/) and their `unit` tests. Any
# ASan, LeakSanitizer or UBSan report aborts the test process, so ctest fails.
#   DP_SANITIZE_UNITS=all scripts/test_sanitize.sh   every folder instrumented, every `unit` test (local, ~2x longer)
#   scripts/test_sanitize.sh -R test_mlt             extra arguments go to ctest
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh

# CI subset of the `unit` executables, chosen for the 20-minute CI budget on 2 cores:
# the instrumented libraries alone take about half of this script's time, so only
# executables that are cheap to compile and run and test memory-owning code are in:
# the MCMC chains and MLT (where chains once held dangling references) and the
# primary-sample streams. Left out (measured cold, user+sys CPU to compile + run
# instrumented): test_core 38 s, test_loader 26 s, test_geometry 67 s, test_bsdf 110 s,
# test_reconstruct 110 s, test_gradients 91 s, test_manifold 98 s, test_mitsuba and
# test_experiments (their own large sources / library). All run uninstrumented in
# scripts/test.sh; the sanitize label's renders go through their code paths anyway.
unit_tests=(test_pathspace test_mcmc test_mlt)

# Instrumented folders: cmake/sanitize.cmake's DP_SANITIZE_DIRS (CI: core, pathspace,
# mcmc, integrators, apps, tests; DP_SANITIZE_UNITS=all instruments every folder).
# The uninstrumented folders keep scripts/build.sh's flags (the same -Werror setting, paths
# relative to the checkout for ccache), so they come from the cache when build/ was built.
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
export CCACHE_BASEDIR="$PWD"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DDP_WERROR=$werror -DDP_SANITIZE=ON -DDP_BUILD_BENCH=OFF \
  -DDP_SANITIZE_DIRS="core;pathspace;mcmc;integrators;tests;apps" >/dev/null
# halt_on_error: stop at the first report (UBSan also aborts: -fno-sanitize-recover);
# detect_leaks: LeakSanitizer at exit; abort_on_error=0: a non-zero exit, no core dump;
# detect_stack_use_after_return: references to dead stack frames (about 1.4x the run
# time of the Eigen-heavy tests; cheap for the CI subset).
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=0:strict_init_order=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
if [ "${DP_SANITIZE_UNITS:-}" = "all" ]; then
  cmake -S . -B build-asan -DDP_SANITIZE_DIRS=all >/dev/null
  cmake --build build-asan -j"$(nproc)"
  ctest --test-dir build-asan -L 'sanitize|unit' --output-on-failure -j"$(nproc)" "$@"
else
  cmake --build build-asan -j"$(nproc)" --target test_sanitize "${unit_tests[@]}"
  regex="^($(echo test_sanitize "${unit_tests[@]}" | tr ' ' '|'))_(sanitize|unit)\$"
  ctest --test-dir build-asan -L 'sanitize|unit' -R "$regex" --output-on-failure -j"$(nproc)" "$@"
fi
