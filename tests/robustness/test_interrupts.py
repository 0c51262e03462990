"""Interrupted runs lose nothing: a kill -9 at any instant leaves every
output readable up to the last step in summary.json; SIGINT and SIGTERM
stop cleanly with status "interrupted"; a full disk ends the run with one
line and exit 4; --resume continues a run exactly as if never stopped."""

import json
import os
import random
import signal
import subprocess
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import h5py
import numpy as np
import pytest
from conftest import ENV, ROOT, SQUARE, command, resume, run_solver

VARIANT = ROOT / "demos" / "contactor_in_contact.json"
# Example 1 at n = 32: a few ms per step, so that kills land in every phase
KILLED = ["mesh.n=32", "time.steps=2000", "output.nodal=all"]
FIELDS = {"u", "phi", "contact_pressure", "D", "stress_xx", "stress_yy", "stress_xy"}


def start(solver, out, overrides, config=SQUARE, np_=1, env=None):
    args = command(solver, np_) + ["--config", str(config), "--output", str(out), "--quiet"]
    for o in overrides:
        args += ["--set", o]
    return subprocess.Popen(args, env={**ENV, **(env or {})}, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)


def wait_for_steps(proc, out, steps, timeout=300):
    """Poll summary.json (replaced atomically) until it lists `steps` steps."""
    summary = Path(out) / "summary.json"
    deadline = time.time() + timeout
    while time.time() < deadline and proc.poll() is None:
        if summary.exists() and len(json.loads(summary.read_text())["steps"]) >= steps:
            return
        time.sleep(0.002)
    raise AssertionError(f"no step {steps} in {summary} (exit {proc.poll()})")


def kill9(proc):
    proc.send_signal(signal.SIGKILL)
    proc.wait()


def indexed_steps(out):
    """{function: [(t, [(h5 file, dataset, dims)...]) per step]} of solution.xdmf;
    it must parse."""
    root = ET.parse(Path(out) / "solution.xdmf").getroot()
    series = {}
    for grid in root.find("Domain").findall("Grid"):
        if grid.get("CollectionType") != "Temporal":
            continue
        steps = []
        for g in grid.findall("Grid"):
            items = []
            for item in g.iter("DataItem"):
                file, dataset = item.text.strip().split(":")
                items.append((Path(out) / file, dataset,
                              tuple(int(d) for d in item.get("Dimensions").split())))
            steps.append((float(g.find("Time").get("Value")), items))
        series[grid.get("Name")] = steps
    return series


def read_indexed(out, name, step):
    """Values of function `name` at step (1-based) through the index."""
    _, items = indexed_steps(out)[name][step - 1]
    file, dataset, _ = items[0]
    with h5py.File(file, "r") as f:
        return f[dataset][()]


def check_outputs(out, status="running"):
    """Everything a kill may have cut short is readable: the summary, its
    checkpoint, the index and the HDF5 data of every indexed step, the mesh,
    the nodal files of every step. Returns the number of steps recorded."""
    out = Path(out)
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == status
    n = len(s["steps"])
    assert s["checkpoint"]["step"] == n
    state = np.load(out / s["checkpoint"]["file"])
    assert state.shape[1] == 9 and np.isfinite(state).all()
    series = indexed_steps(out)
    # the four series come with the first step, all at once
    assert set(series) == FIELDS or (not series and n == 0), (set(series), n)
    for name, steps in series.items():
        # the step after the last recorded one may be indexed already
        assert len(steps) in (n, n + 1), (name, len(steps), n)
        assert [t for t, _ in steps[:n]] == [st["t"] for st in s["steps"]]
        for _, items in steps:
            for file, dataset, dims in items:
                with h5py.File(file, "r") as f:
                    data = f[dataset][()]
                assert data.shape == dims and np.isfinite(data).all()
    with h5py.File(out / "solution.h5", "r") as f:
        assert f["/Mesh/mesh/geometry"].shape[0] > 0
    if s["config"]["output"]["nodal"] == "all":
        for i in range(1, n + 1):
            for name in ("u", "phi", "contact_pressure"):
                assert np.isfinite(np.load(out / "nodal" / f"{name}_{i:04d}.npy")).all()
    return n


