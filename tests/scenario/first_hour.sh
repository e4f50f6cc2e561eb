#!/usr/bin/env bash
# What a first user trips on (issue 25): -o with missing parent folders (and
# nothing left behind when the job fails), one-sided bounds written as
# -inf/inf by numpy or MATLAB, a dry structure with the default added mass.
source "$(dirname "$0")/lib.sh"
# The version names the BLAS femup runs on and its one thread per call.
"$FEMUP" --version > version.txt
grep -q "^femup [0-9]" version.txt || fail "no version: $(cat version.txt)"
grep -q "^BLAS: " version.txt || fail "no BLAS named: $(cat version.txt)"
# On a processor with AVX2 and FMA, OpenBLAS's kernels are at least Haswell's:
# femup starts again with them where Debian's OpenBLAS does not know the
# processor (it would take its SSE3 Prescott kernels); a core the user sets stays.
if grep -q "^BLAS: OpenBLAS" version.txt && grep -qw avx2 /proc/cpuinfo &&
   grep -qw fma /proc/cpuinfo; then
  grep -qw Prescott version.txt && fail "SSE3 kernels on an AVX2 processor: $(cat version.txt)"
  OPENBLAS_CORETYPE=Prescott "$FEMUP" --version > version_user.txt
  grep -qw Prescott version_user.txt || fail "the user's core not kept: $(cat version_user.txt)"
  grep -q "set OPENBLAS_CORETYPE=" version_user.txt ||
    fail "no hint for the older kernels: $(cat version_user.txt)"
fi

# -o a/b/c: the parents are created; the job's files land in c.
"$FEMUP" run "$ROOT/examples/paper_chain_masses_1-3_wet.yaml" -o deep/er/out --no-plots -q \
  || fail "run -o deep/er/out"
[ -s deep/er/out/result.json ] || fail "result.json not in deep/er/out"
[ -z "$(find deep -name '.femup-staging-*')" ] || fail "staging folder left behind"
# A job that fails leaves none of the folders it created.
printf 'name: broken\nmodel: {type: chain, masses: [1], springs: [-1]}\n' > broken.yaml
"$FEMUP" run broken.yaml -o new/parent/out -q 2> err_broken.txt && fail "broken study accepted"
[ -e new ] && fail "a failed run left folders behind: $(find new)"
# A parent that is a file: a clear error naming the path.
touch afile
"$FEMUP" run "$ROOT/examples/paper_chain_masses_1-3_wet.yaml" -o afile/out -q 2> err_file.txt \
  && fail "-o under a file accepted"
grep -q "afile/out" err_file.txt || fail "message does not name the folder: $(cat err_file.txt)"

# Non-negative least squares from files: lower 0, upper inf (numpy's spelling),
# and mixed spellings (MATLAB's Inf, -Infinity); NaN refused with file and line.
small_problem
printf '0\n0\n0\n' > lo.csv
printf 'inf\ninf\ninf\n' > up.csv
"$FEMUP" solve --A A.csv --b b.csv --lower lo.csv --upper up.csv --solver bvls -o nnls -q \
  || fail "solve with upper = inf"
[ "$(json nnls/solution.json "min(j['x']) >= 0 and j['x'][1] == 0")" = True ] \
  || fail "non-negativity not held: $(json nnls/solution.json "j['x']")"
printf -- '-Infinity\n0\n-inf\n' > lo2.csv
printf 'Inf\n+inf\n1e300\n' > up2.csv
"$FEMUP" solve --A A.csv --b b.csv --lower lo2.csv --upper up2.csv --solver bvls -o mixed -q \
  || fail "solve with mixed infinite bounds"
# With x2 held at 0, the normal equations 3 x1 + x3 = 1.5, x1 + 3 x3 = 0.5 give
# x = (0.5, 0, 0).
[ "$(json mixed/solution.json "abs(j['x'][0] - 0.5) < 1e-9 and j['x'][1] == 0 and abs(j['x'][2]) < 1e-9")" = True ] \
  || fail "mixed bounds: $(json mixed/solution.json "j['x']")"
printf '0\nnan\n0\n' > lonan.csv
"$FEMUP" solve --A A.csv --b b.csv --lower lonan.csv -o nan -q 2> err_nan.txt \
  && fail "NaN bound accepted"
grep -q "lonan.csv:2" err_nan.txt || fail "NaN message: $(cat err_nan.txt)"
grep -q "NaN" err_nan.txt || fail "NaN message: $(cat err_nan.txt)"
[ -e nan ] && fail "output left behind"
printf 'inf\n0\n0\n' > loinf.csv
"$FEMUP" solve --A A.csv --b b.csv --lower loinf.csv -o linf -q 2> err_linf.txt \
  && fail "lower bound +inf accepted"
grep -q "lower bound of .* is +inf" err_linf.txt || fail "+inf message: $(cat err_linf.txt)"
# Infinity in A or b is still refused.
printf '1\ninf\n0.5\n-1\n-1.5\n1.5\n' > binf.csv
"$FEMUP" solve --A A.csv --b binf.csv -o binf -q 2> err_binf.txt && fail "b = inf accepted"
grep -q "binf.csv:2" err_binf.txt || fail "b message: $(cat err_binf.txt)"

# A dry structure with parameters that do not mention added mass: none, and no
# added-mass matrix among the outputs.
cat > dry.yaml <<'YAML'
name: dry_chain
model:
  type: chain
  masses: [50, 50, 50]
  springs: [2.9e7, 2.9e7, 2.9e7]
parameters:
  mass: per_element
  stiffness: per_element
  fix: {"mass[1]": 0.01}
truth: {"mass[1]": 0.01, "stiffness[2]": -0.05}
measurements:
  - {state: air, simulate_modes: 3}
YAML
"$FEMUP" run dry.yaml -o dry -q --no-plots 2> err_dry.txt || fail "dry study: $(cat err_dry.txt)"
[ -e dry/added_mass.mtx ] && fail "a dry study wrote added_mass.mtx"
[ "$(json dry/result.json "'added_mass.mtx' in j['files']")" = False ] || fail "files list"
[ "$(json dry/result.json "all(p['kind'] != 'added_mass' for p in j['parameters'])")" = True ] \
  || fail "added-mass parameters in a dry study"
[ -s dry/updated_stiffness.mtx ] || fail "updated_stiffness.mtx"
# Asked for explicitly with nothing wet, added mass is still an error naming the field.
sed 's/  stiffness: per_element/  stiffness: per_element\n  added_mass: single/' dry.yaml > dry_am.yaml
"$FEMUP" run dry_am.yaml -o dry_am -q 2> err_am.txt && fail "added mass on a dry structure accepted"
grep -q "added_mass" err_am.txt || fail "message: $(cat err_am.txt)"
echo "first_hour: ok"
