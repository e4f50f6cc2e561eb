#!/usr/bin/env bash
# femup solve on a general problem from files (Hansen's shaw written as CSV by
# this script is not available here, so a small known problem): every solver by
# name, Tikhonov's L-curve/GCV outputs, bounds; femup run with --solver and
# --method overrides; bad solver names fail before work.
source "$(dirname "$0")/lib.sh"
# A 6 x 3 problem with known x = (1, -2, 0.5) and exact data.
small_problem "a,b,c"
printf '1\n-2\n0.5\n' > x.csv
for s in lstsq tsvd bvls ceres ipopt; do
  "$FEMUP" solve --A A.csv --b b.csv --truth x.csv --solver "$s" -o "out_$s" -q \
    || fail "solve --solver $s"
  [ "$(json "out_$s/solution.json" "j['relative_error'] < 1e-8")" = True ] || fail "$s error"
  [ -s "out_$s/x.csv" ] || fail "$s: x.csv"
done
"$FEMUP" solve --A A.csv --b b.csv --solver tikhonov --parameter-choice lcurve -o out_tik -q \
  || fail "tikhonov"
[ "$(json out_tik/solution.json "j['regularisation']['parameter_choice']")" = lcurve ] \
  || fail "tikhonov report"
[ -s out_tik/solution.png ] || fail "tikhonov plot"
# Bounds: upper bound 0 on every unknown.
printf '0\n0\n0\n' > up.csv
"$FEMUP" solve --A A.csv --b b.csv --upper up.csv --solver bvls -o out_bnd -q || fail "bounded"
[ "$(json out_bnd/solution.json "max(j['x']) <= 0")" = True ] || fail "bound not held"
# Unknown solver: exit 1 and a message naming the choices, no output folder.
if "$FEMUP" solve --A A.csv --b b.csv --solver magic -o out_bad 2> err.txt; then
  fail "unknown solver accepted"
fi
grep -q "available: lstsq, tsvd, tikhonov, bvls, ceres, ipopt" err.txt || fail "message"
[ -e out_bad ] && fail "output left behind"
# A malformed CSV names the file and line.
printf '1,2\n3,x\n' > bad.csv
"$FEMUP" solve --A bad.csv --b b.csv -o out_bad2 2> err2.txt && fail "bad csv accepted"
grep -q "bad.csv:2" err2.txt || fail "csv message: $(cat err2.txt)"
# The paper study with overrides: sensitivity on ipopt recovers the factors.
"$FEMUP" run "$ROOT/examples/paper_chain_masses_1-3_wet_stacked.yaml" --method sensitivity \
  --solver ipopt -o out_sens -q || fail "run --method sensitivity"
[ "$(json out_sens/result.json "j['solver']['method']")" = sensitivity ] || fail "method"
[ "$(json out_sens/result.json "max(abs(p['estimate']-p['preset']) for p in j['parameters'])<1e-7")" = True ] \
  || fail "sensitivity factors"
"$FEMUP" run "$ROOT/examples/paper_chain_masses_1-3_wet.yaml" --solver nope -o out_x 2> e3.txt \
  && fail "bad --solver accepted"
grep -q "solver" e3.txt || fail "override message"
# Solver comparison in the noise study: the same draws for every solver; the
# output-error fits beat the linear solve (20 draws: a smoke test of the
# pipeline; docs/solvers.md has the 1000-draw figures).
/usr/bin/env python3 - "$ROOT/examples/paper_chain_solver_comparison.yaml" <<'PY'
import sys
text = open(sys.argv[1]).read().replace("draws: 100", "draws: 20")
text = text.replace("levels: [0.001, 0.002, 0.005]", "levels: [0.002]")
open("compare.yaml", "w").write(text)
PY
"$FEMUP" noise compare.yaml -o out_cmp -q || fail "noise compare"
[ -s out_cmp/rm_by_solver.png ] || fail "comparison plot"
[ "$(json out_cmp/noise.json "len(j['comparison'])")" = 8 ] || fail "eight solvers"
[ "$(json out_cmp/noise.json "j['comparison'][2]['rm_average_percent'][0] < j['comparison'][0]['rm_average_percent'][0]")" = True ] \
  || fail "sensitivity not better than linear"
echo "solve_and_compare: ok"
