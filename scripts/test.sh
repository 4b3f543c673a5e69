#!/usr/bin/env bash
# Installs dependencies, builds, and runs the fast test labels (unit, stat, render).
# Slow tests: ctest --test-dir build -L slow
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build -L 'unit|stat|render' --output-on-failure -j"$(nproc)"
