#!/usr/bin/env bash
# `render --mpi` under mpirun (issue 17): with N ranks on 2 cores (oversubscribed), the
# image equals the single-process render bit for bit (each rank renders the same
# (pass, tile) work units as `--part r+1/N`; rank 0 adds the buffers in rank order) for
# `path`, `volpath`, `vpm`, `bre`, `beam`, `gvpm`, `gbre`, `gpt`, `bdpt`, `gbdpt`, `vcm`, `gpm`, `gvcm`, `pr`, `gpr` (every layer, the Poisson reconstructions included), and equals the
# merge of the 3 `--partial` files of the same shares; counters are summed over the ranks;
# `mlt` (both state spaces), `memlt` and `gdmlt` (both) run chain shares: N ranks = the
# merge of N files bit for bit, = the single render up to double rounding;
# a --time render works; a rank that dies and --mpi with --partial are loud failures with no image written.
# Skipped (exit 0, says so) without mpirun or when deltapath was built without MPI.
# Usage: test_mpi.sh path/to/deltapath  (run from the repository root)
set -u
bin=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "$0")/harness.sh"  # check, $fail
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
if ! command -v mpirun >/dev/null; then echo "skipped: no mpirun"; exit 0; fi
sed 's/resolution: \[256, 256\]/resolution: [72, 40]/' scenes/cornell_glossy.yaml > "$tmp/scene.yaml"
if "$bin" render "$tmp/scene.yaml" --mpi --spp 1 --quiet --out "$tmp/probe.exr" 2>&1 | grep -q "without MPI"; then
  echo "skipped: deltapath built without MPI"
  exit 0
fi
json_check() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if ($2) else 1)" "$1" 2>/dev/null; }
same_exr() {
  cmp -s "$1" "$2" && return 0
  "$bin" compare "$1" "$2" | sed 's/^/       /'
  return 1
}
common=(--spp 8 --seed 3 --max-depth 5 --quiet)

for integrator in path volpath vpm bre beam gvpm gbre gpt bdpt gbdpt gpm gvcm vcm pr gpr; do
  d="$tmp/$integrator"
  mkdir -p "$d"
  r=(render "$tmp/scene.yaml" --integrator "$integrator" "${common[@]}")
  "$bin" "${r[@]}" --threads 2 --out "$d/single.exr"
  for n in 2 3; do
    mpirun -np $n "$bin" "${r[@]}" --threads 1 --out "$d/mpi$n.exr" 2>"$d/err$n"
    check "$integrator: mpirun -np $n exits 0" test $? -eq 0
    check "$integrator: $n ranks give the single-process image bit for bit" same_exr "$d/mpi$n.exr" "$d/single.exr"
    check "$integrator: sidecar says ranks = $n, with a wall time per rank" \
      json_check "$d/mpi$n.json" "j['ranks'] == $n and len(j['rank_wall_seconds']) == $n and j['mpi_bytes_gathered'] > 0"
    check "$integrator: only rank 0 wrote (no stderr)" test ! -s "$d/err$n"
  done
  # Counters are summed over the ranks: the same totals as one process.
  check "$integrator: counters summed over ranks equal the single render's" python3 -c "
import json,sys
a=json.load(open('$d/mpi3.json'))['counters']; b=json.load(open('$d/single.json'))['counters']
keys=[k for k in b if not k.endswith('_seconds')]
sys.exit(0 if all(a.get(k)==b[k] for k in keys) and keys else 1)"
  for k in 1 2 3; do "$bin" "${r[@]}" --threads 1 --partial --part "$k/3" --out "$d/p$k.exr"; done
  "$bin" merge "$d/p1.exr" "$d/p2.exr" "$d/p3.exr" --quiet --out "$d/merged.exr"
  check "$integrator: merge of 3 partial files = mpirun -np 3" same_exr "$d/merged.exr" "$d/mpi3.exr"
done

mpirun -np 2 "$bin" render "$tmp/scene.yaml" --integrator gpt --time 1 --quiet --threads 1 --out "$tmp/timed.exr"
check "--time under mpirun exits 0 with samples from both ranks" \
  json_check "$tmp/timed.json" "j['ranks'] == 2 and j['spp_min'] > 0 and j['partial'] == False"

# The MCMC integrators: rank r runs chains c = r (mod N) with the whole render's streams
# and its share of the bootstrap's samples (integrators/mcmc_raw.h); rank 0 adds the
# buffers in rank order, as merge adds parts: N ranks = the merge of N partial files bit
# for bit. Against the single render (and 2 ranks against 3 parts) a pixel's splats from
# several chains are added in another order: equal up to double rounding
# (same_up_to_rounding, harness.sh), which another bootstrap per rank or a lost rank's
# buffers fail by far.
mcmc_configs=("mlt:--integrator mlt" "mlt-path:--integrator mlt --set mutations=path" "memlt:--integrator memlt"
              "gdmlt:--integrator gdmlt" "gdmlt-path:--integrator gdmlt --set mutations=path --set candidates=2000")
