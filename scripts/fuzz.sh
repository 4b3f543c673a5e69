#!/usr/bin/env bash
# Fuzzes the loaders (issue 18) with libFuzzer + AddressSanitizer + UBSan:
#   scripts/fuzz.sh SECONDS [TARGET ...]
# Targets (tests/fuzz/fuzz_entries.h): yaml_scene mitsuba_scene ply_mesh obj_mesh
# experiment_file (default: all, one after the other, SECONDS each). Installs clang and
# its libFuzzer runtime if missing, configures build-fuzz/ (clang, -DDP_FUZZ=ON), builds
# the fuzz_<target> executables and runs each from a corpus in fuzz/corpus/<target>/
# seeded with the repository's scenes, meshes and experiment files, the hand-written
# seeds in tests/fuzz/seeds/ and, when present, the Mitsuba scenes of ../shared/scenes.
# A crash (or a timeout, an out-of-memory, a leak) is moved to fuzz/findings/<target>/
# and the run restarts for the rest of the budget. A finding may contain text of a seed
# (the ../shared scenes must never be copied into the repository): reduce it to a minimal
# hand-written input in tests/fuzz/regressions/<target>/ and commit that with the fix;
# test_fuzz_regressions replays every file there in every build. fuzz/summary.txt gets
# one dated line per target and run (appended): executions, coverage (libFuzzer's cov and
# ft), findings.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:?usage: scripts/fuzz.sh SECONDS [TARGET ...]}
[[ "$secs" =~ ^[0-9]+$ ]] || { echo "fuzz.sh: SECONDS must be a whole number, got '$secs'" >&2; exit 2; }
shift
all=(yaml_scene mitsuba_scene ply_mesh obj_mesh experiment_file)
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=("${all[@]}")
for t in "${targets[@]}"; do
  [[ " ${all[*]} " == *" $t "* ]] || { echo "fuzz.sh: unknown target '$t' (${all[*]})" >&2; exit 2; }
done

if ! command -v clang++ >/dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  apt-get update -qq && apt-get install -y -qq clang libclang-rt-14-dev >/dev/null
fi
bash scripts/install_deps.sh
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DDP_FUZZ=ON -DDP_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]/#/fuzz_}"

seed_files() {  # the seed corpus of target $1
  case "$1" in
    yaml_scene) find scenes tests -name '*.yaml' -path '*scene*' 2>/dev/null; find scenes -maxdepth 1 -name '*.yaml' ;;
    mitsuba_scene) find tests/fuzz/seeds/mitsuba_scene ../shared/scenes -name '*.xml' 2>/dev/null || true ;;
    ply_mesh) find tests/fuzz/seeds/ply_mesh -name '*.ply'; find ../shared/scenes -name '*.ply' -size -64k 2>/dev/null || true ;;
    obj_mesh) find scenes -name '*.obj'; find ../shared/scenes -name '*.obj' -size -64k 2>/dev/null || true ;;
    experiment_file) find experiments -name '*.yaml' ;;
  esac
}

mkdir -p fuzz
# Appended, one dated line per target and run, so two runners (different targets) can share it.
for t in "${targets[@]}"; do
  corpus=fuzz/corpus/$t artifacts=fuzz/artifacts/$t/ log=fuzz/$t.log
  mkdir -p "$corpus" "$artifacts" "fuzz/findings/$t"
  seed_files "$t" | sort -u | while read -r f; do cp "$f" "$corpus/seed-$(basename "$f")"; done
  end=$(( $(date +%s) + secs )) execs=0 findings=0 cov=0 ft=0
  : > "$log"
  while :; do
    left=$(( end - $(date +%s) ))
    [ "$left" -gt 0 ] || break
    # -timeout: one input may take 10 s (loading builds an Embree scene); -max_len 64 KiB.
    set +e
    "build-fuzz/fuzz_$t" "$corpus" -max_total_time="$left" -max_len=65536 -timeout=10 -rss_limit_mb=4096 \
      -print_final_stats=1 -artifact_prefix="$artifacts" >>"$log" 2>&1
    rc=$?
    set -e
    n=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || echo 0)
    execs=$(( execs + ${n:-0} ))
    line=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
    if [ -n "$line" ]; then cov=$(echo "$line" | awk '{print $2}'); ft=$(echo "$line" | awk '{print $4}'); fi
    [ "$rc" -eq 0 ] && break
    findings=$(( findings + 1 ))
    for a in "$artifacts"*; do [ -f "$a" ] && mv "$a" "fuzz/findings/$t/"; done
    [ "$findings" -lt 20 ] || break
  done
  printf '%s %s: %s s, %s executions, cov %s, ft %s, findings %s (log fuzz/%s.log)\n' \
    "$(date -u +%Y-%m-%dT%H:%MZ)" "$t" "$secs" "$execs" "$cov" "$ft" "$findings" "$t" | tee -a fuzz/summary.txt
done
