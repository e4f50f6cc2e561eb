# The blind structure suites (validation/blind_structures): the independent
# plane- and space-frame codes against closed forms, then a small shear-building suite end
# to end (cases, truths kept apart, diagnoses, scores, summary, plot).
source "$(dirname "$0")/lib.sh"
PY=""
for p in python3 /usr/bin/python3; do
  if command -v "$p" > /dev/null && "$p" -c 'import numpy, scipy' 2> /dev/null; then PY="$p"; break; fi
done
[ -n "$PY" ] || fail "no python3 with numpy and scipy (scripts/setup.sh installs python3-numpy, python3-scipy)"
SUITE="$ROOT/validation/blind_structures"
(cd "$SUITE" && "$PY" -B -m unittest -q test_frame2d test_frame3d test_jacket3d test_run_suite test_rescore test_paired test_plane_frame_suite test_cantilever_suite test_shear_building_suite 2>&1) || fail "frame2d and frame3d against closed forms, the jacket geometry, run_suite's scoring, rescore's reweighting, paired's sign test, the plane-frame generator's soft foundation, the cantilever generator, the shear-building generator's two losses and its chain's form error"

"$PY" -B "$SUITE/run_suite.py" --suite shear_building --cases 8 --seed 7 --threads 2 \
  --femup "$FEMUP" -o blind > blind.txt 2> blind.err || { cat blind.err; fail "the suite did not run"; }
grep -q "top-1 kind, all" blind.txt || fail "no summary table"
[ "$(ls blind/cases/*.yaml | wc -l)" = 8 ] || fail "8 study files"
[ "$(ls blind/truth/*.json | wc -l)" = 8 ] || fail "8 truths"
[ "$(wc -l < blind/results.jsonl)" = 8 ] || fail "8 scored cases"
# Rescoring the runs as they were decided gives the scores back.
"$PY" -B "$SUITE/rescore.py" blind --check | grep -q "8 cases as in results.jsonl" \
  || fail "rescore --check does not reproduce results.jsonl"
"$PY" -B "$SUITE/rescore.py" blind --gap-threshold 0 | grep -q "top-1 kind, all" \
  || fail "rescore --gap-threshold 0: no summary table"
# A run compared with itself case by case: every case in both, none changed.
"$PY" -B "$SUITE/paired.py" blind blind > paired.txt || fail "paired.py did not run"
grep -q "^8 cases in both runs" paired.txt && grep -q "Verdict kind changed in 0 cases" paired.txt \
  || fail "paired.py on one run twice: $(cat paired.txt)"
# A stopped run (no results.jsonl; one case's diagnosis missing) is scored from
# its diagnoses, on the cases both runs have.
rm -rf stopped && mkdir stopped && cp -r blind/truth blind/runs stopped/
rm -r stopped/runs/shear_building_007
"$PY" -B "$SUITE/paired.py" blind stopped > paired_stopped.txt || fail "paired.py on a stopped run"
grep -q "^7 cases in both runs (1 in A only" paired_stopped.txt \
  && grep -q "Verdict kind changed in 0 cases" paired_stopped.txt \
  || fail "paired.py on a stopped run: $(cat paired_stopped.txt)"
