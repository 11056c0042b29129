"""Shared set-up of the Python module's tests (ctest label `python`, tests/CMakeLists.txt).

ctest runs them with Debian's /usr/bin/python3 (python3-numpy, python3-pytest), PYTHONPATH set to the build tree's
python/ folder (the package crankcheck), and these variables:
    CRANKCHECK_BINARY      the crankcheck CLI, the independent side of every comparison
    CRANKCHECK_SCENES_DIR  scenes/ (the example scenes)
    CRANKCHECK_EXAMPLES_DIR examples/grade/ (the programs `crankcheck grade` examples grade)
"""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import crankcheck

EPS = np.finfo(float).eps


def _env(name):
    value = os.environ.get(name)
    if not value:
        pytest.exit("%s is not set: run the tests through ctest (ctest --test-dir build -L python)" % name, 2)
    return value


CLI = _env("CRANKCHECK_BINARY")
SCENES_DIR = _env("CRANKCHECK_SCENES_DIR")
EXAMPLES_DIR = os.environ.get("CRANKCHECK_EXAMPLES_DIR", "")
SCENE_FILES = sorted(os.path.join(SCENES_DIR, f) for f in os.listdir(SCENES_DIR) if f.endswith(".toml"))


def run_cli(*args, check=True):
    """Runs the CLI; returns (exit status, stdout, stderr)."""
    p = subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600)
    if check and p.returncode != 0:
        raise AssertionError("crankcheck %s: exit %d: %s" % (" ".join(args), p.returncode, p.stderr))
    return p.returncode, p.stdout, p.stderr


def cli_json(*args):
    return json.loads(run_cli(*args, "--format", "json")[1])


def cli_refusal(*args):
    """The CLI's one-line refusal of bad input (exit status 2, nothing on stdout), without its "crankcheck: " prefix."""
    status, out, err = run_cli(*args, check=False)
    assert status == 2, (args, status, err)
    assert out == "", out
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("crankcheck: "), err
    return lines[0][len("crankcheck: "):]


@pytest.fixture(scope="session")
def scene_files():
    return SCENE_FILES


def scene_id(path):
    return os.path.splitext(os.path.basename(path))[0]
