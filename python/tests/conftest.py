"""Fixtures of the Python module's tests (CTest label python, python/CMakeLists.txt):
the `cdyn` program they compare with (CDYN_EXE) and the source tree (CDYN_SOURCE_DIR)."""

import os
import subprocess

import pytest

SOURCE_DIR = os.environ.get("CDYN_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture
def scene():
    """The path of a scene of data/scenes."""
    return lambda name: os.path.join(SOURCE_DIR, "data", "scenes", name + ".toml")


@pytest.fixture
def cli():
    """Runs the `cdyn` program: (exit status, stdout, stderr)."""
    exe = os.environ.get("CDYN_EXE") or os.path.join(SOURCE_DIR, "build", "apps", "cdyn")

    def run(*args, cwd=None):
        p = subprocess.run([exe, *map(str, args)], capture_output=True, text=True, cwd=cwd)
        return p.returncode, p.stdout, p.stderr
    return run
