#!/usr/bin/env bash
# pip_install_test.sh PYTHON WORKDIR BUILDDIR: the README's install of the
# Python module into a clean venv. Makes a venv in WORKDIR with
# --system-site-packages (Debian's numpy, scipy, setuptools, wheel and
# pybind11; no package index is used), runs `pip install --no-build-isolation .`
# from the project folder with its build folder at BUILDDIR (one level below
# the project folder, so that ccache finds the objects the README's build
# compiled), then imports femup from outside the source tree and runs the
# paper's chain from a study dict. Prints the time of each step.
set -euo pipefail
python="$1"; work="$2"; build="$3"
root="$(cd "$(dirname "$0")/../.." && pwd)"
# A clean build each time (objects come from ccache): what a new user's install does.
rm -rf "$work" "$build"; mkdir -p "$work"
start=$(date +%s)
"$python" -m venv --system-site-packages "$work/venv"
export FEMUP_PIP_BUILD_DIR="$build" PIP_NO_INDEX=1 PIP_DISABLE_PIP_VERSION_CHECK=1
(cd "$root" && "$work/venv/bin/pip" install --no-build-isolation -q .)
built=$(date +%s)
echo "pip install: $((built - start)) s"
cd "$work"
"$work/venv/bin/python" - <<'PY'
import femup, numpy as np
assert "venv" in femup.__file__, femup.__file__
study = femup.study_from_dict({
    "model": {"type": "chain", "masses": [50] * 5, "springs": [2.9e7] * 5, "wet": [1, 2, 3]},
    "parameters": {"fix": {"mass[4]": 0.0058}},
    "truth": {"mass[1]": -0.0087, "mass[2]": -0.0333, "mass[3]": 0.0025, "mass[4]": 0.0058,
              "mass[5]": -0.0230, "stiffness[1]": 0.0119, "stiffness[2]": 0.0119,
              "stiffness[3]": -0.0004, "stiffness[4]": 0.0033, "stiffness[5]": 0.0017,
              "added_mass[1]": 0.15, "added_mass[2]": 0.25, "added_mass[3]": 0.20},
    "measurements": [{"state": "air", "immersion": "dry", "simulate_modes": 2},
                     {"state": "water", "immersion": "wet", "simulate_modes": 2}],
    "system": {"form": "summed"},
})
result = femup.run_update(study)
worst = max(abs(f.error) for f in result.factors)
assert result.solution.summary.status == "solved", result.solution.summary
assert worst < 1e-10, worst
print(f"installed femup from {femup.__file__}: 13 factors, largest error {worst:.1e}")
PY
echo "total: $(( $(date +%s) - start )) s"
