#!/usr/bin/env bash
# The README's second command (and CI's): set up, build with warnings as
# errors, run every test; then the same tests under ASan/UBSan; then check the
# formatting of the sources.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
JOBS=$(nproc)

echo "== release build and tests"
cmake -S . -B build-ci -G Ninja -DCMAKE_BUILD_TYPE=Release -DFEMUP_BUILD_BENCHMARKS=ON \
  -DCMAKE_CXX_FLAGS="-Werror" > /dev/null
cmake --build build-ci -j "$JOBS"
(cd build-ci && ctest --output-on-failure -j "$JOBS")

echo "== sanitizer build (ASan + UBSan) and tests"
# -O1 with line tables only (-g1: file and line in every sanitizer report, no
# variable info): half the compile time of RelWithDebInfo's -O2 -g, which the
# build type would otherwise append after any -O1 in CMAKE_CXX_FLAGS. Without
# NDEBUG, so that Eigen's own checks (an index out of range, sizes that do not
# match in a product or an assignment) fail here too: ASan cannot see an index
# that stays inside a matrix's storage but outside its row or column.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFEMUP_SANITIZE=ON \
  -DFEMUP_BUILD_BENCHMARKS=OFF -DCMAKE_CXX_FLAGS="" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" > /dev/null
cmake --build build-asan -j "$JOBS"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure -j "$JOBS")

echo "== clang-format check"
files=$(git ls-files '*.cc' '*.h' 2>/dev/null || find lib problems solvers studies app tests bench -name '*.cc' -o -name '*.h')
clang-format --dry-run -Werror $files
echo "all checks passed"
