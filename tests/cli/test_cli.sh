#!/usr/bin/env bash
# End-to-end checks of the deltapath CLI: outputs of render, one-line errors with
# non-zero exit for bad input, Ctrl-C keeping a partial render, info and compare.
# Usage: test_cli.sh path/to/deltapath  (run from the repository root)
set -u
bin=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
source "$(dirname "$0")/harness.sh"  # check, $fail

# 1. A render writes EXR, PNG and a JSON sidecar with the resolved settings.
"$bin" render scenes/cornell.yaml --spp 2 --threads 2 --quiet --set rr_depth=3 --out "$tmp/c.exr" 2>"$tmp/err"
check "render exits 0" test $? -eq 0
check "render writes exr/png/json" test -s "$tmp/c.exr" -a -s "$tmp/c.png" -a -s "$tmp/c.json"
check "sidecar has settings and spp" grep -q '"rr_depth": "3"' "$tmp/c.json"
check "sidecar not partial" grep -q '"partial": false' "$tmp/c.json"
check "sidecar records peak memory" grep -Eq '"peak_rss_bytes": [1-9][0-9]{6,}' "$tmp/c.json"

# 2. Bad input: one line on stderr naming file:line, exit code 1, no crash.
printf 'version: 1\ncamera: {position: [0,0,0], look_at: [0,0,1], fov: 45, resolution: [8, 8]}\nshapes:\n  - {type: sphere, center: [0,0,3], radius: -1, material: nope}\n' > "$tmp/bad.yaml"
"$bin" render "$tmp/bad.yaml" --quiet --out "$tmp/b.exr" 2>"$tmp/err"
code=$?
check "bad scene exits 1 (got $code)" test $code -eq 1
check "bad scene error is one line" test "$(wc -l < "$tmp/err")" -eq 1
check "bad scene error names file:line" grep -q "bad.yaml:4:" "$tmp/err"
printf 'version: 1\ncamera: [1, 2\n' > "$tmp/malformed.yaml"
"$bin" info "$tmp/malformed.yaml" 2>"$tmp/err"
check "malformed yaml exits 1" test $? -eq 1
check "malformed yaml names the file" grep -q "malformed.yaml" "$tmp/err"
"$bin" render "$tmp/none.yaml" --quiet 2>"$tmp/err"
check "missing scene exits 1" test $? -eq 1
"$bin" render scenes/cornell.yaml --spp 1 --quiet --set no_such_key=1 --out "$tmp/x.exr" 2>"$tmp/err"
check "unknown setting exits 1" test $? -eq 1
check "unknown setting is named" grep -q "no_such_key" "$tmp/err"
"$bin" render scenes/cornell.yaml --integrator nope --quiet 2>"$tmp/err"
check "unknown integrator exits 1" test $? -eq 1

# Extreme numeric options are usage errors naming the option (issue 18), never silently
# ignored, an endless render or an abort.
for bad in "--spp 0" "--spp -1" "--max-depth -1" "--time nan" "--time inf" "--time -3" "--threads 100000"; do
  set -- $bad
  "$bin" render scenes/cornell.yaml $bad --quiet --out "$tmp/v.exr" 2>"$tmp/err" >/dev/null
  code=$?
  check "render $bad is a usage error (exit $code)" test $code -ne 0 -a $code -lt 128
  check "render $bad names $1" grep -q -- "^$1:" "$tmp/err"
done
for cmd in "stress --quick" "experiment experiments/figures/gbdpt_vs_bdpt.yaml"; do
  "$bin" $cmd --threads 100000 2>"$tmp/err" >/dev/null
  code=$?
  check "$cmd --threads 100000 is a usage error (exit $code)" test $code -ne 0 -a $code -lt 128
done
# An image too large to allocate is a file:line error, not std::bad_alloc.
printf 'version: 1\ncamera: {position: [0,0,0], look_at: [0,0,1], fov: 45, resolution: [65536, 65536]}\nshapes:\n  - {type: sphere, center: [0,0,3], radius: 1}\n' > "$tmp/huge.yaml"
"$bin" render "$tmp/huge.yaml" --spp 1 --quiet --out "$tmp/h.exr" 2>"$tmp/err"
code=$?
check "65536 x 65536 film exits 1 (got $code)" test $code -eq 1
check "65536 x 65536 film error is one line naming file:line" grep -q "huge.yaml:2:.*resolution" "$tmp/err"
# A time budget below one sample is an error (exit 1, nothing written), not a black image.
"$bin" render scenes/cornell.yaml --time 1e-9 --quiet --out "$tmp/tiny.exr" 2>"$tmp/err"
check "tiny time budget exits 1" test $? -eq 1
check "tiny time budget says no samples were taken" grep -q "no samples were taken within --time 1e-09" "$tmp/err"
check "tiny time budget writes nothing" test ! -e "$tmp/tiny.exr" -a ! -e "$tmp/tiny.json"

