"""Hostile but realistic input beyond the config's own keys (those are in
bad_inputs.py / test_config.py): the command line, encodings, processes
without cells, output directories the OS refuses, and a penalty so large
that Newton's scaled test would pass with forces unbalanced. Every engine
answers with exit 0, 2 or 3 and one line; see also test_fuzz.py."""

import json
import os
import pwd
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest
from conftest import ENGINES, ENV, SQUARE, command, run_solver

QUICK = ["mesh.n=4", "time.steps=2"]


def call(solver, args, np_=1, timeout=300):
    proc = subprocess.run(command(solver, np_) + args, capture_output=True, text=True,
                          env=ENV, timeout=timeout)
    errors = [line for line in proc.stderr.splitlines() if line.startswith("error")]
    return proc.returncode, errors, proc.stderr


@pytest.mark.parametrize("solver", ENGINES)
@pytest.mark.parametrize("args,message", [
    (["--quite"], "error: unknown argument '--quite' (did you mean --quiet?)"),
    (["-ksp_view"], "error: unknown argument '-ksp_view'"),
    (["stray"], "error: unknown argument 'stray'"),
    (["--set"], "error: --set needs a value"),
    (["--output", "/tmp/other"], "error: --output given twice"),
])
def test_command_line_is_strict(solver, args, message, tmp_path):
    """Everything on the command line is ours: nothing is passed on to PETSc
    or silently ignored."""
    code, errors, _ = call(solver, ["--config", str(SQUARE), "--output", str(tmp_path / "o")]
                           + args)
    assert (code, errors) == (2, [message])
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("solver", ENGINES)
def test_byte_order_mark_is_read_as_json(solver, tmp_path):
    """A UTF-8 byte-order mark (some editors write one) is accepted by every
    engine, and the run is the same."""
    config = tmp_path / "bom.json"
    config.write_bytes(b"\xef\xbb\xbf" + SQUARE.read_bytes())
    with_bom, _ = run_solver(solver, tmp_path / "a", QUICK, config=config)
    plain, _ = run_solver(solver, tmp_path / "b", QUICK)
    assert with_bom["steps"][-1]["probes"] == plain["steps"][-1]["probes"]


@pytest.mark.parametrize("solver", ENGINES)
def test_a_process_without_cells_is_refused(solver, tmp_path):
    """2 cells on 3 processes: dolfinx 0.5 cannot collapse a space on a
    process without cells (it crashed); now one line and exit 2 on all."""
    proc = subprocess.run(["mpirun", "--oversubscribe", "-n", "3"] + command(solver)
                          + ["--config", str(SQUARE), "--output", str(tmp_path / "o"),
                             "--quiet", "--set", "mesh.n=1", "--set", "time.steps=1"],
                          capture_output=True, text=True, env=ENV, timeout=300)
    assert proc.returncode == 2
    errors = [line for line in proc.stderr.splitlines() if line.startswith("error")]
    assert errors == [f"error: {SQUARE}: mesh: 2 cells for 3 processes leave a process "
                      "without a cell, which is not supported (dolfinx 0.5 cannot collapse a "
                      "space there): use a finer mesh or fewer processes"]


def balanced(step, load=(0.0, 10.0)):
    """The top's 10 N/m against the contact force and the left's reaction."""
    total = np.array(step["contact_force"]) + np.array(step["reactions"]["left"])
    return np.allclose(total, load, rtol=0, atol=1e-6 * np.linalg.norm(load))


