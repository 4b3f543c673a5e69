#!/usr/bin/env bash
# `render --partial --part K/N` + `merge` (issue 17): the merged parts of a render equal
# the single-process render bit for bit (same (pass, tile) work units and random streams,
# tile_scheduler.h) for `path`, `gpt`, `bdpt`, `gbdpt`, `vcm`, `gpm` and `gvcm` (every layer, the Poisson reconstructions
# included), with every pixel's count summed to --spp; for `mlt`, `memlt` and `gdmlt` (chain
# shares) up to double rounding, with a z-test of time-budgeted parts' scale; incompatible files (integrator,
# setting, seed, scene) and a repeated part are refused with one line naming the
# difference; time-budgeted parts merge; misuse of the options is a one-line error.
# Usage: test_merge.sh path/to/deltapath  (run from the repository root)
set -u
bin=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "$0")/harness.sh"  # check, $fail
# json_check FILE PYTHON-EXPRESSION (on `j`, the parsed sidecar)
json_check() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if ($2) else 1)" "$1" 2>/dev/null; }
# fails_with MESSAGE-REGEX COMMAND...: exit 1 and exactly one stderr line matching.
fails_with() {
  local pattern=$1; shift
  "$@" 2>"$tmp/err" >/dev/null
  local code=$?
  [ $code -eq 1 ] && [ "$(wc -l < "$tmp/err")" -eq 1 ] && grep -Eq -- "$pattern" "$tmp/err" && return 0
  echo "       exit $code, stderr: $(head -c 300 "$tmp/err")"
  return 1
}
# Bit-identical EXRs (the writer puts no time stamp in the file); on a difference, the metrics.
same_exr() {
  cmp -s "$1" "$2" && return 0
  "$bin" compare "$1" "$2" | sed 's/^/       /'
  return 1
}

# 72 x 40 pixels: 5 x 3 = 15 tiles, so with 2 parts a pixel's passes alternate between
# the parts (their sums are added in another order than the single render adds them),
# with 3 parts each part keeps its tiles; glossy materials exercise G-PT's shifts.
sed 's/resolution: \[256, 256\]/resolution: [72, 40]/' scenes/cornell_glossy.yaml > "$tmp/scene.yaml"
common=(--spp 8 --seed 3 --max-depth 5 --quiet)

for integrator in path volpath vpm bre beam gvpm gbre gpt bdpt gbdpt gpm gvcm vcm pr gpr; do
  d="$tmp/$integrator"
  mkdir -p "$d"
  r=("$bin" render "$tmp/scene.yaml" --integrator "$integrator" "${common[@]}")
  "${r[@]}" --threads 2 --out "$d/single.exr"
  check "$integrator: single render exits 0" test $? -eq 0
  for n in 2 3; do
    files=()
    for k in $(seq 1 $n); do
      # Thread counts differ between the parts: the result must not depend on them.
      "${r[@]}" --threads $((1 + k % 2)) --partial --part "$k/$n" --out "$d/p$k-$n.exr"
      check "$integrator: part $k/$n exits 0" test $? -eq 0
      check "$integrator: part $k/$n holds a share, not all (sidecar spp $k/$n)" \
        json_check "$d/p$k-$n.json" "j['part'] == '$k/$n' and j['spp_max'] > 0 and j['spp_min'] < 8 and not j['partial']"
      files=("$d/p$k-$n.exr" "${files[@]}")  # reversed: merge sorts by part
    done
    "$bin" merge "${files[@]}" --threads 2 --quiet --out "$d/merged$n.exr"
    check "$integrator: merge of $n parts exits 0" test $? -eq 0
    check "$integrator: merge of $n parts writes exr/png/json" test -s "$d/merged$n.png" -a -s "$d/merged$n.json"
    check "$integrator: merged counts are 8 spp everywhere, not partial" \
      json_check "$d/merged$n.json" "j['spp_min'] == 8 and j['spp_max'] == 8 and not j['partial'] and j['parts_merged'] == list(range(1, $n + 1))"
    check "$integrator: merge of $n parts equals the single render bit for bit (all layers)" \
      same_exr "$d/merged$n.exr" "$d/single.exr"
  done