def kill_at_random_instant(solver, out, seed):
    """kill -9 a run some random time after it has written its first files;
    what it left resumes. PIEZO_KILL_SEED shifts the seeds, for campaigns at
    other instants."""
    proc = start(solver, out, KILLED)
    wait_for_steps(proc, out, 0)
    seed += int(os.environ.get("PIEZO_KILL_SEED", "0"))
    time.sleep(random.Random(seed).uniform(0.0, 1.5))
    kill9(proc)
    done = check_outputs(out)
    # to a power of two of steps at the same k = 1/2000 (m k / m == k exactly)
    m = 1 << done.bit_length()
    resumed, _ = resume(solver, out, overrides=[f"time.steps={m}", f"time.T={m / 2000!r}"])
    assert [r["step"] for r in resumed["resumed"]] == [done]
    assert check_outputs(out, status="completed") == m
    return done


@pytest.mark.parametrize("seed", range(3))
def test_kill_at_any_instant_leaves_readable_outputs(solver, seed, tmp_path):
    kill_at_random_instant(solver, tmp_path, seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(100, 150))
def test_kill_campaign(solver, seed, tmp_path):
    """The same at 50 more instants per solver."""
    kill_at_random_instant(solver, tmp_path, seed)


def without_timing(summary):
    return {k: v for k, v in summary.items() if k not in ("timing", "resumed", "mpi_size", "mesh_file")}


def assert_same_run(a, b, rel):
    """Every step record equal (bit for bit when rel = 0), events, status."""
    if rel == 0:
        assert without_timing(a) == without_timing(b)
        return

    def close(x, y):
        if isinstance(x, dict):
            assert x.keys() == y.keys()
            for k in x:
                close(x[k], y[k])
        elif isinstance(x, list):
            assert len(x) == len(y)
            for p, q in zip(x, y):
                close(p, q)
        elif isinstance(x, float):
            assert y == pytest.approx(x, rel=rel, abs=1e-300)
        else:
            assert x == y
    close(without_timing(a), without_timing(b))


def full_and_killed(solver, tmp_path, overrides, steps, config=SQUARE):
    """The run whole, in tmp_path/full, and killed in tmp_path/part once its
    summary lists `steps` steps: (full summary, part, steps part recorded)."""
    full, _ = run_solver(solver, tmp_path / "full", overrides, config=config)
    part = tmp_path / "part"
    proc = start(solver, part, overrides, config=config)
    wait_for_steps(proc, part, steps)
    kill9(proc)
    return full, part, check_outputs(part)


# The bar of the interrupted-runs issue: bit for bit (one loop, either front door)
REL = {"cpp": 0.0, "cpp-jit": 0.0}


