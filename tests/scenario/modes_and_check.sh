#!/usr/bin/env bash
# femup modes and femup check on the paper's cantilever model.
source "$(dirname "$0")/lib.sh"
"$FEMUP" check "$ROOT/examples/cantilever_model_a.yaml" | grep -q "30 DOFs" || fail "check"
"$FEMUP" modes "$ROOT/examples/cantilever_model_a.yaml" -o out -n 4 -q
[ -s out/mode_shapes.png ] || fail "mode shape plot"
# method.md: 7.82 / 49.01 Hz; continuous Euler-Bernoulli for this I: 7.818 / 48.995 Hz.
[ "$(json out/modes.json "abs(j['frequencies_hz'][0]-7.82)<0.005 and abs(j['frequencies_hz'][1]-49.01)<0.02")" = True ] \
  || fail "cantilever frequencies $(json out/modes.json "j['frequencies_hz'][:2]")"
echo "modes_and_check: ok"
