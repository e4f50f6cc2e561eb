"""Shared fixtures of the Python module's tests (run by ctest as python_pytest,
with PYTHONPATH at the built module and FEMUP_CLI at the same build's
command line)."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"

# The paper's preset factors (Liu et al. 2014, section 4; the study's `truth`).
PAPER_TRUTH = {
    "mass[1]": -0.0087, "mass[2]": -0.0333, "mass[3]": 0.0025, "mass[4]": 0.0058,
    "mass[5]": -0.0230, "stiffness[1]": 0.0119, "stiffness[2]": 0.0119,
    "stiffness[3]": -0.0004, "stiffness[4]": 0.0033, "stiffness[5]": 0.0017,
    "added_mass[1]": 0.15, "added_mass[2]": 0.25, "added_mass[3]": 0.20,
}


def paper_study_dict(wet=(1, 2, 3), form="summed", fix=True):
    """The paper's chain study as a dict (examples/paper_chain_masses_1-3_wet.yaml)."""
    truth = {k: v for k, v in PAPER_TRUTH.items()
             if not k.startswith("added_mass") or int(k[11]) in wet}
    study = {
        "name": "paper_chain_dict",
        "model": {"type": "chain", "masses": [50] * 5, "springs": [2.9e7] * 5,
                  "wet": list(wet)},
        "parameters": {"mass": "per_element", "stiffness": "per_element",
                       "added_mass": "per_element"},
        "truth": truth,
        "measurements": [{"state": "air", "immersion": "dry", "simulate_modes": 2},
                         {"state": "water", "immersion": "wet", "simulate_modes": 2}],
        "system": {"form": form, "fem_modes": "all"},
        "solver": {"name": "lstsq"},
    }
    if fix:
        study["parameters"]["fix"] = {"mass[4]": 0.0058}
    return study


@pytest.fixture
def paper_dict():
    return paper_study_dict()


def cli_path():
    cli = os.path.abspath(os.environ.get("FEMUP_CLI") or str(ROOT / "build" / "femup"))
    if not os.path.exists(cli):
        pytest.skip(f"the command line is not built ({cli}); ctest sets FEMUP_CLI")
    return cli


@pytest.fixture
def run_cli(tmp_path):
    """Runs `femup COMMAND STUDY -o DIR --no-plots -q` and returns the JSON it wrote."""

    def run(command, study, json_name, *extra):
        out = tmp_path / f"{command}_{pathlib.Path(study).stem}"
        subprocess.run([cli_path(), command, str(study), "-o", str(out), "--no-plots",
                        "-q", *extra], check=True, cwd=tmp_path, capture_output=True)
        with open(out / json_name) as f:
            return json.load(f)

    return run
