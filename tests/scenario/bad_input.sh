#!/usr/bin/env bash
# Bad input: a clear message naming file and field, exit code 1, no output.
source "$(dirname "$0")/lib.sh"
expect_error() {  # expect_error NEEDLE ARGS...
  local needle="$1"; shift
  set +e; "$FEMUP" "$@" > stdout.txt 2> stderr.txt; local rc=$?; set -e
  [ "$rc" = 1 ] || fail "exit code $rc for $*"
  grep -qF -- "$needle" stderr.txt || fail "message lacks '$needle': $(cat stderr.txt)"
}
expect_error "missing.yaml: study file not found" run missing.yaml -o out1
[ -e out1 ] && fail "output created for a missing study"

sed 's/^solver:/solvr:/' "$ROOT/examples/paper_chain_masses_1-3_wet.yaml" > typo.yaml
expect_error "typo.yaml:" run typo.yaml -o out2
grep -q "solvr: unknown key" stderr.txt || fail "unknown key not named"
[ -e out2 ] && fail "output created for a bad study"

sed 's/masses: \[50, 50, 50, 50, 50\]/masses: [50, 50, .nan, 50, 50]/' \
  "$ROOT/examples/paper_chain_masses_1-3_wet.yaml" > nan.yaml
expect_error "model.masses[3]" run nan.yaml -o out3

# A failing run must not touch an existing output folder's files.
mkdir -p out4 && echo keep > out4/result.json
sed 's/form: summed .*/form: summed/; s/- {state: water, immersion: wet, simulate_modes: 2}//' \
  "$ROOT/examples/paper_chain_masses_1-3_wet.yaml" > dry_only.yaml
expect_error "stacked" run dry_only.yaml -o out4
[ "$(cat out4/result.json)" = keep ] || fail "old output overwritten by a failed run"
[ "$(ls -A out4 | wc -l)" = 1 ] || fail "partial output left: $(ls -A out4)"

set +e; "$FEMUP" run > /dev/null 2>&1; rc=$?; set -e
[ "$rc" != 0 ] || fail "missing argument accepted"
echo "bad_input: ok"