# The study files give nothing of the truth away.
! grep -qiE "stiffness_loss|attached_mass|support_flex|material_scal|damage|storey [0-9]" blind/cases/*.yaml \
  || fail "a study file names its effect"
[ "$(json blind/summary.json 'j["cases"]')" = 8 ] || fail "summary: cases"
json blind/summary.json '0 <= j["top1_kind"] <= 1 and 0 <= j["bic_top1_kind"] <= 1 and sum(b["cases"] for b in j["reliability_class"]) == 8' \
  | grep -q True || fail "summary: figures out of range"
if command -v gnuplot > /dev/null; then [ -s blind/reliability.png ] || fail "reliability.png"; fi

# The plane-frame suite (femup's plane_frame model, frame2d's Timoshenko truth
# with semi-rigid joints, partial damage, masses between nodes), 3 cases, with a
# stated model error, the frames on base springs (soft foundations among the
# effects).
"$PY" -B "$SUITE/run_suite.py" --suite plane_frame --cases 3 --seed 3 --threads 2 \
  --stated-model-error 0.01 --foundation springs --femup "$FEMUP" -o frames > frames.txt \
  2> frames.err || { cat frames.err; fail "the plane_frame suite did not run"; }
[ "$(wc -l < frames/results.jsonl)" = 3 ] || fail "3 scored frame cases"
grep -q "type: plane_frame" frames/cases/plane_frame_000.yaml || fail "a plane_frame study"
grep -q "  base: {rotation: " frames/cases/plane_frame_000.yaml || fail "base springs in the model"
json frames/summary.json 'j["stated_model_error"] == 0.01 and j["foundation"] == "springs"' \
  | grep -q True || fail "stated model error, foundation"

# The jacket suite (femup's space_frame, jacket3d's Timoshenko truth in water:
# marine growth, one damaged brace, deck equipment, E, a softer foundation), its
# generator's checks and 3 cases on springs end to end.
(cd "$SUITE" && "$PY" -B -m unittest -q test_jacket_suite 2>&1) || fail "the jacket suite's generator"
"$PY" -B "$SUITE/run_suite.py" --suite jacket --cases 3 --seed 3 --threads 2 \
  --foundation springs --femup "$FEMUP" -o jackets > jackets.txt 2> jackets.err \
  || { cat jackets.err; fail "the jacket suite did not run"; }
[ "$(wc -l < jackets/results.jsonl)" = 3 ] || fail "3 scored jacket cases"
grep -q "type: space_frame" jackets/cases/jacket_000.yaml || fail "a space_frame study"
grep -q "  base: {horizontal: " jackets/cases/jacket_000.yaml || fail "springs under the legs"
! grep -qiE "growth|brace_|deck|damage|soft|stiffness_loss|attached_mass" jackets/cases/*.yaml \
  || fail "a jacket study names its effect"

# femup's jacket on springs under its legs against the numpy jacket of the
# same formulation (jacket3d.py, written apart): the same frequencies to 1e-8.
sed 's/^  horizontals: {diameter: 0.6, wall: 0.015}$/&\n  base: {horizontal: 1.0e+8, vertical: 5.0e+8, rocking: 2.0e+9}/' \
  "$ROOT/examples/diagnosis/jacket.yaml" > jacket_on_springs.yaml
grep -q "  base: {horizontal" jacket_on_springs.yaml || fail "the base-spring study"
"$PY" -B "$SUITE/compare_jacket3d.py" --study jacket_on_springs.yaml --femup "$FEMUP" \
  --modes 6 --check 1e-8 > jacket3d.txt 2>&1 || { cat jacket3d.txt; fail "femup's jacket on springs against jacket3d"; }

# Bad arguments: a clear message, nothing run.
if "$PY" -B "$SUITE/run_suite.py" --cases 0 --femup "$FEMUP" -o bad > /dev/null 2> bad.err; then
  fail "--cases 0 accepted"
fi
grep -q "cases must be at least 1" bad.err || fail "--cases 0 message"
if "$PY" -B "$SUITE/run_suite.py" --cases 2 --femup /nonexistent/femup -o bad > /dev/null 2> bad.err; then
  fail "a missing femup accepted"
fi
grep -q "/nonexistent/femup: not an executable" bad.err || fail "missing femup message"
if "$PY" -B "$SUITE/run_suite.py" --suite shear_building --foundation springs --cases 2 \
    --femup "$FEMUP" -o bad > /dev/null 2> bad.err; then
  fail "--foundation springs accepted on shear buildings"
fi
grep -q "only the plane_frame and jacket suites have column bases" bad.err || fail "--foundation message"
[ ! -e bad ] || fail "output written for bad arguments"
echo "blind_structures: ok"
