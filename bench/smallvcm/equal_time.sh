#!/usr/bin/env bash
# Equal-time error of Deltapath's `vcm` (modes vcm, bpt) and `bdpt` against SmallVCM's vcm
# and bpt on SmallVCM's scenes (scenes/smallvcm_*.yaml): relMSE against one long Deltapath
# VCM reference per scene (compare.sh shows both renderers agree in expectation).
#
#   bench/smallvcm/equal_time.sh SMALLVCM_DIR [SCENES] [BUDGETS] [REF_ITERATIONS]
#
# Defaults: scenes "0 1" (sun + small spheres; light box + large mirror), budgets "10 30"
# seconds, reference 128 VCM iterations. Prints one line per scene, renderer and budget:
# iterations reached (ours, from the JSON sidecar; SmallVCM does not report them) and relMSE.
set -euo pipefail
cd "$(dirname "$0")/../.."
src=${1:?usage: bench/smallvcm/equal_time.sh SMALLVCM_DIR [SCENES] [BUDGETS] [REF_ITERATIONS]}
scenes=${2:-"0 1"}
budgets=${3:-"10 30"}
ref_iters=${4:-128}
out=build/smallvcm
mkdir -p "$out"
[ -x "$out/smallvcm" ] || g++ -O3 -fopenmp -std=c++11 -o "$out/smallvcm" "$src/src/smallvcm.cxx"
relmse() { build/deltapath compare "$1" "$2" | grep "relMSE:" | awk '{print $2}'; }
spp_of() { grep -o '"spp_min": *[0-9]*' "$1" | grep -o '[0-9]*$'; }
for idx in $scenes; do
  yaml=$(ls scenes/smallvcm_${idx}_*.yaml)
  name=$(basename "$yaml" .yaml)
  ref="$out/${name}_reference.exr"
  [ -f "$ref" ] || build/deltapath render "$yaml" --spp "$ref_iters" --seed 99 --out "$ref" --quiet
  for t in $budgets; do
    for a in vcm bpt; do
      "$out/smallvcm" -s "$idx" -a "$a" -t "$t" -o "$out/${name}_svcm_${a}_${t}s.hdr" >/dev/null
      printf '%-34s %-14s %4ss  %-16s relMSE %s\n' "$name" "SmallVCM $a" "$t" "-" \
        "$(relmse "$out/${name}_svcm_${a}_${t}s.hdr" "$ref")"
      build/deltapath render "$yaml" --set mode="$a" --time "$t" --seed 1 --out "$out/${name}_ours_${a}_${t}s.exr" --quiet
      printf '%-34s %-14s %4ss  %-16s relMSE %s\n' "$name" "vcm mode=$a" "$t" \
        "$(spp_of "$out/${name}_ours_${a}_${t}s.json") iterations" "$(relmse "$out/${name}_ours_${a}_${t}s.exr" "$ref")"
    done
    build/deltapath render "$yaml" --integrator bdpt --time "$t" --seed 1 --out "$out/${name}_bdpt_${t}s.exr" --quiet
    printf '%-34s %-14s %4ss  %-16s relMSE %s\n' "$name" "bdpt" "$t" \
      "$(spp_of "$out/${name}_bdpt_${t}s.json") spp" "$(relmse "$out/${name}_bdpt_${t}s.exr" "$ref")"
  done
done
