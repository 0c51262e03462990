"""A command line (`python3 -m piezocontact`) stopped before its run began.

The C++ core handles SIGINT and SIGTERM from the start of a run (the step
under way is abandoned, the summary says so, exit 130 / 143). Before that
the interpreter is importing dolfinx and compiling forms, where Python's
default SIGINT handler would raise KeyboardInterrupt inside some import and
print its traceback. Nothing is written yet, so the process ends at once
with one line and the same exit codes."""

import os
import signal

_NAMES = {signal.SIGINT: "SIGINT", signal.SIGTERM: "SIGTERM"}


def _stop(signum, frame):
    os.write(2, f"interrupted by {_NAMES[signum]} before the run started: nothing written\n"
             .encode())
    os._exit(128 + signum)


def quiet_until_run():
    """Install the handlers (the core replaces them for the run, then
    restores them)."""
    for signum in _NAMES:
        signal.signal(signum, _stop)
