#!/usr/bin/env bash
# SIGINT / SIGTERM during `deltapath render` (issue 18): the first signal stops the render,
# the outputs are written complete and marked partial, and the exit status is 128 + signal
# (130 SIGINT, 143 SIGTERM); a signal while the scene loads exits with one line and writes
# nothing; never a truncated file, never a leftover temporary (*.tmp-<pid>).
# Usage: test_interrupt.sh path/to/deltapath  (run from the repository root)
set -u
# Job control: background jobs get their own process group and, unlike in a plain
# non-interactive shell, do not start with SIGINT ignored (as a terminal's Ctrl-C sees them).
set -m
bin=$1
tmp=$(mktemp -d)
# Only this shell cleans up: a forked child signalled before it execs would run the EXIT
# trap too (bash's fatal-signal handler) and delete the folder under the running test.
trap '[ "$BASHPID" = '$$' ] && rm -rf "$tmp"' EXIT
fail=0
check() {  # check DESCRIPTION CONDITION...
  local what=$1; shift
  if "$@"; then echo "ok   - $what"; else
    echo "FAIL - $what"; fail=1
    [ -n "${errfile:-}" ] && [ -f "$errfile" ] && sed 's/^/       stderr: /' "$errfile"
  fi
}
# A small, quick scene: a lit diffuse box corner, 48 x 32 pixels.
printf 'version: 1\ncamera: {position: [0,1,-3], look_at: [0,1,0], fov: 45, resolution: [48, 32]}\nmaterials: {w: {type: diffuse, albedo: [0.7,0.7,0.7]}}\nshapes:\n  - {type: quad, material: w, vertices: [[-2,0,-4],[2,0,-4],[2,0,4],[-2,0,4]]}\n  - {type: quad, material: w, vertices: [[-2,0,2],[2,0,2],[2,3,2],[-2,3,2]]}\nlights: [{type: point, position: [0.5, 2, 0], intensity: [4,4,4]}]\n' > "$tmp/box.yaml"

no_temporaries() { ! ls "$1" | grep -q '\.tmp-'; }
exr_reads() { "$bin" compare "$1" "$1" --json 2>/dev/null | grep -q '"relmse": 0'; }
# json_check FILE PYTHON-EXPRESSION (on `j`, the parsed sidecar)
json_check() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if ($2) else 1)" "$1" 2>/dev/null; }
# Outputs of an interrupted render in DIR/out.*: all three exist and parse, partial, spp > 0.
check_partial_outputs() {  # DIR LABEL
  local d=$1 what=$2
  check "$what: writes exr/png/json" test -s "$d/out.exr" -a -s "$d/out.png" -a -s "$d/out.json"
  check "$what: exr reads back" exr_reads "$d/out.exr"
  check "$what: json parses, partial, spp_min > 0" json_check "$d/out.json" "j['partial'] is True and j['spp_min'] > 0"
  check "$what: no temporary file left" no_temporaries "$d"
}
# wait_exec PID: returns once PID runs deltapath (not the forked shell that will exec it).
wait_exec() {
  local want i=0
  want=$(readlink -f "$bin")
  while [ "$(readlink /proc/$1/exe 2>/dev/null)" != "$want" ] && kill -0 $1 2>/dev/null && [ $i -lt 100000 ]; do
    i=$((i + 1))
  done
}
# wait_bounded PID: waits up to 60 s for PID and sets `code` to its exit status, or to
# "hung" (and SIGKILLs it) if it ignored the signal.
wait_bounded() {
  local pid=$1 i=0
  while kill -0 $pid 2>/dev/null && [ $i -lt 600 ]; do sleep 0.1; i=$((i + 1)); done
  if kill -0 $pid 2>/dev/null; then kill -KILL $pid; wait $pid 2>/dev/null; code=hung; return; fi
  wait $pid
  code=$?
}
# run_and_signal DIR DELAY SIGNAL ARGS...: starts a render into DIR/out.exr, sends SIGNAL
# after DELAY seconds, sets `code` to the exit status.
run_and_signal() {
  local d=$1 delay=$2 sig=$3; shift 3
  mkdir -p "$d"
  errfile="$d/err"
  "$bin" render "$@" --quiet --out "$d/out.exr" 2>"$d/err" &
  local pid=$!
  wait_exec $pid
  sleep "$delay"
  kill -"$sig" $pid
  wait_bounded $pid
}

# 1. SIGTERM and SIGINT during a --time render: partial outputs, exit 143 / 130.
run_and_signal "$tmp/term" 1.5 TERM "$tmp/box.yaml" --time 120 --threads 2
check "SIGTERM during render exits 143 (got $code)" test "$code" = 143
check_partial_outputs "$tmp/term" "SIGTERM"
check "SIGTERM: the exr says which pixels it lacks (layer spp)" "$bin" layer "$tmp/term/out.exr" spp --out "$tmp/term/spp.exr"
run_and_signal "$tmp/int" 1.5 INT "$tmp/box.yaml" --time 120 --threads 2
check "SIGINT during render exits 130 (got $code)" test "$code" = 130
check_partial_outputs "$tmp/int" "SIGINT"

# 2. A gradient integrator in --spp mode: stopped, reconstructed from the passes kept.
run_and_signal "$tmp/gpt" 1.5 TERM "$tmp/box.yaml" --integrator gpt --spp 1000000 --threads 2
check "SIGTERM during gpt exits 143 (got $code)" test "$code" = 143
check_partial_outputs "$tmp/gpt" "gpt SIGTERM"