# 3. Ctrl-C stops at a tile boundary, writes what was rendered, marked partial, and exits
#    130 (more signal cases: test_interrupt.sh).
"$bin" render scenes/cornell.yaml --time 60 --threads 2 --quiet --out "$tmp/int.exr" 2>"$tmp/err" &
pid=$!
sleep 2
kill -INT $pid
wait $pid
code=$?
check "interrupted render exits 130 (got $code)" test $code -eq 130
check "interrupted render writes images" test -s "$tmp/int.exr" -a -s "$tmp/int.png"
check "interrupted render is marked partial" grep -q '"partial": true' "$tmp/int.json"

# 4. info and compare.
"$bin" info scenes/cornell.yaml > "$tmp/info" 2>&1
check "info prints caps" grep -q "has_specular=0" "$tmp/info"
"$bin" compare "$tmp/c.exr" "$tmp/c.exr" --json > "$tmp/cmp" 2>&1
check "compare of an image with itself has zero relMSE" grep -q '"relmse": 0' "$tmp/cmp"
printf 'version: 1\ncamera: {position: [0,0,0], look_at: [0,0,1], fov: 45, resolution: [8, 4]}\nlights: [{type: environment, radiance: [1, 1, 1]}]\n' > "$tmp/small.yaml"
"$bin" render "$tmp/small.yaml" --spp 1 --quiet --out "$tmp/small.exr" 2>"$tmp/err"
check "scene without shapes renders the environment" test $? -eq 0
"$bin" compare "$tmp/c.exr" "$tmp/small.exr" 2>"$tmp/err"
check "compare of different sizes exits 1" test $? -eq 1

# 5. A gdmlt render with the adaptive kernel carries its pair list: `reconstruct --in`
#    solves it again (L2, the integrator's alpha) and matches the render's recon_l2; `layer`
#    extracts a named layer and names the layers it has when asked for a missing one.
printf 'version: 1\ncamera: {position: [0,1,-3], look_at: [0,1,0], fov: 45, resolution: [24, 16]}\nmaterials: {w: {type: diffuse, albedo: [0.7,0.7,0.7]}}\nshapes:\n  - {type: quad, material: w, vertices: [[-2,0,-4],[2,0,-4],[2,0,4],[-2,0,4]]}\n  - {type: quad, material: w, vertices: [[-2,0,2],[2,0,2],[2,3,2],[-2,3,2]]}\nlights: [{type: point, position: [0.5, 2, 0], intensity: [4,4,4]}]\n' > "$tmp/room.yaml"
"$bin" render "$tmp/room.yaml" --integrator gdmlt --spp 2 --threads 2 --quiet --set bootstrap=2000 --out "$tmp/g.exr" 2>"$tmp/err"
check "gdmlt adaptive render exits 0" test $? -eq 0
"$bin" reconstruct --in "$tmp/g.exr" --norm l2 --out "$tmp/re.exr" >/dev/null 2>"$tmp/err"
check "reconstruct of a pair-layer render exits 0" test $? -eq 0
"$bin" layer "$tmp/g.exr" recon_l2 --out "$tmp/l2.exr" >/dev/null 2>"$tmp/err"
check "layer extracts recon_l2" test $? -eq 0
"$bin" compare "$tmp/re.exr" "$tmp/l2.exr" --json > "$tmp/cmp" 2>&1
check "reconstruct --in matches the render's recon_l2 (relMSE < 1e-8)" \
  python3 -c "import json,sys; sys.exit(0 if json.load(open('$tmp/cmp'))['relmse'] < 1e-8 else 1)"
"$bin" layer "$tmp/g.exr" no_such_layer --out "$tmp/n.png" 2>"$tmp/err"
check "layer of a missing name exits 1" test $? -eq 1
check "layer error lists the layers" grep -q "pairs.0.offset" "$tmp/err"
exit $fail
