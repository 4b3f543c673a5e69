# Shared by the CLI test scripts (sourced): `check DESCRIPTION CONDITION...` prints ok/FAIL
# and remembers a failure in $fail, which the script exits with.
fail=0
check() {
  local what=$1; shift
  if "$@"; then echo "ok   - $what"; else echo "FAIL - $what"; fail=1; fi
}
