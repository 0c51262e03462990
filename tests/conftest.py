"""Fixtures: run the C++ executable or the Python twin on a config, with
overrides and optionally under mpirun, and hand back its summary."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "demos"))
BUILD = Path(os.environ.get("PIEZO_BUILD", ROOT / "build"))
SQUARE = ROOT / "demos" / "square.json"
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def command(solver, np_=1):
    exe = {"cpp": [str(BUILD / "piezo-contact")],
           "python": ["/usr/bin/python3", str(ROOT / "demos" / "piezo_contact.py")]}[solver]
    return (["mpirun", "-n", str(np_)] if np_ > 1 else []) + exe


def run_solver(solver, out, overrides=(), config=SQUARE, np_=1, check=True, resume=False):
    """Run one solver (with resume: continue the run in `out`, no config);
    return (summary or None, CompletedProcess)."""
    args = command(solver, np_) + (["--resume"] if resume else ["--config", str(config)]) \
        + ["--output", str(out), "--quiet"]
    for o in overrides:
        args += ["--set", o]
    proc = subprocess.run(args, capture_output=True, text=True, env=ENV, timeout=600)
    if check and proc.returncode != 0:
        raise AssertionError(f"{' '.join(args)} failed ({proc.returncode}):\n{proc.stderr}")
    summary_file = Path(out) / "summary.json"
    summary = json.loads(summary_file.read_text()) if summary_file.exists() else None
    return summary, proc


@pytest.fixture(scope="session")
def small_runs(tmp_path_factory):
    """Example 1 at n = 8, 8 steps, nodal output at every step: both solvers."""
    base = tmp_path_factory.mktemp("square8")
    overrides = ["mesh.n=8", "time.steps=8", "output.nodal=all"]
    return {s: (run_solver(s, base / s, overrides)[0], base / s) for s in ("cpp", "python")}


@pytest.fixture(params=["cpp", "python"])
def solver(request):
    return request.param
