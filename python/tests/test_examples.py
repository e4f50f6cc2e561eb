"""The scripts of examples/python run to the end and check their own answers
(each exits non-zero when its numbers are off)."""

import os
import subprocess
import sys

import pathlib

import pytest

import femup
from conftest import ROOT

SCRIPTS = sorted((ROOT / "examples" / "python").glob("*.py"))


def test_the_three_examples_are_there():
    assert {p.name for p in SCRIPTS} >= {"paper_study.py", "diagnosis.py",
                                         "era_to_update.py"}


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_example_script(script, tmp_path):
    # The module under test, wherever the script runs from.
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(femup.__file__).resolve().parents[1]))
    run = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                         text=True, env=env, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.strip()
