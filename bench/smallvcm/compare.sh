#!/usr/bin/env bash
# Deltapath's `vcm` against SmallVCM (Georgiev et al.'s reference implementation of VCM) on
# SmallVCM's four scenes (scenes/smallvcm_*.yaml, written by make_scenes.py).
#
#   bench/smallvcm/compare.sh SMALLVCM_DIR [ITERATIONS] [ALGORITHMS]
#
# SMALLVCM_DIR: a checkout of github.com/SmallVCM/SmallVCM (not vendored; not needed by any
# test). Builds it with g++ -O3 -fopenmp into build/smallvcm/, then for every scene and
# algorithm (default "vcm bpt bpm ppm lt"; SmallVCM's acronyms, ours: mode=vcm|bpt|vm|ppm|lt)
# renders ITERATIONS (default 64) iterations with both renderers on all cores, and a second
# Deltapath render with another seed. Prints the wall times and, from `deltapath compare`,
# the per-channel mean ratio Deltapath / SmallVCM and the MAPE between them next to the
# MAPE between Deltapath's two seeds: the images agree to the noise when the first is not
# above the second. Run from the repository root after scripts/build.sh.
set -euo pipefail
cd "$(dirname "$0")/../.."
src=${1:?usage: bench/smallvcm/compare.sh SMALLVCM_DIR [ITERATIONS] [ALGORITHMS]}
iters=${2:-64}
algos=${3:-"vcm bpt bpm ppm lt"}
out=build/smallvcm
mkdir -p "$out"
if [ ! -x "$out/smallvcm" ]; then
  g++ -O3 -fopenmp -std=c++11 -o "$out/smallvcm" "$src/src/smallvcm.cxx"
fi
mode_of() { case "$1" in bpm) echo vm ;; *) echo "$1" ;; esac; }
metric() { grep "$1" | sed "s/^$1 *//"; }
printf '%-34s %-4s %9s %9s  %-28s %8s %8s\n' scene alg "svcm s" "ours s" "mean ratio ours/svcm (RGB)" "MAPE" "MAPE ss"
for yaml in scenes/smallvcm_[0-3]_*.yaml; do
  idx=$(basename "$yaml" | cut -c10)
  name=$(basename "$yaml" .yaml)
  for a in $algos; do
    t0=$(date +%s.%N)
    "$out/smallvcm" -s "$idx" -a "$a" -i "$iters" -o "$out/${name}_$a.hdr" >/dev/null
    t1=$(date +%s.%N)
    build/deltapath render "$yaml" --integrator vcm --set mode="$(mode_of "$a")" --spp "$iters" --seed 1 \
      --out "$out/${name}_$a.exr" --quiet
    t2=$(date +%s.%N)
    build/deltapath render "$yaml" --integrator vcm --set mode="$(mode_of "$a")" --spp "$iters" --seed 2 \
      --out "$out/${name}_${a}_seed2.exr" --quiet
    cmp_out=$(build/deltapath compare "$out/${name}_$a.exr" "$out/${name}_$a.hdr")
    self=$(build/deltapath compare "$out/${name}_$a.exr" "$out/${name}_${a}_seed2.exr" | metric "MAPE:")
    ratio=$(echo "$cmp_out" | metric "mean ratio:")
    mape=$(echo "$cmp_out" | metric "MAPE:")
    printf '%-34s %-4s %9.1f %9.1f  %-28s %8s %8s\n' "$name" "$a" "$(awk "BEGIN{print $t1 - $t0}")" "$(awk "BEGIN{print $t2 - $t1}")" \
      "$ratio" "$mape" "$self"
  done
done
