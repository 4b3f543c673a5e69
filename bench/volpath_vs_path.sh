#!/usr/bin/env bash
# Throughput of volpath against path on the same scenes without media (issue 15): both
# render the same scene at the same spp, alternately, `reps` times each, on one thread;
# prints each run's paths/s and the ratio volpath/path of the medians (1.0 = no cost for
# the medium support on a scene without media). Then volpath's paths/s on the media box
# (scenes/cornell_media.yaml) for scale. The load average is printed before and after.
# Usage: bash bench/volpath_vs_path.sh [build/deltapath] [spp (default 32)] [reps (default 3)]
set -euo pipefail
bin=${1:-build/deltapath}
spp=${2:-32}
reps=${3:-3}
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(d[sys.argv[2]])" "$1" "$2"; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "commit: $(git -C "$root" rev-parse --short HEAD)"
median() { python3 -c "import statistics,sys; print(statistics.median(float(x) for x in sys.argv[1:]))" "$@"; }
for scene in cornell cornell_specular cornell_glossy; do
  p=() v=()
  for ((i = 0; i < reps; ++i)); do
    for integrator in path volpath; do
      "$bin" render "$root/scenes/$scene.yaml" --integrator "$integrator" --spp "$spp" --threads 1 --seed $((i + 1)) \
        --out "$tmp/r.exr" --quiet
      s=$(field "$tmp/r.json" wall_seconds)
      if [[ $integrator == path ]]; then p+=("$s"); else v+=("$s"); fi
    done
  done
  mp=$(median "${p[@]}")
  mv=$(median "${v[@]}")
  printf '%-18s path %s s  volpath %s s  (medians %.3f / %.3f s)  throughput volpath/path %.3f\n' "$scene" \
    "${p[*]}" "${v[*]}" "$mp" "$mv" "$(python3 -c "print($mp / $mv)")"
done
"$bin" render "$root/scenes/cornell_media.yaml" --integrator volpath --spp "$spp" --threads 1 --out "$tmp/m.exr" --quiet
s=$(field "$tmp/m.json" wall_seconds)
printf 'cornell_media      volpath %.3f s, %.0f paths/s\n' "$s" "$(python3 -c "print(256 * 256 * $spp / $s)")"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
