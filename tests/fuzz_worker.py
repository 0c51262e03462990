"""Run fuzz cases (tests/fuzz.py) through `python3 -m piezocontact` in one
process: argv lists as JSON on stdin; per case, one JSON line {"code",
"stderr"} on stdout. A Python exception escaping the package is reported as
its traceback with exit code -1; a crash ends the process (the parent names
the case)."""

import ctypes
import json
import os
import sys
import tempfile
import traceback

from piezocontact.__main__ import main

LIBC = ctypes.CDLL(None)


def run(argv, engine):
    """Exit code and everything written to fd 1 and 2 (C++ and Python)."""
    with tempfile.TemporaryFile() as capture:
        saved = os.dup(1), os.dup(2)
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(capture.fileno(), 1)
        os.dup2(capture.fileno(), 2)
        try:
            code = main(["--engine", engine] + argv)
        except BaseException:  # noqa: B902 (anything escaping is a finding)
            traceback.print_exc()
            code = -1
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            LIBC.fflush(None)  # C stdio buffers, before fd 1 and 2 go back
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])
        capture.seek(0)
        return code, capture.read().decode(errors="replace")


if __name__ == "__main__":
    engine = sys.argv[1]
    for argv in json.load(sys.stdin):
        code, output = run(argv, engine)
        print(json.dumps({"code": code, "stderr": output}), flush=True)