done
check "gpt: merged output has the reconstruction layers" \
  json_check "$tmp/gpt/merged2.json" "all(l in j['layers'] for l in ['recon_l1', 'recon_l2', 'primal', 'dx', 'dy'])"
check "gpt: merged sidecar sums the parts' counters" \
  json_check "$tmp/gpt/merged2.json" "j['counters'].get('gpt.samples', 0) == 72 * 40 * 8"

# Time-budgeted parts (a job array with a wall-clock limit per task): each part runs its
# own passes (streams of passes k, n + k, ... of a single --time render; test_parts.cpp),
# the merge has every pixel sampled and is not partial.
for integrator in path volpath vpm bre beam gvpm gbre gpt bdpt gbdpt gpm gvcm vcm pr gpr; do
  for k in 1 2; do
    "$bin" render "$tmp/scene.yaml" --integrator $integrator --time 0.3 --seed 3 --max-depth 5 --threads 1 --quiet \
      --partial --part $k/2 --out "$tmp/t$integrator$k.exr"
  done
  "$bin" merge "$tmp/t${integrator}1.exr" "$tmp/t${integrator}2.exr" --quiet --out "$tmp/t$integrator.exr"
  check "$integrator: merge of 2 time-budgeted parts exits 0" test $? -eq 0
  check "$integrator: merged time-budgeted parts: every pixel sampled, not partial, no spp target" \
    json_check "$tmp/t$integrator.json" "j['spp_min'] >= 2 and not j['partial'] and j['spp_requested'] is None"
done

# The MCMC integrators (mlt in both state spaces, memlt, gdmlt in both): part k of n runs
# chains c = k-1 (mod n) of the whole chain set with the whole render's streams and its
# share of the bootstrap's samples (integrators/mcmc_raw.h), the direct pass its (pass,
# tile) units. The merged parts hold the single render's samples, but a pixel's splats
# from several chains are added in another order, so the double sums may differ in the
# last bits: same_up_to_rounding (harness.sh) accepts bit-identical files or layers within
# double rounding, and rejects another bootstrap per part or a lost part's buffers (Monte
# Carlo differences). Fixed chain count: the image does not depend on --threads.
mcmc_configs=("mlt:--integrator mlt" "mlt-path:--integrator mlt --set mutations=path" "memlt:--integrator memlt"
              "gdmlt:--integrator gdmlt" "gdmlt-path:--integrator gdmlt --set mutations=path --set candidates=2000")
mcmc_common=(--set chains=6 --set bootstrap=4000 --spp 4 --seed 3 --max-depth 5 --quiet)
for config in "${mcmc_configs[@]}"; do
  label=${config%%:*}
  read -ra args <<< "${config#*:}"
  d="$tmp/$label"
  mkdir -p "$d"
  r=("$bin" render "$tmp/scene.yaml" "${args[@]}" "${mcmc_common[@]}")
  "${r[@]}" --threads 2 --out "$d/single.exr"
  check "$label: single render exits 0" test $? -eq 0
  for n in 2 3; do
    files=()
    for k in $(seq 1 $n); do
      "${r[@]}" --threads $((1 + k % 2)) --partial --part "$k/$n" --out "$d/p$k-$n.exr"
      check "$label: part $k/$n exits 0, holds a share of the mutations" \
        json_check "$d/p$k-$n.json" "j['part'] == '$k/$n' and 0 < j['spp_max'] and j['spp_min'] < 4 and not j['partial']"
      files=("$d/p$k-$n.exr" "${files[@]}")
    done
    "$bin" merge "${files[@]}" --threads 2 --quiet --out "$d/merged$n.exr"
    check "$label: merge of $n parts: 4 mutations per pixel, not partial" \
      json_check "$d/merged$n.json" "j['spp_min'] == 4 and j['spp_max'] == 4 and not j['partial']"
    check "$label: merge of $n parts = the single render (all layers, up to double rounding)" \
      same_up_to_rounding "$bin" "$d/merged$n.exr" "$d/single.exr"
    check "$label: merge of $n parts sums the counters to the single render's" python3 -c "
import json,sys
a=json.load(open('$d/merged$n.json'))['counters']; b=json.load(open('$d/single.json'))['counters']
bad=[k for k in set(a)|set(b) if a.get(k)!=b.get(k)]
print('       differ:', bad[:5]) if bad else None
sys.exit(1 if bad or not b else 0)"
  done
