#!/usr/bin/env bash
# Runs every benchmark on this machine and prints their CSV output (paste the figures
# into bench/RESULTS.md with the machine line). Usage: bash bench/run_all.sh [build dir]
set -euo pipefail
cd "$(dirname "$0")/.."
b=${1:-build}
echo "# machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# commit: $(git rev-parse --short HEAD)"
"$b/bench_pt" scenes/cornell.yaml scenes/cornell_specular.yaml scenes/cornell_glossy.yaml scenes/textured.yaml \
  scenes/concave.yaml --spp 16 --threads 1
"$b/bench_pt" scenes/cornell.yaml --spp 16 --threads 2
"$b/bench_build" 1000000
[ -x "$b/bench_reconstruct" ] && "$b/bench_reconstruct"
[ -x "$b/bench_gpt" ] && "$b/bench_gpt"
[ -x "$b/bench_manifold" ] && "$b/bench_manifold"
exit 0