@pytest.mark.parametrize("solver", ENGINES)
@pytest.mark.parametrize("c_p", ["1e20", "1e30", "1e100"])
def test_forces_balance_or_the_run_says_why(solver, c_p, tmp_path):
    """A penalty far beyond the elastic stiffness makes the scaled per-field
    test blind to the contact rows: at 1e30 a run "completed" with 10 N/m
    applied and 11.3 N/m found; at 1e100 phi was accepted after 0
    iterations. Now every engine iterates until the forces balance too, or
    stops with exit 3 saying so; no unbalanced step is ever recorded."""
    out = tmp_path / "o"
    code, errors, _ = call(solver, ["--config", str(SQUARE), "--output", str(out), "--quiet",
                                    "--set", f"contact.c_p={c_p}", "--set", "time.steps=2"])
    summary = json.loads((out / "summary.json").read_text())
    assert all(balanced(step) for step in summary["steps"])
    if c_p == "1e20":
        assert code == 0
    elif c_p == "1e100":
        assert code == 3 and len(errors) == 1 and "balance" in errors[0], errors
    else:
        assert code in (0, 3) and (code == 0 or "balance" in errors[0]), errors


@pytest.mark.parametrize("solver", ENGINES)
@pytest.mark.parametrize("probes", [[], None])
def test_probes_are_optional(solver, probes, tmp_path):
    config = json.loads(SQUARE.read_text())
    if probes is None:
        del config["probes"]
    else:
        config["probes"] = probes
    path = tmp_path / "c.json"
    path.write_text(json.dumps(config))
    summary, _ = run_solver(solver, tmp_path / "o", QUICK, config=path)
    assert summary["status"] == "completed"
    assert all(step["probes"] == [] for step in summary["steps"])


def test_tiny_permittivity_is_positive_definite(tmp_path):
    """1e-170 I is positive definite: validation must not say otherwise (its
    minors underflowed to 0). Solving with it is another matter."""
    code, errors, _ = call("cpp", ["--config", str(SQUARE), "--output", str(tmp_path / "o"),
                                   "--quiet", "--set",
                                   "material.permittivity=[[1e-170,0],[0,1e-170]]"]
                           + [a for o in QUICK for a in ("--set", o)])
    assert code in (0, 3)
    assert not any("positive definite" in e for e in errors)


def as_nobody():
    """A prefix that runs a command as the unprivileged user `nobody` (the
    tests run as root, to whom every permission is granted)."""
    if os.geteuid() != 0 or not shutil.which("setpriv"):
        pytest.skip("needs root (to become nobody) and setpriv")
    nobody = pwd.getpwnam("nobody")
    return ["setpriv", f"--reuid={nobody.pw_uid}", f"--regid={nobody.pw_gid}",
            "--clear-groups"]


@pytest.mark.parametrize("solver", ENGINES)
def test_permission_denied_is_reported_as_such(solver):
    """Not "No such file or directory": the OS's reason."""
    prefix = as_nobody()
    base = Path(tempfile.mkdtemp(prefix="piezo-nobody-"))  # pytest's tmp is root's alone
    try:
        os.chmod(base, 0o755)
        locked = base / "locked"
        locked.mkdir(mode=0o555)
        config = base / "c.json"
        config.write_text(SQUARE.read_text())
        os.chmod(config, 0o644)
        home = base / "home"  # nobody's HOME, for the JIT cache
        home.mkdir(mode=0o777)
        os.chmod(home, 0o777)
        proc = subprocess.run(prefix + command(solver)
                              + ["--config", str(config), "--output", str(locked / "out")],
                              capture_output=True, text=True, env=dict(ENV, HOME=str(home)),
                              timeout=300)
    finally:
        shutil.rmtree(base)
    errors = [line for line in proc.stderr.splitlines() if line.startswith("error")]
    assert proc.returncode == 2
    assert errors == [f"error: {config}: --output {locked / 'out'}: cannot write there: "
                      "Permission denied"]


def test_message_lines_stay_short(tmp_path):
    """A 30 kB value or key is abbreviated in the message, which stays one
    line."""
    code, errors, _ = call("cpp", ["--config", str(SQUARE), "--output", str(tmp_path / "o"),
                                   "--set", "time.T=" + json.dumps(["x" * 30000]),
                                   "--set", "x" * 30000 + "=1"])
    assert code == 2 and len(errors) == 1 and len(errors[0]) < 400, errors