# 2b. A signal during the reconstruction (the L1 solve of 1600 x 1200 pixels takes ~3 s on 2
#     threads; the render prints "reconstructing" when it starts): the solve stops at its next
#     reweighting, the outputs are written complete and partial, and the json says the
#     reconstruction was interrupted after fewer than its 20 reweightings.
d="$tmp/recon"
mkdir -p "$d"
errfile="$d/err"
sed 's/resolution: \[48, 32\]/resolution: [1600, 1200]/' "$tmp/box.yaml" > "$d/big.yaml"
"$bin" render "$d/big.yaml" --integrator gpt --spp 1 --threads 2 --out "$d/out.exr" 2>"$d/err" &
pid=$!
i=0
while ! grep -q "^reconstructing" "$d/err" 2>/dev/null && kill -0 $pid 2>/dev/null && [ $i -lt 1200 ]; do
  sleep 0.05
  i=$((i + 1))
done
sleep 0.3
kill -TERM $pid
wait_bounded $pid
check "SIGTERM during gpt's reconstruction exits 143 (got $code)" test "$code" = 143
check_partial_outputs "$d" "reconstruction SIGTERM"
check "reconstruction SIGTERM: json says the L1 solve was interrupted before its 20 reweightings" \
  json_check "$d/out.json" "j['info']['reconstruction_interrupted'] is True and j['info']['solve_l1_reweightings'] < 20"

# 3. A signal while the scene loads (the scene is a FIFO nobody writes: the loader blocks in
#    it): one line on stderr, exit 128 + signal, nothing written.
for sig in TERM INT; do
  d="$tmp/load-$sig"
  mkdir -p "$d"
  mkfifo "$d/scene.yaml"
  run_and_signal "$d" 0.5 $sig "$d/scene.yaml" --spp 1
  want=$([ $sig = TERM ] && echo 143 || echo 130)
  check "SIG$sig while loading exits $want (got $code)" test "$code" = "$want"
  check "SIG$sig while loading prints one line naming the signal" \
    test "$(grep -c . "$d/err")" -eq 1 -a "$(grep -c "SIG$sig" "$d/err")" -eq 1
  check "SIG$sig while loading writes nothing" test "$(ls "$d" | grep -v '^scene.yaml$' | grep -v '^err$' | wc -l)" -eq 0
done

# 4. A signal at once (right after exec: start-up or loading), and a second signal right after the
#    first: whatever exists is complete, nothing temporary is left.
for case in "now 0 TERM" "now-int 0 INT" "twice 1.5 TERM"; do
  set -- $case
  d="$tmp/$1"
  mkdir -p "$d"
  errfile="$d/err"
  "$bin" render "$tmp/box.yaml" --time 120 --threads 2 --quiet --out "$d/out.exr" 2>"$d/err" &
  pid=$!
  wait_exec $pid
  sleep "$2"
  kill -"$3" $pid
  [ "$1" = twice ] && kill -"$3" $pid
  wait_bounded $pid
  want=$([ "$3" = TERM ] && echo 143 || echo 130)
  check "$1: exits $want (got $code)" test "$code" = "$want"
  check "$1: no temporary file left" no_temporaries "$d"
  if [ -e "$d/out.exr" ]; then check "$1: the exr that exists reads back" exr_reads "$d/out.exr"; fi
  if [ -e "$d/out.json" ]; then check "$1: the json that exists is partial" json_check "$d/out.json" "j['partial'] is True"; fi
done

# 5. SIGTERM during an experiment's point: exit 143, the interrupted point is not kept
#    (no image, no .done marker), the cached reference is complete, no temporary file.
d="$tmp/exp"
mkdir -p "$d"
errfile="$d/err"
printf 'name: interrupt\nscene: %s\nreference: {integrator: path, spp: 16}\nbudget: {time: [120]}\nseeds: 1\nruns:\n  - {name: PT, integrator: path}\nmetrics: [relmse]\noutput: out\n' \
  "$PWD/tests/experiments/data/tiny_cornell.yaml" > "$d/e.yaml"
"$bin" experiment "$d/e.yaml" --out "$d/out" --threads 2 --no-plot --quiet 2>"$d/err" &
pid=$!
wait_exec $pid
sleep 2
kill -TERM $pid
wait_bounded $pid
check "SIGTERM during an experiment exits 143 (got $code)" test "$code" = 143
check "interrupted experiment says how to resume" grep -q "run it again to resume" "$d/err"
check "interrupted experiment keeps no image of the point" test -z "$(find "$d/out" -name '*.exr' -o -name '*.done')"
ref=$(find "$d/reference-cache" -name '*.exr')
check "interrupted experiment's cached reference reads back" exr_reads "$ref"
check "interrupted experiment leaves no temporary file" test -z "$(find "$d" -name '*.tmp-*')"

# 6. A --time budget too small for any sample is an error, not a black image.
errfile="$tmp/tiny.err"
"$bin" render "$tmp/box.yaml" --time 1e-9 --quiet --out "$tmp/tiny.exr" 2>"$tmp/tiny.err"
code=$?
check "--time 1e-9 exits 1 (got $code)" test $code -eq 1
check "--time 1e-9 says no samples were taken" grep -q "no samples were taken within --time" "$tmp/tiny.err"
check "--time 1e-9 writes nothing" test ! -e "$tmp/tiny.exr" -a ! -e "$tmp/tiny.json" -a ! -e "$tmp/tiny.png"
exit $fail
