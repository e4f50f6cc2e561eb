#!/usr/bin/env bash
# femup noise: Rm statistics per factor and level, figures 4 and 5; the same
# numbers with any --threads; no progress bar when stderr is not a terminal.
source "$(dirname "$0")/lib.sh"
"$FEMUP" noise "$ROOT/examples/paper_chain_noise.yaml" -o out -q
[ -s out/noise.json ] && [ -s out/rm_vs_level.png ] && [ -s out/factors_at_level.png ] \
  || fail "outputs missing"
[ "$(json out/noise.json "len(j['levels'])")" = 11 ] || fail "levels"
[ "$(json out/noise.json "j['rm_average_percent'][0] < 1e-8")" = True ] || fail "Rm at 0 %"
[ "$(json out/noise.json "all(a < b for a, b in zip(j['rm_average_percent'][:5], j['rm_average_percent'][1:6]))")" = True ] \
  || fail "Rm does not grow with the level"

# --threads: a shorter study, run on 1 and on 2 threads, identical numbers.
sed 's/draws: 1000/draws: 60/' "$ROOT/examples/paper_chain_noise.yaml" > short.yaml
"$FEMUP" noise short.yaml -o one --threads 1 --no-plots -q
"$FEMUP" noise short.yaml -o two --threads 2 --no-plots > two.stdout 2> two.stderr
strip() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); [c.pop('seconds') for c in j['comparison']]; print(json.dumps(j, sort_keys=True))" "$1"; }
[ "$(strip one/noise.json)" = "$(strip two/noise.json)" ] || fail "--threads 1 and 2 differ"
[ "$(json two/noise.json "j['noise_model']['draws_per_level']")" = 60 ] || fail "short study"
[ "$(json two/noise.json "'Philox4x64' in j['noise_model']['generator']")" = True ] \
  || fail "the generator is not named"
grep -q "mean Rm" two.stdout || fail "no report on stdout"
[ ! -s two.stderr ] || fail "stderr is not a terminal, yet got: $(cat -A two.stderr | head -3)"

# Bad thread counts: exit 1, the option named, no output folder.
set +e
"$FEMUP" noise short.yaml -o zero --threads 0 -q 2> zero.stderr
code=$?
set -e
[ "$code" = 1 ] || fail "--threads 0 exited with $code"
grep -q -- "--threads" zero.stderr || fail "error does not name --threads: $(cat zero.stderr)"
[ ! -e zero ] || fail "output written despite the error"
echo "noise_study: ok"