done
check "gdmlt: merged output has the reconstruction and the adaptive kernel's layers" \
  json_check "$tmp/gdmlt/merged3.json" "all(l in j['layers'] for l in ['recon_l1', 'recon_l2', 'primal', 'direct', 'pairs.0', 'features.normal', 'ao', 'density'])"
"$bin" merge "$tmp/mlt/p1-3.exr" "$tmp/mlt/p3-3.exr" --quiet --out "$tmp/mlt/two.exr" 2>/dev/null
check "mlt: merge of 2 of 3 parts is marked partial, with its parts' mutations" \
  json_check "$tmp/mlt/two.json" "j['partial'] and 2 <= j['spp_min'] < 4"
check "gdmlt (adaptive kernel): a merge lacking a part is one line naming the missing feature buffers" \
  fails_with "p1-3.exr: gdmlt: the feature buffers of pixel 1 are in a missing part" \
  "$bin" merge "$tmp/gdmlt/p1-3.exr" "$tmp/gdmlt/p3-3.exr" --quiet --out "$tmp/x.exr"

# --time parts of the MCMC integrators reach different mutation counts; the image scale
# b W H / (summed mutations) must hold for any mix. No single render takes those samples,
# so this is a z-test of the merged image's mean (channel mean of `layer`, as a ratio to
# one reference render) against K independent --spp 4 renders (seeds 11..): their sample
# variance s^2 at 4 W H mutations, scaled by 4 W H / mutations for the merged render
# (MCMC variance falls as 1 / mutations), gives z = (m - mean) / sqrt(s^2 4WH/M + s^2/K);
# |z| < 6.87 = Student t, K - 1 = 5 dof, two-sided 0.001 (s^2 is estimated).
mean_ratio() {  # IMAGE LAYER REFERENCE -> channel mean of the layer's mean ratio
  "$bin" layer "$1" "$2" --out "$tmp/zl.exr" >/dev/null &&
    "$bin" compare --json "$tmp/zl.exr" "$3" | python3 -c "import json,sys; print(sum(json.load(sys.stdin)['mean_ratio']) / 3)"
}
for config in "mlt:--integrator mlt:RGB:mlt" "memlt:--integrator memlt:RGB:memlt" "gdmlt:--integrator gdmlt:primal:gdmlt"; do
  IFS=: read -r label opts layer counter <<< "$config"
  read -ra args <<< "$opts"
  d="$tmp/z-$label"
  mkdir -p "$d"
  z=(render "$tmp/scene.yaml" "${args[@]}" --set chains=6 --set bootstrap=4000 --max-depth 5 --quiet --threads 1)
  refs=()
  for s in 11 12 13 14 15 16; do
    "$bin" "${z[@]}" --spp 4 --seed $s --out "$d/ref$s.exr"
    "$bin" layer "$d/ref$s.exr" "$layer" --out "$d/reflayer$s.exr" >/dev/null
  done
  for s in 11 12 13 14 15 16; do refs+=("$(mean_ratio "$d/ref$s.exr" "$layer" "$d/reflayer11.exr")"); done
  for k in 1 2; do "$bin" "${z[@]}" --time 0.$((4 * k - 2)) --seed 5 --partial --part $k/2 --out "$d/t$k.exr"; done
  "$bin" merge "$d/t1.exr" "$d/t2.exr" --quiet --out "$d/t.exr"
  m=$(mean_ratio "$d/t.exr" "$layer" "$d/reflayer11.exr")
  check "$label: time-budgeted parts (different mutation counts) merge to the right scale (z-test)" python3 -c "
import json,math,statistics,sys
refs=[float(x) for x in '${refs[*]}'.split()]; m=float('$m')
muts=json.load(open('$d/t.json'))['counters']['$counter.mutations']; n_ref=4*72*40
s2=statistics.variance(refs); mean=statistics.fmean(refs)
z=(m-mean)/math.sqrt(s2*n_ref/muts + s2/len(refs))
print('       z = %.2f (merged %.4f, refs %.4f +- %.4f, %d mutations)' % (z, m, mean, math.sqrt(s2), muts))
sys.exit(0 if abs(z) < 6.87 else 1)"
done

