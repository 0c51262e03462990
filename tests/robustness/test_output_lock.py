"""One run at a time in an output folder: a second run into a folder that
another is writing is refused at once (exit 2, one line naming the folder);
the lock goes with the process however it ends, so a killed run resumes."""

import os
import signal
import subprocess
import time

from conftest import ENV, SQUARE, command, run_solver

LONG = ["mesh.n=48", "time.steps=300", "output.xdmf=false"]  # several seconds


def start(out):
    args = command("cpp") + ["--config", str(SQUARE), "--output", str(out), "--quiet"]
    for o in LONG:
        args += ["--set", o]
    proc = subprocess.Popen(args, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.time() + 60
    while not (out / "summary.json").exists():  # the run holds the lock from before it
        assert proc.poll() is None and time.time() < deadline
        time.sleep(0.05)
    return proc


def test_second_run_is_refused_and_resume_works_after_a_kill(tmp_path):
    out = tmp_path / "run"
    first = start(out)
    try:
        for solver in ("cpp", "reference"):
            _, second = run_solver(solver, out, ["mesh.n=4"], check=False)
            assert second.returncode == 2, second.stderr
            lines = second.stderr.strip().splitlines()
            assert len(lines) == 1 and f"--output {out}: another run is writing there" \
                in lines[0], second.stderr
        _, resumed = run_solver("cpp", out, check=False, resume=True)
        assert resumed.returncode == 2 and "another run is writing there" in resumed.stderr
        assert first.poll() is None  # the first run goes on, untouched
    finally:
        first.send_signal(signal.SIGKILL)
        first.wait()
    summary, _ = run_solver("cpp", out, resume=True)
    assert summary["status"] == "completed"


def test_the_lock_goes_with_a_finished_run(tmp_path):
    out = tmp_path / "run"
    run_solver("cpp", out, ["mesh.n=4", "time.steps=2"])
    summary, _ = run_solver("cpp", out, ["mesh.n=4", "time.steps=2"])
    assert summary["status"] == "completed"
    assert (out / ".lock").exists() and os.path.getsize(out / ".lock") == 0