def test_resume_after_kill_reproduces_the_run(solver, tmp_path):
    """Killed at step >= 40 of 150, then killed again while resuming: the
    resumed run's summary, nodal files and XDMF data equal the uninterrupted
    run's, every step."""
    overrides = ["mesh.n=24", "time.steps=150", "output.nodal=all"]
    full, part, first = full_and_killed(solver, tmp_path, overrides, 40)
    args = command(solver) + ["--output", str(part), "--resume", "--quiet"]
    proc = subprocess.Popen(args, env=ENV, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    wait_for_steps(proc, part, first + 20)
    kill9(proc)
    second = check_outputs(part)
    resumed, _ = resume(solver, part)
    assert [r["step"] for r in resumed["resumed"]] == [first, second]
    assert resumed["status"] == "completed"
    assert_same_run(full, resumed, REL[solver])
    for i in range(1, 151):
        for name in ("u", "phi", "contact_pressure"):
            a = np.load(tmp_path / "full" / "nodal" / f"{name}_{i:04d}.npy")
            b = np.load(part / "nodal" / f"{name}_{i:04d}.npy")
            np.testing.assert_allclose(b, a, rtol=REL[solver], atol=0)
    for i in (1, first, first + 1, 150):
        for name in FIELDS:
            np.testing.assert_allclose(read_indexed(part, name, i),
                                       read_indexed(tmp_path / "full", name, i),
                                       rtol=REL[solver], atol=0)
    # only the last checkpoint is kept
    assert [p.name for p in (part / "checkpoint").iterdir()] == ["state_000150.npy"]


def test_resume_keeps_step_cuts(solver, tmp_path):
    """At most 2 Newton iterations: the first nominal step is cut in four
    (events at the start, k kept small until t = 0.25). A run stopped after
    its first steps resumes to the uninterrupted one, events included."""
    overrides = ["mesh.size=0.05", "time.steps=40", "output.nodal=none",
                 "solver.newton.max_iterations=2", "solver.newton.max_step_halvings=8"]
    full, part, _ = full_and_killed(solver, tmp_path, overrides, 1, config=VARIANT)
    assert len(full["events"]) >= 3
    resumed, _ = resume(solver, part)
    assert_same_run(full, resumed, REL[solver])


def test_resume_before_the_first_step(solver, tmp_path):
    """A run that stopped before its first step (Newton fails at step 1: k =
    0.5, at most 3 iterations, no halving) resumes from its step-0
    checkpoint, and fails there again the same way; the resume keeps that
    checkpoint (it once removed it, as a fresh run does, and refused)."""
    cfg = json.loads(VARIANT.read_text())  # on a fixed mesh: iteration counts
    cfg["mesh"] = {"type": "xdmf", "path": str(ROOT / "tests" / "data" / "contactor_0.2.xdmf")}
    config = tmp_path / "variant.json"
    config.write_text(json.dumps(cfg))
    out = tmp_path / "run"
    overrides = ["time.steps=20", "output.nodal=none", "solver.newton.max_iterations=3",
                 "solver.newton.max_step_halvings=0"]
    first, proc = run_solver(solver, out, overrides, config=config, check=False)
    assert proc.returncode == 3 and first["checkpoint"]["step"] == 0 and not first["steps"]
    resumed, again = resume(solver, out, check=False)
    assert again.returncode == 3, again.stderr
    assert again.stderr.splitlines()[-1] == proc.stderr.splitlines()[-1]
    assert [r["step"] for r in resumed["resumed"]] == [0]
    assert without_timing(resumed) == without_timing(first)
    assert [p.name for p in (out / "checkpoint").iterdir()] == ["state_000000.npy"]


def test_resume_after_a_kill_before_the_first_step(solver, tmp_path):
    """Killed as soon as its summary appears (step 0 written, the first step
    under way, most times), a run resumes to the uninterrupted one."""
    overrides = ["mesh.n=48", "time.steps=6", "output.nodal=all"]
    full, part, done = full_and_killed(solver, tmp_path, overrides, 0)
    resumed, _ = resume(solver, part)
    assert [r["step"] for r in resumed["resumed"]] == [done]
    assert_same_run(full, resumed, REL[solver])
    for name in ("u", "phi", "contact_pressure"):
        np.testing.assert_array_equal(np.load(part / "nodal" / f"{name}_0006.npy"),
                                      np.load(tmp_path / "full" / "nodal" / f"{name}_0006.npy"))


def test_resume_extends_a_run_to_a_later_time(solver, tmp_path):
    """A completed run to T = 0.5, extended to T = 1 at the same step,
    equals the run to T = 1; the step size cannot change, nor other keys."""
    base = ["mesh.n=16", "output.nodal=all"]
    full, _ = run_solver(solver, tmp_path / "full", base + ["time.T=1", "time.steps=40"])
    short = tmp_path / "short"
    run_solver(solver, short, base + ["time.T=0.5", "time.steps=20"])
    for bad, message in [
            (["time.T=1", "time.steps=30"], "an extended run keeps its step T/steps = 0.025"),
            (["mesh.n=8"], "--set mesh.n: only time.T and time.steps can change on --resume"),
            (["time.T=0.25", "time.steps=10"], "time.steps = 10: the run has done 20 steps"),
            ([], 'cannot resume: status = "completed" (to extend it')]:
        _, proc = resume(solver, short, check=False, overrides=bad)
        assert proc.returncode == 2 and message in proc.stderr, proc.stderr
    # leftovers a kill can leave: the previous step's checkpoint (killed
    # between the summary and its removal) and a later one of an earlier run
    for stale in (19, 31):
        (short / "checkpoint" / f"state_{stale:06d}.npy").write_bytes(
            (short / "checkpoint" / "state_000020.npy").read_bytes())
    extended, _ = resume(solver, short, overrides=["time.T=1", "time.steps=40"])
    assert extended["status"] == "completed" and len(extended["steps"]) == 40
    assert [p.name for p in (short / "checkpoint").iterdir()] == ["state_000040.npy"]
    assert_same_run(full, extended, REL[solver])
    np.testing.assert_allclose(np.load(short / "nodal" / "u_0040.npy"),
                               np.load(tmp_path / "full" / "nodal" / "u_0040.npy"),
                               rtol=REL[solver], atol=0)
    # a fresh run in the same directory keeps nothing of the earlier one
    run_solver(solver, short, base + ["time.steps=3"])
    assert sorted(p.name for p in (short / "solution").iterdir()) == \
        [f"step_{i:06d}.h5" for i in (1, 2, 3)]
    assert [p.name for p in (short / "checkpoint").iterdir()] == ["state_000003.npy"]
    assert len(list((short / "nodal").iterdir())) == 9  # u, phi, contact_pressure
    assert check_outputs(short, status="completed") == 3


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_signal_stops_cleanly(solver, sig, tmp_path):
    """SIGINT/SIGTERM: the step under way is abandoned, the summary says
    "interrupted", one line says so, exit 128 + signal; no traceback."""
    proc = start(solver, tmp_path, KILLED)
    wait_for_steps(proc, tmp_path, 5)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 128 + sig
    n = check_outputs(tmp_path, status="interrupted")
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["signal"] == signal.Signals(sig).name
    assert err.strip().splitlines() == [
        f"interrupted by {signal.Signals(sig).name} after step {n} "
        f"(t = {s['steps'][-1]['t']!r}); continue with --resume"]
    # an interrupted step is not half-written: the index lists the n steps
    assert all(len(v) == n for v in indexed_steps(tmp_path).values())


def mpirun_forwards_sigterm(tmp_path):
    """Whether a SIGTERM to mpirun reaches its ranks: Open MPI 4 and 5 send
    them SIGTERM (SIGKILL a second later); 6.0 (Debian unstable) kills them
    outright. Probed with a rank that records what it receives."""
    mark = tmp_path / "got_sigterm"
    rank = ("import signal, sys, time, pathlib\n"
            "signal.signal(signal.SIGTERM, lambda *a: (pathlib.Path(sys.argv[1]).touch(),"
            " sys.exit(0)))\n"
            "pathlib.Path(sys.argv[1] + '.ready').touch()\n"
            "time.sleep(60)\n")
    proc = subprocess.Popen(["mpirun", "-n", "1", "/usr/bin/python3", "-c", rank, str(mark)],
                            env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 60
    while not Path(str(mark) + ".ready").exists() and time.time() < deadline:
        time.sleep(0.01)
    proc.send_signal(signal.SIGTERM)
    proc.wait(timeout=60)
    return mark.exists()


def ranks_of(proc):
    """The processes mpirun started (its children's children included)."""
    children = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(stat.parent.name))
    below = children.get(proc.pid, [])
    return below + [g for c in below for g in children.get(c, [])]


def test_sigterm_under_mpirun_stops_every_rank(solver, tmp_path):
    """A SIGTERM to one rank under mpirun: all ranks stop at the same
    iteration and the summary says so; the run then resumes on one process
    to the serial answer (a checkpoint is by input vertex). A rank is
    signalled, not mpirun: what mpirun does with a signal depends on the
    Open MPI and the load (the next test)."""
    overrides = ["mesh.n=24", "time.steps=200", "output.nodal=all"]
    proc = start(solver, tmp_path / "part", overrides, np_=2)
    wait_for_steps(proc, tmp_path / "part", 10)
    os.kill(ranks_of(proc)[-1], signal.SIGTERM)
    proc.communicate(timeout=60)
    assert proc.returncode != 0
    check_outputs(tmp_path / "part", status="interrupted")
    resumed, _ = resume(solver, tmp_path / "part")
    full, _ = run_solver(solver, tmp_path / "full", overrides)
    a = np.load(tmp_path / "full" / "nodal" / "u_0200.npy")
    b = np.load(tmp_path / "part" / "nodal" / "u_0200.npy")
    # rows in another order under MPI: match them by coordinates
    a, b = a[np.lexsort(a[:, :2].T)], b[np.lexsort(b[:, :2].T)]
    np.testing.assert_allclose(b, a, rtol=1e-9, atol=1e-9 * np.abs(a[:, 2:]).max())
    assert resumed["steps"][-1]["t"] == full["steps"][-1]["t"]


def test_sigterm_to_mpirun_loses_nothing(solver, tmp_path):
    """A SIGTERM to mpirun itself. Open MPI 4 and 5 forward it and send
    SIGKILL 1 s later; 6.0 kills the ranks outright. So the run ends
    "interrupted" when the step under way finished within that second, else
    "running" (README, "When things go wrong": a loaded machine, CI's two
    lanes, gives either). Either way every file is readable and --resume
    continues."""
    overrides = ["mesh.n=24", "time.steps=200", "output.nodal=all"]
    forwards = mpirun_forwards_sigterm(tmp_path)
    proc = start(solver, tmp_path / "part", overrides, np_=2)
    wait_for_steps(proc, tmp_path / "part", 10)
    proc.send_signal(signal.SIGTERM)
    proc.communicate(timeout=60)
    assert proc.returncode != 0
    status = json.loads((tmp_path / "part" / "summary.json").read_text())["status"]
    assert status in (("interrupted", "running") if forwards else ("running",))
    steps = check_outputs(tmp_path / "part", status=status)
    resumed, _ = resume(solver, tmp_path / "part")
    assert resumed["status"] == "completed" and len(resumed["steps"]) == 200 > steps


def test_resume_refuses_what_it_cannot_continue(solver, tmp_path):
    """Nothing to resume, a completed run, another solver's run, --config
    with --resume: one line, exit 2."""  # extending: test_resume_extends_...
    _, proc = resume(solver, tmp_path / "none", check=False)
    assert proc.returncode == 2
    assert proc.stderr.strip().splitlines()[-1] == \
        f"error: {tmp_path / 'none' / 'summary.json'}: cannot resume: no such file"
    run_solver(solver, tmp_path / "done", ["mesh.n=4", "time.steps=2"])
    _, proc = resume(solver, tmp_path / "done", check=False)
    assert proc.returncode == 2 and proc.stderr.strip().endswith(
        'cannot resume: status = "completed" (to extend it, --set time.T and time.steps)')
    other = {"cpp": "cpp-jit", "cpp-jit": "cpp"}[solver]
    s = json.loads((tmp_path / "done" / "summary.json").read_text())
    s["status"], s["solver"] = "running", other
    (tmp_path / "done" / "summary.json").write_text(json.dumps(s))
    _, proc = resume(solver, tmp_path / "done", check=False)
    assert proc.returncode == 2 and proc.stderr.strip().endswith(
        f'cannot resume: solver = "{other}", this is the "{solver}" solver')
    args = command(solver) + ["--output", str(tmp_path / "done"), "--resume",
                              "--config", str(SQUARE)]
    proc = subprocess.run(args, capture_output=True, text=True, env=ENV)
    assert proc.returncode == 2 and "DIR/summary.json: no --config" in proc.stderr


@pytest.fixture
def small_disk(tmp_path):
    """A 1.5 MB tmpfs: needs root and a kernel that lets us mount."""
    if os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs needs root")
    disk = tmp_path / "disk"
    disk.mkdir()
    proc = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1536k", "tmpfs", str(disk)],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {proc.stderr.strip()}")
    yield disk
    subprocess.run(["umount", str(disk)], check=True)


def test_full_disk_ends_with_one_line(solver, small_disk):
    """The disk fills up at some step: exit 4, one line naming the file and
    "No space left on device", no HDF5 dump; the summary says "failed" with
    the error and every step it records is readable."""
    out = small_disk / "run"
    _, proc = run_solver(solver, out, ["mesh.n=32", "time.steps=300"], check=False)
    assert proc.returncode == 4
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith(f"error: cannot write {out}/")
    assert lines[0].endswith(": No space left on device")
    n = check_outputs(out, status="failed")
    s = json.loads((out / "summary.json").read_text())
    assert s["error"] == lines[0][len("error: "):] and n > 0
