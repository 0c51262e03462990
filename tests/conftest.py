"""Fixtures: run an engine on a config through its command line, with
overrides and optionally under mpirun, and hand back its summary. Engines:
"cpp" the executable (ahead-of-time kernels), "cpp-jit" the same C++ loop
from `python3 -m piezocontact` (JIT kernels), "reference" the independent
reference engine (`--engine reference`)."""

import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
# The support code here (fuzz, bad_inputs...) for the tests in the folders
# below, one folder per kind: verification/, engines/, robustness/, demos/
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "demos"))
BUILD = Path(os.environ.get("PIEZO_BUILD", ROOT / "build"))
# This tree's build of the Python package, not an installed one
sys.path.insert(0, str(BUILD / "python"))
SQUARE = ROOT / "demos" / "square.json"
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           PYTHONPATH=os.pathsep.join([str(BUILD / "python"), str(ROOT / "demos")]
                                      + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))


MODULE = ["/usr/bin/python3", "-m", "piezocontact"]


def command(solver, np_=1):
    exe = {"cpp": [str(BUILD / "piezo-contact")],
           "cpp-jit": MODULE,
           "reference": MODULE + ["--engine", "reference"]}[solver]
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


def resume(solver, out, np_=1, check=True, overrides=()):
    """Continue the run in `out` (--resume): (summary or None, CompletedProcess)."""
    return run_solver(solver, out, overrides, np_=np_, check=check, resume=True)



def slab(m, steps=4):
    """demos/slab.json on n = [4m, 4m, m] for `steps` steps of k = 1/16"""
    return [f"mesh.n=[{4 * m},{4 * m},{m}]", f"time.steps={steps}", f"time.T={steps / 16}"]


def probe_values(summary):
    """Every probe's u and phi at every step, as arrays"""
    u = np.array([p["u"] for s in summary["steps"] for p in s["probes"]])
    phi = np.array([p["phi"] for s in summary["steps"] for p in s["probes"]])
    return u, phi


def relative_difference(a, b):
    """The largest probe differences of two runs, each relative to the
    field's largest value in `a`: (u, phi)"""
    (ua, pa), (ub, pb) = probe_values(a), probe_values(b)
    return (np.abs(ua - ub).max() / np.abs(ua).max(),
            np.abs(pa - pb).max() / max(np.abs(pa).max(), 1e-300))

def xdmf_times(path):
    """Time values per function listed in an XDMF file (it must parse)."""
    root = ET.parse(path).getroot()
    out = {}
    for grid in root.iter("Grid"):
        if grid.get("CollectionType") == "Temporal":
            out[grid.get("Name")] = [float(t.get("Value")) for t in grid.iter("Time")]
    return out


@pytest.fixture(scope="session")
def small_runs(tmp_path_factory):
    """Example 1 at n = 8, 8 steps, nodal output at every step: every engine."""
    base = tmp_path_factory.mktemp("square8")
    overrides = ["mesh.n=8", "time.steps=8", "output.nodal=all"]
    return {s: (run_solver(s, base / s, overrides)[0], base / s) for s in ENGINES}


ENGINES = ("cpp", "cpp-jit", "reference")


@pytest.fixture(params=["cpp", "cpp-jit"])
def solver(request):
    """The two front doors of the C++ loop (the same driver behind both)."""
    return request.param


@pytest.fixture(params=ENGINES)
def engine(request):
    return request.param
