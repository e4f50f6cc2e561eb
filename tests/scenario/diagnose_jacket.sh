#!/usr/bin/env bash
# femup diagnose on a jacket (model.type space_frame, examples/diagnosis/jacket.yaml):
# the model is Euler-Bernoulli with 2 elements per member, the "measured" modes
# come from the generator's Timoshenko elements, 4 per member, with the braces
# of level 2 softened by 40 %. The verdict names that brace group, tried with
# the 12 of the 72 members and their 144 halves a linearised screen ranks
# best, each on its own, the others ranked at their screen's step (a note
# says so); attached masses
# are tried at the four top joints and between them on the top horizontals;
# support flexibility is tried at the clamped feet (springs released there).
source "$(dirname "$0")/lib.sh"
"$FEMUP" diagnose "$ROOT/examples/diagnosis/jacket.yaml" -o out --no-plots > stdout.txt
grep -q "space_frame model" stdout.txt || fail "report lacks the model type"
grep -q "verdict: stiffness_loss at element l2:braces1" stdout.txt \
  || fail "verdict: $(grep verdict stdout.txt)"
[ "$(json out/diagnosis.json "j['model_type']")" = space_frame ] || fail "model_type"
[ "$(json out/diagnosis.json "j['verdict']['region']")" = "element l2:braces1" ] || fail "region"
[ "$(json out/diagnosis.json "j['verdict']['probability'] > 0.9")" = True ] || fail "probability"
[ "$(json out/diagnosis.json "sorted(c['region'] for c in j['classes'] if c['kind']=='attached_mass' and c['region'].startswith('node'))")" \
  = "['node n10', 'node n11', 'node n12', 'node n9']" ] || fail "attached-mass candidates"
[ "$(json out/diagnosis.json "sum(c['kind']=='attached_mass' and not c['region'].startswith('node') for c in j['classes'])")" \
  = 8 ] || fail "attached masses between the top joints: not the 8 segments of the top horizontals"
[ "$(json out/diagnosis.json "sum(c['region'].startswith('member ') and c['fitted'] for c in j['classes'])")" \
  = 12 ] || fail "stiffness loss not fitted on the 12 members the screen ranks best"
[ "$(json out/diagnosis.json "sum(c['region'].startswith('member ') and not c['fitted'] for c in j['classes'])")" \
  = 204 ] || fail "the 204 other members and member halves not ranked on their screen's step"
grep -q "note: stiffness_loss was fitted on 12 of its 216 places on single members" stdout.txt \
  || fail "no note of the members' screen"
[ "$(json out/diagnosis.json "any(c['kind']=='added_mass' for c in j['classes'])")" = True ] \
  || fail "added mass on the wet groups not tried"
[ "$(json out/diagnosis.json "any(c['kind']=='support_flexibility' and c['region']=='supports' for c in j['classes'])")" \
  = True ] || fail "support flexibility at the clamped feet not tried"
echo "diagnose_jacket: ok"
