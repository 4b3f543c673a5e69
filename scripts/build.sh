#!/usr/bin/env bash
# Installs dependencies (apt), configures a Release build in build/ and builds it.
# Warnings are errors when CI=true.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDP_WERROR=$werror >/dev/null
cmake --build build -j"$(nproc)"
