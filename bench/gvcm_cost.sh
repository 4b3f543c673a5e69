#!/usr/bin/env bash
# Cost of the gradient-domain photon integrators (issue 13): seconds per iteration of
# gbdpt, vcm, gpm and gvcm at equal iterations on the 256x256 specular and glossy boxes
# (one run each, same machine state), and peak resident memory (the sidecar's
# peak_rss_bytes) of every one at 1280x720 on the specular box (2 iterations).
# Usage: bash bench/gvcm_cost.sh [build/deltapath] [iterations (default 8)]
set -euo pipefail
bin=${1:-build/deltapath}
n=${2:-8}
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(d[sys.argv[2]])" "$1" "$2"; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
for scene in cornell_specular cornell_glossy; do
  for integrator in gbdpt vcm gpm gvcm; do
    "$bin" render "$root/scenes/$scene.yaml" --integrator "$integrator" --spp "$n" --out "$tmp/r.exr" --quiet
    s=$(field "$tmp/r.json" wall_seconds)
    printf '%-18s %-6s %2d iterations  %8.2f s  %7.3f s/iteration\n' "$scene" "$integrator" "$n" "$s" \
      "$(python3 -c "print($s / $n)")"
  done
done
# 1280x720: the same scene file with its resolution replaced (written beside the original
# so that relative paths resolve), removed on exit.
hd="$root/scenes/.cornell_specular_1280x720.yaml"
trap 'rm -rf "$tmp" "$hd"' EXIT
sed 's/resolution: \[256, 256\]/resolution: [1280, 720]/' "$root/scenes/cornell_specular.yaml" > "$hd"
for integrator in gbdpt vcm gpm gvcm; do
  "$bin" render "$hd" --integrator "$integrator" --spp 2 --out "$tmp/hd.exr" --quiet
  printf '1280x720 specular  %-6s peak RSS %6.0f MiB  (%.1f s for 2 iterations)\n' "$integrator" \
    "$(python3 -c "print($(field "$tmp/hd.json" peak_rss_bytes) / 2**20)")" "$(field "$tmp/hd.json" wall_seconds)"
done