# Incompatible files: one line naming what differs.
p=(render "$tmp/scene.yaml" --integrator path --spp 8 --max-depth 5 --quiet --partial --part 2/2)
"$bin" "${p[@]}" --seed 3 --set rr_depth=3 --out "$tmp/rr.exr"
"$bin" "${p[@]}" --seed 4 --out "$tmp/seed.exr"
sed 's/albedo: \[0.725, 0.71, 0.68\]/albedo: [0.7, 0.7, 0.7]/' "$tmp/scene.yaml" > "$tmp/other.yaml"
"$bin" render "$tmp/other.yaml" "${common[@]}" --integrator path --partial --part 2/2 --out "$tmp/scene2.exr"
a="$tmp/path/p1-2.exr"
check "merge path + gpt parts is refused naming the integrator" \
  fails_with "p2-2.exr: cannot merge with .*p1-2.exr: integrator differs \(.*: path, .*: gpt\)" "$bin" merge "$a" "$tmp/gpt/p2-2.exr" --out "$tmp/x.exr"
check "merge with another setting is refused naming it" \
  fails_with "setting.rr_depth differs \(.*: 5, .*: 3\)" "$bin" merge "$a" "$tmp/rr.exr" --out "$tmp/x.exr"
check "merge with another seed is refused naming it" \
  fails_with "seed differs \(.*: 3, .*: 4\)" "$bin" merge "$a" "$tmp/seed.exr" --out "$tmp/x.exr"
check "merge with another scene is refused naming the scene hash" \
  fails_with "scene_hash differs" "$bin" merge "$a" "$tmp/scene2.exr" --out "$tmp/x.exr"
check "merge of parts of different splits is refused" \
  fails_with "parts differs \(.*: 2, .*: 3\)" "$bin" merge "$a" "$tmp/path/p2-3.exr" --out "$tmp/x.exr"
check "a repeated part is refused" \
  fails_with "p1-2.exr: part 1/2 is also in .*p1-2.exr" "$bin" merge "$a" "$tmp/path/p2-2.exr" "$a" --out "$tmp/x.exr"
check "nothing written by refused merges" test ! -e "$tmp/x.exr" -a ! -e "$tmp/x.json"
check "a normal render is not a partial file" \
  fails_with "single.exr: .*not a --partial file" "$bin" merge "$tmp/path/single.exr" --out "$tmp/x.exr"
check "a missing file is named" fails_with "nope.exr" "$bin" merge "$a" "$tmp/nope.exr" --out "$tmp/x.exr"
head -c 1200 "$tmp/path/p2-2.exr" > "$tmp/cut.exr"
check "a truncated part is one line naming it" fails_with "cut.exr: cannot read EXR" "$bin" merge "$a" "$tmp/cut.exr" --out "$tmp/x.exr"

"$bin" compare "$a" "$tmp/path/single.exr" 2>"$tmp/err" >/dev/null
check "compare on a partial file says to merge it first" grep -q "merge. it first" "$tmp/err"

# A missing part: merged with a warning, marked partial, never silently complete.
"$bin" merge "$a" --quiet --out "$tmp/half.exr" 2>"$tmp/err"
check "merge of 1 of 2 parts exits 0" test $? -eq 0
check "merge of 1 of 2 parts warns about part 2" grep -q "parts 2 of 2 are missing" "$tmp/err"
check "merge of 1 of 2 parts is marked partial" json_check "$tmp/half.json" "j['partial'] and j['spp_min'] < 8"

# Option misuse.
check "more parts than work units is refused" \
  fails_with "only 15 work units" "$bin" render "$tmp/scene.yaml" --spp 1 --quiet --partial --part 1/16 --out "$tmp/misuse.exr"
"$bin" render "$tmp/scene.yaml" --spp 1 --quiet --part 1/2 --out "$tmp/misuse.exr" 2>/dev/null
check "--part without --partial is a usage error" test $? -ne 0 -a ! -e "$tmp/misuse.exr"
"$bin" render "$tmp/scene.yaml" --spp 1 --quiet --partial --part 3/2 --out "$tmp/misuse.exr" 2>"$tmp/err"
check "--part 3/2 is a usage error naming --part" grep -q -- "--part" "$tmp/err"

exit $fail