for config in "${mcmc_configs[@]}"; do
  label=${config%%:*}
  read -ra args <<< "${config#*:}"
  d="$tmp/$label"
  mkdir -p "$d"
  r=(render "$tmp/scene.yaml" "${args[@]}" --set chains=6 --set bootstrap=4000 --spp 4 --seed 3 --max-depth 5 --quiet)
  "$bin" "${r[@]}" --threads 2 --out "$d/single.exr"
  for k in 1 2 3; do "$bin" "${r[@]}" --threads 1 --partial --part "$k/3" --out "$d/p$k.exr"; done
  "$bin" merge "$d/p1.exr" "$d/p2.exr" "$d/p3.exr" --quiet --out "$d/merged.exr"
  for n in 2 3; do
    mpirun -np $n "$bin" "${r[@]}" --threads 1 --out "$d/mpi$n.exr" 2>"$d/err$n"
    check "$label: mpirun -np $n exits 0, ranks = $n, 4 mutations per pixel" \
      json_check "$d/mpi$n.json" "j['ranks'] == $n and j['spp_min'] == 4 and not j['partial'] and j['mpi_bytes_gathered'] > 0"
    check "$label: only rank 0 wrote (no stderr)" test ! -s "$d/err$n"
  done
  check "$label: merge of 3 partial files = mpirun -np 3 bit for bit" same_exr "$d/merged.exr" "$d/mpi3.exr"
  check "$label: mpirun -np 2 = merge of 3 partial files (up to double rounding)" \
    same_up_to_rounding "$bin" "$d/mpi2.exr" "$d/merged.exr"
  check "$label: mpirun -np 3 = the single render (up to double rounding)" \
    same_up_to_rounding "$bin" "$d/mpi3.exr" "$d/single.exr"
  check "$label: counters summed over 2 ranks equal the single render's" python3 -c "
import json,sys
a=json.load(open('$d/mpi2.json'))['counters']; b=json.load(open('$d/single.json'))['counters']
bad=[k for k in set(a)|set(b) if a.get(k)!=b.get(k)]
print('       differ:', bad[:5]) if bad else None
sys.exit(1 if bad or not b else 0)"
done

# Rank 1 is killed before it renders: mpirun must fail and rank 0 must not write an image.
mpirun -np 2 bash -c 'if [ "$OMPI_COMM_WORLD_RANK" = 1 ]; then kill -9 $$; fi; exec "$0" "$@"' \
  "$bin" render "$tmp/scene.yaml" --spp 4 --quiet --out "$tmp/dead.exr" >/dev/null 2>&1
code=$?
check "a rank that dies fails the run (exit $code), no image written" test $code -ne 0 -a ! -e "$tmp/dead.exr"

"$bin" render "$tmp/scene.yaml" --mpi --partial --spp 1 --out "$tmp/x.exr" >/dev/null 2>&1
check "--mpi with --partial is a usage error" test $? -ne 0 -a ! -e "$tmp/x.exr"
# An experiment file with `launcher: mpirun -np 2` runs every point through mpirun; its
# points (spp budgets) equal the in-process experiment's bit for bit, so the CSVs match.
for mode in local mpi; do
  {
    echo "name: launch-$mode"
    echo "scene: scene.yaml"
    echo "reference: {integrator: path, spp: 16}"
    echo "budget: {spp: [4]}"
    echo "runs:"
    echo "  - {name: PT, integrator: path}"
    echo "  - {name: G-PT L1, integrator: gpt, reconstruction: l1}"
    echo "metrics: [relmse, mse]"
    echo "output: out-$mode"
    [ $mode = mpi ] && echo "launcher: mpirun -np 2"
  } > "$tmp/exp-$mode.yaml"
  "$bin" experiment "$tmp/exp-$mode.yaml" --quiet --no-plot --threads 1 >/dev/null 2>"$tmp/exp-$mode.err"
  check "experiment ($mode) exits 0" test $? -eq 0
done
check "launcher: mpirun -np 2 gives the in-process experiment's metrics exactly" \
  cmp -s <(cut -d, -f1-3,5- "$tmp/out-local/results.csv") <(cut -d, -f1-3,5- "$tmp/out-mpi/results.csv")
check "  ... and its points' sidecars say 2 ranks" \
  json_check "$(ls "$tmp"/out-mpi/runs/*/*.json 2>/dev/null | head -1)" "j['info']['ranks'] == 2"
exit $fail
