"""SIGINT or SIGTERM at any instant of `python3 -m piezocontact`'s start-up
(importing dolfinx, compiling forms, building the mesh) ends it with one
line and exit 130 / 143, never a traceback. The first ~20 ms, before the
interpreter runs the package's first line, are Python's own."""

import signal
import subprocess
import time

import pytest
from conftest import ENV, MODULE, SQUARE

# from 0.15 s: before the package's first line runs (~30 ms idle, more on a loaded
# machine) a signal meets Python's own handlers
INSTANTS = [0.15, 0.25, 0.35, 0.5, 0.8, 1.2]


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_no_traceback_at_any_instant(tmp_path, signum):
    for i, delay in enumerate(INSTANTS):
        args = MODULE + ["--config", str(SQUARE), "--output", str(tmp_path / str(i)),
                         "--quiet", "--set", "mesh.n=48", "--set", "time.steps=400"]
        proc = subprocess.Popen(args, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True)
        time.sleep(delay)
        proc.send_signal(signum)
        _, err = proc.communicate(timeout=120)
        assert proc.returncode == 128 + signum, (delay, err)
        assert "Traceback" not in err and "Error" not in err, (delay, err)
        lines = [line for line in err.splitlines() if not line.startswith("piezocontact: compiling")]
        assert len(lines) == 1 and "interrupted by" in lines[0], (delay, err)
