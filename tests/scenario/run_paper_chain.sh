#!/usr/bin/env bash
# femup run on the paper's study: JSON with parameters, rank, singular values,
# frequencies per state; plots written; factors recovered.
source "$(dirname "$0")/lib.sh"
"$FEMUP" run "$ROOT/examples/paper_chain_masses_1-3_wet.yaml" -o out > stdout.txt
grep -q "rank 12 of 13" stdout.txt || fail "report lacks the rank"
grep -q "common scaling" stdout.txt || fail "report lacks the null direction"
for f in result.json factors.png frequencies.png shapes_air.png shapes_water.png added_mass.mtx \
         updated_stiffness.mtx updated_dry_mass.mtx system_Z.mtx; do
  [ -s "out/$f" ] || fail "missing out/$f"
done
[ "$(json out/result.json "j['rank']")" = 12 ] || fail "rank"
[ "$(json out/result.json "len(j['singular_values'])")" = 13 ] || fail "singular values"
[ "$(json out/result.json "max(abs(p['estimate']-p['preset']) for p in j['parameters'])<1e-10")" = True ] \
  || fail "factors not recovered"
[ "$(json out/result.json "[round(f,3) for f in j['states'][1]['measured_hz']]")" = "[33.588, 95.673]" ] \
  || fail "water frequencies"
[ "$(json out/result.json "j['states'][0]['updated_hz'] is not None")" = True ] || fail "updated"
ls -a out | grep -q staging && fail "staging folder left behind"
echo "run_paper_chain: ok"
