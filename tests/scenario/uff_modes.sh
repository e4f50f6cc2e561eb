#!/usr/bin/env bash
# Measured mode shapes from UFF files (dataset 55) as a study measurement.
#  1. The "real" beam's modes (femup modes on examples/uff_modes/real_beam.yaml,
#     E 8 % below the drawing's) are written as a UFF file of complex modes
#     with the test geometry (dataset 15) by the example's own Python writer
#     (examples/uff_modes/make_modes_uff.py, independent of femup's writer).
#  2. femup info lists the datasets: nodes, 4 complex modes with the
#     frequencies of modes.json, their damping.
#  3. femup run on the nominal model with modes_file / geometry_file: the
#     single stiffness factor is -0.08 (E x 0.92), the updated frequencies
#     match the measured ones, the sensors are the ten ux DOFs; the same with
#     the bundled examples/uff_modes/air_modes.uff.
#  4. femup identify on the file says it holds mode shapes for modes_file.
#  5. Bad input: no dataset 55, a node nothing maps, a direction the data
#     lack, modes with other node sets, an unknown file kind: exit 1, the
#     message names the file (and line), nothing is written.
source "$(dirname "$0")/lib.sh"
EX="$ROOT/examples/uff_modes"

"$FEMUP" modes "$EX/real_beam.yaml" -n 4 -o real --no-plots -q || fail "modes of the real beam"
python3 "$EX/make_modes_uff.py" real/modes.json air_modes.uff || fail "writing the UFF file"

# 2. femup info, text and JSON.
"$FEMUP" info air_modes.uff > info.txt || fail "info"
grep -q "dataset 15 (line 2): nodes (single precision): 11 (100-110)" info.txt \
  || fail "info nodes: $(cat info.txt)"
[ "$(grep -c 'complex mode (first order)' info.txt)" = 4 ] || fail "info modes: $(cat info.txt)"
grep -q "modes_file" info.txt || fail "info hint"
"$FEMUP" info air_modes.uff --json > info.json || fail "info --json"
[ "$(python3 -c "
import json
i = json.load(open('info.json')); m = json.load(open('real/modes.json'))
s = [d for d in i['datasets'] if d['dataset'] == 55]
print(len(s) == 4 and all(abs(d['frequency_hz'] / f - 1) < 1e-5 for d, f in zip(s, m['frequencies_hz']))
      and abs(s[0]['damping_ratio'] - 0.01) < 1e-5 and s[0]['nodes'] == list(range(100, 111)))
")" = True ] || fail "info json: $(head -c 600 info.json)"

# 3. femup run, on the file written here and on the bundled one.
cp "$EX/model.yaml" model.yaml
check_run() {  # check_run OUT MODES_JSON
  [ "$(json "$1/result.json" "
abs(j['parameters'][0]['estimate'] + 0.08) < 2e-3
and all(abs(e) < 0.05 for e in j['states'][0]['updated_error_percent'])
and len(j['measurements'][0]['uff']['sensors']) == 10
and j['measurements'][0]['uff']['sensors'][0]['dof'] == 'n1:ux'
and j['measurements'][0]['uff']['modes_in_file'] == 4
and [m['mode'] for m in j['measurements'][0]['uff']['modes']] == [1, 2, 3]
and all(m['complex'] for m in j['measurements'][0]['uff']['modes'])
and j['measurements'][0]['uff']['modes'][0]['mpc'] > 0.99999
and 0.99 < j['measurements'][0]['uff']['modes'][1]['mpc'] < 0.9999
and abs(j['measurements'][0]['uff']['modes'][1]['damping_ratio'] - 0.008) < 1e-5
and all(m > 0.999 for m in j['states'][0]['updated_mac'])")" = True ] \
    || fail "run $1: $(head -c 1500 "$1/result.json")"
  python3 -c "
import json, sys
j = json.load(open(sys.argv[1])); m = json.load(open(sys.argv[2]))
assert all(abs(a / b - 1) < 1e-5 for a, b in zip(j['states'][0]['measured_hz'], m['frequencies_hz']))
" "$1/result.json" "$2" || fail "measured frequencies of $1"
}
"$FEMUP" run model.yaml -o out_run -q --no-plots || fail "run"
check_run out_run real/modes.json
"$FEMUP" run "$EX/model.yaml" -o out_example -q --no-plots || fail "run the example"
check_run out_example real/modes.json

# 4. identify on mode shapes.
"$FEMUP" identify air_modes.uff -o out_id 2> id_err.txt && fail "identify accepted mode shapes"
grep -q "holds 4 mode shape(s) (dataset 55)" id_err.txt && grep -q "modes_file" id_err.txt \
  || fail "identify message: $(cat id_err.txt)"

# 5. Bad input.
expect_fail() {  # expect_fail NAME STUDY_TEXT NEEDLE...
  local name=$1 text=$2
  shift 2
  printf '%s\n' "$text" > "$name.yaml"
  "$FEMUP" run "$name.yaml" -o "out_$name" -q 2> "$name.err" && fail "$name accepted"
  for needle in "$@"; do
    grep -qF -- "$needle" "$name.err" || fail "$name: '$needle' not in: $(cat "$name.err")"
  done
  [ ! -e "out_$name" ] || fail "$name: partial output"
}
head -n 14 air_modes.uff > nodes_only.uff   # dataset 15 alone
expect_fail no55 "$(sed 's/air_modes.uff/nodes_only.uff/g' model.yaml)" \
  "nodes_only.uff" "no mode shape (dataset 55)" "1 x dataset 15"
expect_fail unmapped \
  "$(sed -e '/geometry_file/d' -e '/uff_directions/d' -e 's/{"100": skip}/{"100": skip, "101:X": n1:ux}/' model.yaml)" \
  "air_modes.uff: line 29" "node 102 is not mapped"
expect_fail direction \
  "$(sed -e '/geometry_file/d' -e '/uff_directions/d' -e '/expansion/d' -e 's/{"100": skip}/{"101:RZ": n1:rz, "*": skip}/' model.yaml)" \
  "uff_dofs.101:RZ" "direction +RZ is missing" "3 values per node"
python3 "$EX/make_modes_uff.py" real/modes.json holes.uff --drop-node 105 --in-mode 2
expect_fail nodesets "$(sed 's/air_modes.uff/holes.uff/g' model.yaml)" \
  "holes.uff: line" "node 105 is missing" "share one node set"
"$FEMUP" info air_modes.wav 2> info_err.txt && fail "info: unknown kind accepted"
grep -q "air_modes.wav" info_err.txt && grep -q "extension" info_err.txt || fail "info message"
"$FEMUP" info missing.uff 2> info_err2.txt && fail "info: missing file accepted"
grep -q "missing.uff" info_err2.txt || fail "info missing message"
echo "uff_modes: ok"
