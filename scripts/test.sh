#!/usr/bin/env bash
# The README's second command (and CI's): set up, build (Release, in the same
# build/ folder and with the same flags as the first command, so that one build
# serves both; a compiler warning fails the run), run every test; then the same
# tests under ASan/UBSan; then fuzz each parser briefly; then check the
# formatting of the sources. Prints each stage's time.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/stages.sh
JOBS=$(nproc)

stage "set-up"
bash scripts/setup.sh

stage "release build"
bash scripts/build.sh build -DFEMUP_BUILD_TESTS=ON -DFEMUP_BUILD_BENCHMARKS=ON \
  -DFEMUP_BUILD_VALIDATION=ON

stage "release tests"
(cd build && ctest --output-on-failure -j "$JOBS")

stage "sanitizer build (ASan + UBSan)"
# -O1 with line tables only (-g1: file and line in every sanitizer report, no
# variable info): half the compile time of RelWithDebInfo's -O2 -g, which the
# build type would otherwise append after any -O1 in CMAKE_CXX_FLAGS. Without
# NDEBUG, so that Eigen's own checks (an index out of range, sizes that do not
# match in a product or an assignment) fail here too: ASan cannot see an index
# that stays inside a matrix's storage but outside its row or column.
# Without femup_validate: its cases are the solvers' and the certified
# datasets', which their unit tests (nist_strd_test.cc, lstsq_test.cc,
# regularisation_test.cc, ...) run under the sanitizers; its scenario
# (validate_tables, 77 s there in session 51) runs in the Release stage.
bash scripts/build.sh build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFEMUP_SANITIZE=ON \
  -DFEMUP_BUILD_BENCHMARKS=OFF -DFEMUP_BUILD_VALIDATION=OFF \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1"

stage "sanitizer tests"
# Less the tests labelled long (tests/test_properties.cmake: minutes each under
# the sanitizers, their paths run there by shorter tests); Release ran them.
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure -j "$JOBS" -LE long)

stage "fuzzing (short)"
# Each parser's libFuzzer harness (fuzz/) for 12 s from its seeds, in
# build-fuzz/ (clang, ASan + UBSan); docs/fuzzing.md has the long campaign.
FEMUP_FUZZ_JOBS="$JOBS" bash scripts/fuzz.sh 12

stage "clang-format check"
files=$(git ls-files '*.cc' '*.h' 2>/dev/null || find lib problems solvers studies evaluation app tests bench fuzz -name '*.cc' -o -name '*.h')
clang-format --dry-run -Werror $files
stage_end
echo "all checks passed"
