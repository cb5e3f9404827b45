"""Shared set-up of the demfit module tests: the source tree, the demfit executable the module is
compared with, and a reader of the CSV files it writes.

Run by ctest (tests/python/CMakeLists.txt sets PYTHONPATH, DEMFIT_EXE, DEMFIT_SOURCE_DIR and
DEMFIT_CACHE_DIR); by hand:
  PYTHONPATH=build/python DEMFIT_EXE=build/apps/demfit /usr/bin/python3 -m pytest -q tests/python
"""
import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("DEMFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def source_dir():
    return SOURCE_DIR


@pytest.fixture(scope="session")
def demfit_exe():
    exe = os.environ.get("DEMFIT_EXE", str(SOURCE_DIR / "build" / "apps" / "demfit"))
    if not os.access(exe, os.X_OK):
        pytest.fail(f"the demfit executable {exe} is missing: build it, or set DEMFIT_EXE")
    return exe


def run_cli(exe, *args, cwd=None):
    """The command line's exit status, standard output and standard error."""
    done = subprocess.run([exe, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=600)
    return done.returncode, done.stdout, done.stderr


def cli_error(stderr):
    """The message of the command line's one error line 'demfit: error: <message>'."""
    lines = [line for line in stderr.splitlines() if line.startswith("demfit: error: ")]
    assert len(lines) == 1, stderr
    return lines[0][len("demfit: error: "):]


def read_csv(path):
    """A CSV file demfit wrote: '#' comment lines, one header line, numbers. Returns (header, columns)."""
    lines = [line for line in pathlib.Path(path).read_text().splitlines() if not line.startswith("#")]
    header = lines[0].split(",")
    values = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    return header, values.T
