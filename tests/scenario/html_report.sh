#!/usr/bin/env bash
# report.html: every command that writes results writes one self-contained page
# beside its JSON, and headless Chromium renders every bundled example's page
# without a console error, a broken or non-inline image, an empty section, a
# network reference, or a page wider than a laptop screen
# (tests/browser/check_reports.py).
#  1. Every study in examples/ through the command it is made for (run, noise,
#     diagnose, simulate; the paper's experiment: simulate the records, then
#     run Models A-E on them), modes and compare on the paper's chain, solve
#     on the correction system the run wrote, identify on the bundled UFF FRFs,
#     and a two-case benchmark.
#  2. What a page holds: the summary the terminal prints (the factors), every
#     plot, the study file, the files written; with --no-plots, no plot section.
#  3. A failed run writes no report (nothing half-written), and the checker
#     itself fails a broken page.
# Screenshots of the pages are left in screenshots/ of the work folder.
source "$(dirname "$0")/lib.sh"
PY=/usr/bin/python3
CHECK="$ROOT/tests/browser/check_reports.py"
reports=()
make() {  # make OUT COMMAND ARGS...: runs femup COMMAND ARGS -o reports/OUT -q
  local out="reports/$1"; shift
  "$FEMUP" "$@" -o "$out" -q > /dev/null || fail "femup $* failed"
  [ -s "$out/report.html" ] || fail "femup $*: no report.html in $out"
  reports+=("$out/report.html")
}
for f in "$ROOT"/examples/*.yaml "$ROOT"/examples/*/*.yaml; do
  case "$f" in */cantilever_experiment/*) continue ;; esac
  name=$(basename "$(dirname "$f")")_$(basename "$f" .yaml)
  if grep -q '^noise_study:' "$f"; then make "$name" noise "$f" --threads 2
  elif [[ "$f" == */diagnosis/* ]]; then make "$name" diagnose "$f"
  elif grep -q '^measurements:' "$f"; then make "$name" run "$f"
  else make "$name" simulate "$f"
  fi
done
cp -r "$ROOT/examples/cantilever_experiment" experiment
"$FEMUP" simulate experiment/real_beam.yaml -o experiment/data -q || fail "simulate"
reports+=(experiment/data/report.html)
for m in a b c d e; do make "experiment_model_$m" run "experiment/model_$m.yaml"; done
chain="$ROOT/examples/paper_chain_masses_1-3_wet.yaml"
make modes modes "$chain"
make compare compare "$chain" "$ROOT/examples/paper_chain_masses_1-2_wet.yaml"
make solve solve --A "reports/examples_paper_chain_masses_1-3_wet/system_Z.mtx" \
  --b "reports/examples_paper_chain_masses_1-3_wet/system_F.mtx" --solver tikhonov
make identify identify "$ROOT/examples/data/pyuff_beam_frf.uff"
make benchmark benchmark --suite single --cases 2 --threads 2

# 2. What the paper's run page holds.
page=reports/examples_paper_chain_masses_1-3_wet/report.html
for want in '<h1>femup run: paper_chain_masses_1-3_wet</h1>' 'id="summary"' \
    'added_mass[3]' 'id="plots"' 'data:image/png;base64,' 'correction factors' \
    'id="inputs"' 'wet: [1, 2, 3]' 'id="files"' 'href="result.json"' \
    'femup run '; do
  grep -qF -- "$want" "$page" || fail "the run's page lacks: $want"
done
[ "$(grep -c '<figure>' "$page")" -eq 4 ] || fail "the run's page should have 4 plots"
"$FEMUP" run "$chain" -o bare --no-plots -q || fail "run --no-plots"
grep -q 'id="plots"' bare/report.html && fail "--no-plots page has a plot section"
grep -q 'id="summary"' bare/report.html || fail "--no-plots page lacks its summary"
reports+=(bare/report.html)

# 3. Nothing written by a failed run; the checker fails a broken page.
printf 'name: broken\nmodel: {type: chain, masses: [1, 1], springs: [1]}\n' > broken.yaml
"$FEMUP" run broken.yaml -o failed -q 2> /dev/null && fail "a broken study ran"
[ ! -e failed ] || fail "a failed run left $(ls failed) behind"
cat > broken.html <<'HTML'
<!DOCTYPE html><html><head><title>x</title></head><body><h1>x</h1>
<section><h2>Plots</h2></section><img alt="gone" src="gone.png">
<script>console.error("broken")</script></body></html>
HTML
out=$($PY "$CHECK" broken.html) && fail "the checker passed a broken page"
for want in "section 'Plots' is empty" "image 'gone' did not load" "is not inline" \
    'console:'; do
  grep -qF -- "$want" <<< "$out" || fail "the checker missed: $want"
done

# 1. Every page in the browser.
echo "rendering ${#reports[@]} reports in Chromium"
$PY "$CHECK" --screenshot-dir screenshots "${reports[@]}" || fail "a report is broken"
