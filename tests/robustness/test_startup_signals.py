"""SIGINT or SIGTERM at any instant of `python3 -m piezocontact`'s start-up
(importing dolfinx, compiling forms, building the mesh) ends it with one
line and exit 130 / 143, never a traceback. Before the package's first line
runs (~30 ms), the signals are Python's own: the instants are counted from
when the package has taken them (SIGTERM caught, in /proc/PID/status)."""

import signal
import subprocess
import time

import pytest
from conftest import ENV, MODULE, SQUARE

INSTANTS = [0.0, 0.05, 0.1, 0.2, 0.35, 0.5, 0.8, 1.2]


def catches_sigterm(pid):
    """Whether the process has a handler for SIGTERM (Python has none of
    its own: only the package installs one)."""
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("SigCgt:"):
                return bool(int(line.split()[1], 16) >> (signal.SIGTERM - 1) & 1)
    return False


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_no_traceback_at_any_instant(tmp_path, signum):
    for i, delay in enumerate(INSTANTS):
        args = MODULE + ["--config", str(SQUARE), "--output", str(tmp_path / str(i)),
                         "--quiet", "--set", "mesh.n=48", "--set", "time.steps=400"]
        proc = subprocess.Popen(args, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True)
        deadline = time.time() + 30
        while not catches_sigterm(proc.pid):
            assert proc.poll() is None and time.time() < deadline
            time.sleep(0.002)
        time.sleep(delay)
        proc.send_signal(signum)
        _, err = proc.communicate(timeout=120)
        assert proc.returncode == 128 + signum, (delay, err)
        assert "Traceback" not in err and "Error" not in err, (delay, err)
        lines = [line for line in err.splitlines() if not line.startswith("piezocontact: compiling")]
        assert len(lines) == 1 and "interrupted by" in lines[0], (delay, err)
