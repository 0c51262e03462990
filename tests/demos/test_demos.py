"""Every demo of demos/, the README's main command first, each at its
smallest honest size (the demo itself exits non-zero when its engines
disagree or its claims do not hold). Opt-in (marker `demo`): CI's demos leg
runs them, `bash scripts/demos.sh` or `pytest -m demo tests/demos`."""

import subprocess

import pytest

from conftest import ENV, ROOT

PY = "/usr/bin/python3"
DEMOS = {
    "main": ["bash", "scripts/demo.sh"],
    "square": [PY, "demos/demo_square.py", "--set", "mesh.n=16", "--set", "time.steps=16"],
    "unimorph": [PY, "demos/demo_unimorph.py"],
    "sensor": [PY, "demos/demo_sensor.py"],
    "python_api": [PY, "demos/demo_python_api.py"],
    "dolfinx_api": [PY, "demos/demo_dolfinx_api.py"],
    "dolfinx_api_mpi": ["mpirun", "-n", "2", PY, "demos/demo_dolfinx_api.py", "--steps", "4"],
    "step_control": [PY, "demos/demo_step_control.py"],
    "manufactured_rates": [PY, "demos/manufactured_rates.py", "--finest", "16"],
    "convergence_study": [PY, "demos/convergence_study.py", "--finest", "16"],
    "disc": [PY, "demos/demo_disc.py"],
    "plate": [PY, "demos/demo_plate.py", "--set", "mesh.n=8"],
    "indentation": [PY, "demos/demo_indentation.py"],
    "transducer": [PY, "demos/demo_transducer.py", "--points", "100"],
    "contact_resonance": [PY, "demos/demo_contact_resonance.py"],
}

IN_MEMORY = {"dolfinx_api", "dolfinx_api_mpi", "step_control"}


def test_every_demo_is_here():
    """A new demo joins this list (and so CI)."""
    scripts = {p.name for p in (ROOT / "demos").glob("*.py")}
    named = {part.split("/")[-1] for cmd in DEMOS.values() for part in cmd if part.endswith(".py")}
    assert scripts - {"demo_contactor.py"} == named  # the main command runs demo_contactor.py
    assert "demo_contactor.py" in (ROOT / "scripts" / "demo.sh").read_text()


@pytest.mark.demo
@pytest.mark.parametrize("name", DEMOS)
def test_demo(name, tmp_path):
    run = subprocess.run(DEMOS[name] + ["--output", str(tmp_path / name)], cwd=ROOT, env=ENV,
                         capture_output=True, text=True, timeout=900)
    log = run.stdout + run.stderr
    assert run.returncode == 0, f"{name} exited {run.returncode}:\n{log[-3000:]}"
    # no traceback, no JIT build log on the screen (the front door's promise)
    assert "Traceback" not in log and "running build_ext" not in log, log[-3000:]
    written = any((tmp_path / name).rglob("summary.json"))
    # the dolfinx-native API's demos run in memory: no summary, only the figures asked for
    assert written != (name in IN_MEMORY), "a summary written" if written else "no summary written"
