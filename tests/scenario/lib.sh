# Shared helpers for scenario tests (sourced; not a test itself).
set -euo pipefail
FEMUP="$1"; ROOT="$2"; WORK="$3"
rm -rf "$WORK"; mkdir -p "$WORK"; cd "$WORK"
fail() { echo "FAIL: $*" >&2; exit 1; }
# sanitized: true in the sanitizer build's run (tests/CMakeLists.txt sets
# FEMUP_SANITIZED), where a scenario may leave out a section of minutes whose
# paths a named unit test runs under the sanitizers as well.
sanitized() { [ -n "${FEMUP_SANITIZED:-}" ]; }
# json FILE EXPR: evaluates a Python expression on the parsed JSON `j`.
json() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"; }
# small_problem [HEADER]: A.csv (6 x 3, under the header line HEADER when given)
# and b.csv of a problem with known x = (1, -2, 0.5) and exact data.
small_problem() {
  {
    if [ $# -gt 0 ]; then echo "$1"; fi
    printf '1,0,0\n0,1,0\n0,0,1\n1,1,0\n0,1,1\n1,0,1\n'
  } > A.csv
  printf '1\n-2\n0.5\n-1\n-1.5\n1.5\n' > b.csv
}
