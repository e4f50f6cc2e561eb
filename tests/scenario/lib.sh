# Shared helpers for scenario tests (sourced; not a test itself).
set -euo pipefail
FEMUP="$1"; ROOT="$2"; WORK="$3"
rm -rf "$WORK"; mkdir -p "$WORK"; cd "$WORK"
fail() { echo "FAIL: $*" >&2; exit 1; }
# json FILE EXPR: evaluates a Python expression on the parsed JSON `j`.
json() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"; }
