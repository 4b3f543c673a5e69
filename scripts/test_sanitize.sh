#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run (CI, after scripts/test.sh):
# configures build-asan/ with -DDP_SANITIZE=ON (cmake/sanitize.cmake), builds only the
# test executables below and runs ctest's `sanitize` label (every integrator rendering
# tiny scenes at 1-3 threads, tests/sanitize/) and their `unit` tests. Any ASan, LSan or
# UBSan report aborts the test process, so ctest fails.
# Extra ctest arguments are passed through, e.g. scripts/test_sanitize.sh -R test_mlt
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh

# Executables whose `unit` tests run instrumented: the layers the integrators' hot loops
# live in (core, path space, shifts, MCMC). Left out to keep CI near its time budget (an
# instrumented build of the libraries alone takes ~9 min on 2 cores): test_loader,
# test_bsdf, test_geometry, test_manifold, test_reconstruct, test_experiments and
# test_mitsuba; their code still runs instrumented inside the `sanitize` renders (scene
# loading aside), and their tests run uninstrumented in scripts/test.sh.
unit_tests=(test_core test_pathspace test_gradients test_mcmc test_mlt)

cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DDP_SANITIZE=ON -DDP_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j"$(nproc)" --target test_sanitize "${unit_tests[@]}"

# halt_on_error: stop at the first report (UBSan also aborts: -fno-sanitize-recover);
# detect_leaks: LeakSanitizer at exit; abort_on_error=0 keeps the exit code non-zero
# without a core dump.
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=0:detect_stack_use_after_return=1:strict_init_order=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
regex="^($(echo test_sanitize "${unit_tests[@]}" | tr ' ' '|'))_(sanitize|unit)\$"
ctest --test-dir build-asan -L 'sanitize|unit' -R "$regex" --output-on-failure -j"$(nproc)" "$@"
