#!/usr/bin/env bash
# femup noise: Rm statistics per factor and level, figures 4 and 5.
source "$(dirname "$0")/lib.sh"
"$FEMUP" noise "$ROOT/examples/paper_chain_noise.yaml" -o out -q
[ -s out/noise.json ] && [ -s out/rm_vs_level.png ] && [ -s out/factors_at_level.png ] \
  || fail "outputs missing"
[ "$(json out/noise.json "len(j['levels'])")" = 11 ] || fail "levels"
[ "$(json out/noise.json "j['rm_average_percent'][0] < 1e-8")" = True ] || fail "Rm at 0 %"
[ "$(json out/noise.json "all(a < b for a, b in zip(j['rm_average_percent'][:5], j['rm_average_percent'][1:6]))")" = True ] \
  || fail "Rm does not grow with the level"
echo "noise_study: ok"
