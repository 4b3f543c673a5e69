# Shared by the CLI test scripts (sourced): `check DESCRIPTION CONDITION...` prints ok/FAIL
# and remembers a failure in $fail, which the script exits with.
fail=0
check() {
  local what=$1; shift
  if "$@"; then echo "ok   - $what"; else echo "FAIL - $what"; fail=1; fi
}
# same_up_to_rounding BIN A.exr B.exr: bit-identical files, or else every layer (names from
# A's JSON sidecar) within double rounding of B's: relMSE <= 1e-10. Renders that take the
# same samples but add them in another order (the MCMC integrators' parts: splats of
# several chains land in one pixel) differ by at most a few float ulps per value (~1e-7
# relative, relMSE ~1e-14); any other difference (another bootstrap, a lost part, a wrong
# scale) is Monte Carlo noise or worse, relMSE > 1e-4 on these renders.
same_up_to_rounding() {
  local bin=$1 a=$2 b=$3 layer ok=0
  cmp -s "$a" "$b" && return 0
  local dir
  dir=$(mktemp -d)
  for layer in $(python3 -c "import json,sys; print(' '.join(json.load(open(sys.argv[1]))['layers']))" "${a%.exr}.json"); do
    "$bin" layer "$a" "$layer" --out "$dir/a.exr" >/dev/null && "$bin" layer "$b" "$layer" --out "$dir/b.exr" >/dev/null || { ok=1; break; }
    if ! "$bin" compare --json "$dir/a.exr" "$dir/b.exr" |
        python3 -c "import json,sys; j=json.load(sys.stdin); sys.exit(0 if j['relmse'] <= 1e-10 and j['nonfinite_pixels'] == 0 else 1)"; then
      echo "       layer $layer differs by more than rounding:"; "$bin" compare "$dir/a.exr" "$dir/b.exr" | sed 's/^/       /'
      ok=1
    fi
  done
  rm -rf "$dir"
  return $ok
}
