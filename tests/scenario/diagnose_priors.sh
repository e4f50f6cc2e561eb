#!/usr/bin/env bash
# Stated engineering priors in femup diagnose (diagnosis.priors, diagnosis.weights;
# docs/diagnosis.md, "Stated priors"):
#  1. examples/diagnosis/portal_frame_priors.yaml (the portal frame's two lowest
#     modes; the machine's place and mass range and E within 5 % stated): exit
#     0, the verdict attached_mass at node n7 with P > 0.99 and a mass inside
#     the stated 1.5-2.5 t, diagnosis.json echoing the stated priors and the
#     report naming them; the same study without its priors cannot separate n7
#     from the first-floor joints (P < 0.5).
#  2. Bad priors: lower > upper, a region that names no node of the model, a
#     family not among the candidates, a quantity the family lacks and a
#     non-positive standard deviation each exit 1 with a message naming the
#     study file and the field, and leave no output folder behind.
source "$(dirname "$0")/lib.sh"

example="$ROOT/examples/diagnosis/portal_frame_priors.yaml"

# 1. With and without the stated priors.
"$FEMUP" diagnose "$example" -o stated --no-plots > stated.txt \
  || fail "diagnose exit $?: $(cat stated.txt)"
[ "$(json stated/diagnosis.json "(j['verdict']['kind'], j['verdict']['region'])")" \
  = "('attached_mass', 'node n7')" ] || fail "verdict: $(json stated/diagnosis.json "j['verdict']")"
# Bagged 0.991 (the Laplace posterior alone: 1.00).
[ "$(json stated/diagnosis.json "j['verdict']['probability'] > 0.97 and j['classes'][0]['laplace_probability'] > 0.99")" = True ] \
  || fail "probability: $(json stated/diagnosis.json "j['verdict']")"
[ "$(json stated/diagnosis.json "1500 <= j['classes'][0]['magnitudes'][0]['value'] <= 2500")" \
  = True ] || fail "mass: $(json stated/diagnosis.json "j['classes'][0]['magnitudes']")"
[ "$(json stated/diagnosis.json "j['stated_priors']['families']['attached_mass']['regions']")" \
  = "['n7']" ] || fail "stated_priors: $(json stated/diagnosis.json "j.get('stated_priors')")"
[ "$(json stated/diagnosis.json "j['stated_priors']['families']['material_scaling']['factor']")" \
  = "{'normal': [1.0, 0.05]}" ] || fail "stated_priors: $(json stated/diagnosis.json "j['stated_priors']")"
grep -q "stated priors: attached_mass mass_kg \[1500, 2500\] at n7" stated.txt \
  || fail "report: $(cat stated.txt)"
sed -e '/^  priors:/,$d' "$example" > plain.yaml
"$FEMUP" diagnose plain.yaml -o plain --no-plots > plain.txt \
  || fail "diagnose plain exit $?: $(cat plain.txt)"
[ "$(json plain/diagnosis.json "j['verdict']['probability'] < 0.5 and j['verdict']['kind'] == 'attached_mass'")" \
  = True ] || fail "plain verdict: $(json plain/diagnosis.json "j['verdict']")"
grep -q "stated priors" plain.txt && fail "plain report names priors: $(cat plain.txt)"

# 2. Bad priors: nothing is written.
# refused NAME PRIORS NEEDLE...: the example with its priors section replaced by
# PRIORS exits 1, its message holds the file name and every NEEDLE, and no
# output folder is left behind.
refused() {
  local name="$1" priors="$2" rc
  shift 2
  { sed -e '/^  priors:/,$d' "$example"; printf '%s\n' "$priors"; } > "$name.yaml"
  set +e
  "$FEMUP" diagnose "$name.yaml" -o "out_$name" > /dev/null 2> "err_$name.txt"
  rc=$?
  set -e
  [ "$rc" = 1 ] || fail "$name: exit $rc"
  grep -q -- "$name.yaml" "err_$name.txt" || fail "$name: no file in $(cat "err_$name.txt")"
  for needle in "$@"; do
    grep -q -F -- "$needle" "err_$name.txt" || fail "$name: message: $(cat "err_$name.txt")"
  done
  [ ! -e "out_$name" ] || fail "$name: output folder written"
}
refused lower_above_upper "  priors: {attached_mass: {mass_kg: [2500, 1500]}}" \
  "diagnosis.priors.attached_mass.mass_kg: lower 2500 > upper 1500"
refused no_such_node "  priors: {attached_mass: {regions: [n7, n99]}}" \
  "diagnosis.priors.attached_mass.regions[2]" "'n99' names no element"
{ sed -e '/^  priors:/,$d' "$example"; echo "  candidates: [attached_mass]"; } > few.yaml
set +e
"$FEMUP" diagnose few.yaml -o out_few > /dev/null 2>&1
rc=$?
set -e
[ "$rc" = 0 ] || fail "few candidates without priors: exit $rc"
refused not_a_candidate "  candidates: [attached_mass]
  priors: {stiffness_loss: {loss: [0.05, 0.5]}}" \
  "diagnosis.priors.stiffness_loss" "not among diagnosis.candidates"
refused unknown_quantity "  priors: {material_scaling: {e_modulus: [200e9, 220e9]}}" \
  "diagnosis.priors.material_scaling.e_modulus: unknown key" "factor"
refused zero_std "  priors: {material_scaling: {factor: {normal: [1.0, 0]}}}" \
  "diagnosis.priors.material_scaling.factor.normal[2]" "positive standard deviation"
refused bad_weight "  weights: {none: -1}" "diagnosis.weights.none" "positive"
echo "diagnose_priors: ok"
