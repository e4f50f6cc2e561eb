#!/usr/bin/env bash
# femup run on a jacket-like space frame (10,560 DOF): the linear method weighted
# by all FEM modes through M^-1 without the eigenbasis; the preset factors come
# back; shapes are drawn along the corner leg. Bad space-frame input is named.
source "$(dirname "$0")/lib.sh"
"$FEMUP" run "$ROOT/examples/space_frame/jacket.yaml" -o out > stdout.txt
grep -q "weighted by all 10560 FEM modes" stdout.txt || fail "report lacks the M^-1 weighting"
grep -q "105600 equations compressed to 86 x 86" stdout.txt || fail "report lacks the system size"
for f in result.json factors.png frequencies.png shapes_air.png shapes_water.png added_mass.mtx; do
  [ -s "out/$f" ] || fail "missing out/$f"
done
[ "$(json out/result.json "j['model']['dofs']")" = 10560 ] || fail "dofs"
[ "$(json out/result.json "j['system']['weighted_by_inverse_mass']")" = True ] || fail "flag"
[ "$(json out/result.json "max(abs(p['estimate']-p['preset']) for p in j['parameters'])<1e-8")" = True ] \
  || fail "factors not recovered"
[ "$(json out/result.json "[round(p['estimate'],6) for p in j['parameters'] if p['name']=='stiffness[l2:legs1]']")" = "[-0.3]" ] \
  || fail "the stiffness loss"
# The shape plot draws the corner leg: one point per node of that leg (10
# levels x 4 elements), bottom to top.
[ "$(grep -cv '^#\|^$' out/shapes_water.dat)" -ge 40 ] || fail "shape plot data"

# Bad input: a family layout on a generated frame; a summed form too large for
# the dense eigenbasis; an invalid frame size.
sed 's/^parameters:$/parameters:\n  mass: single/' "$ROOT/examples/space_frame/jacket.yaml" > families.yaml
if "$FEMUP" run families.yaml -o out2 > /dev/null 2> err.txt; then fail "families accepted"; fi
grep -q "parameters.mass" err.txt || fail "families: $(cat err.txt)"
sed 's/^solver: .*/system: {form: summed}\nsolver: {method: linear, name: lstsq}/' \
  "$ROOT/examples/space_frame/jacket.yaml" > summed.yaml
if "$FEMUP" run summed.yaml -o out3 > /dev/null 2> err.txt; then fail "summed accepted"; fi
grep -q "system.form" err.txt || fail "summed: $(cat err.txt)"
[ ! -e out3/result.json ] || fail "half-written output"
sed 's/^  bays_x: 2$/  bays_x: 0/' "$ROOT/examples/space_frame/jacket.yaml" > zero.yaml
if "$FEMUP" run zero.yaml -o out4 > /dev/null 2> err.txt; then fail "bays_x 0 accepted"; fi
grep -q "model.bays_x" err.txt || fail "bays_x: $(cat err.txt)"
echo "run_space_frame: ok"
