#!/usr/bin/env bash
# Installs dependencies (apt), configures a Release build in build/ and builds it.
# Warnings are errors when CI=true.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
# ccache keys use paths relative to the checkout, so scripts/test_sanitize.sh's build-asan/
# reuses the objects of every folder it does not instrument.
export CCACHE_BASEDIR="$PWD"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDP_WERROR=$werror >/dev/null
cmake --build build -j"$(nproc)"
