"""A command line (`python3 -m piezocontact`) stopped before its run began
or after it ended.

The C++ core handles SIGINT and SIGTERM during a run (the step under way is
abandoned, the summary says so, exit 130 / 143), from before the model's
forms are compiled to the end of the run. Before that the interpreter is
importing dolfinx, where Python's default SIGINT handler would raise
KeyboardInterrupt inside some import and print its traceback; nothing is
written yet (no form is compiled at import), so the process ends at once
with one line and the same exit codes. After the run, the same: what the
run wrote is complete."""

import os
import signal

_NAMES = {signal.SIGINT: "SIGINT", signal.SIGTERM: "SIGTERM"}
_when = "before the run started: nothing written"


def _stop(signum, frame):
    os.write(2, f"interrupted by {_NAMES[signum]} {_when}\n".encode())
    os._exit(128 + signum)


def quiet_until_run():
    """Install the handlers (the core replaces them for the run, then
    restores them)."""
    for signum in _NAMES:
        signal.signal(signum, _stop)


def run_ended():
    """From now on a signal comes after the run."""
    global _when
    _when = "after the run ended"
