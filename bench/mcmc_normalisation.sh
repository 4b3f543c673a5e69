#!/usr/bin/env bash
# Does the MCMC image scale converge with render time (issue 11, "normalisation that
# converges")? Renders the Cornell box (a small ceiling light) with PT for REF seconds
# as the reference, then `mlt` and `gdmlt` for T seconds each (seed 1, b refined by
# every large step, the default), and prints each image's mean over the reference's
# (`deltapath compare`). The reference's own standard error is printed from two
# independent halves. Usage: bash bench/mcmc_normalisation.sh [T=60] [REF=240] [build dir]
set -euo pipefail
cd "$(dirname "$0")/.."
t=${1:-60}
ref=${2:-240}
b=${3:-build}
out=$(mktemp -d)
echo "# machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# commit: $(git rev-parse --short HEAD); scene scenes/cornell.yaml; mlt/gdmlt ${t} s, PT reference 2 x $((ref / 2)) s"
"$b/deltapath" render scenes/cornell.yaml --integrator path --time $((ref / 2)) --seed 101 --quiet --out "$out/ref_a.exr"
"$b/deltapath" render scenes/cornell.yaml --integrator path --time $((ref / 2)) --seed 202 --quiet --out "$out/ref_b.exr"
echo "PT half A over half B (reference noise):"
"$b/deltapath" compare "$out/ref_a.exr" "$out/ref_b.exr" | grep "mean ratio"
for integ in mlt gdmlt; do
  "$b/deltapath" render scenes/cornell.yaml --integrator "$integ" --time "$t" --seed 1 --quiet --out "$out/$integ.exr"
  echo "$integ ${t} s over PT half A:"
  "$b/deltapath" compare "$out/$integ.exr" "$out/ref_a.exr" | grep "mean ratio"
  echo "$integ ${t} s over PT half B:"
  "$b/deltapath" compare "$out/$integ.exr" "$out/ref_b.exr" | grep "mean ratio"
done
rm -rf "$out"
