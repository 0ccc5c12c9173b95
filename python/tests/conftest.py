"""Shared fixtures: the real scans ($PDEFACE_DATA, default ../shared/faces; tests that need them skip,
saying so, when absent) and the command line (PDEFACE_CLI, set by ctest) to compare against."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def faces_dir() -> pathlib.Path:
    return pathlib.Path(os.environ.get("PDEFACE_DATA") or os.environ.get("PDEFACE_DEFAULT_FACES")
                        or ROOT.parent / "shared" / "faces")


@pytest.fixture(scope="session")
def faces() -> pathlib.Path:
    d = faces_dir()
    if not (d / "facefuns_f18.ply").is_file():
        pytest.skip(f"the shared face scans are not in {d} (set PDEFACE_DATA)")
    return d


@pytest.fixture(scope="session")
def cli():
    """Runs the pdeface command: cli("encode", a, "-o", b) -> CompletedProcess (text)."""
    exe = os.environ.get("PDEFACE_CLI") or str(ROOT / "build" / "apps" / "pdeface" / "pdeface")
    if not os.path.exists(exe):
        pytest.skip(f"the pdeface command is not built ({exe}; set PDEFACE_CLI)")

    def run(*args, check=True):
        return subprocess.run([exe, *map(str, args)], capture_output=True, text=True, check=check)

    return run
