"""Command line shared by the Python twin and the demos; the same flags and
exit codes as the C++ executable `piezo-contact`."""

import argparse
import logging
import sys
from pathlib import Path

from mpi4py import MPI

from . import config

EXIT_RUN_ERROR = 3


def parser(description):
    # ffcx/cffi JIT compilation logs every compiler call at INFO on the root
    # logger; keep its handler at WARNING
    logging.basicConfig()
    for handler in logging.getLogger().handlers:
        handler.setLevel(logging.WARNING)
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--config", required=True, help="JSON run configuration")
    ap.add_argument("--output", required=True, help="output directory")
    ap.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE",
                    help="override a config value (JSON value), e.g. --set mesh.n=64")
    ap.add_argument("--quiet", action="store_true", help="no per-step progress lines")
    return ap


def fail(message, code):
    """Print on rank 0, exit with the same code on every rank (no deadlock)."""
    if MPI.COMM_WORLD.rank == 0:
        print(f"error: {message}", file=sys.stderr, flush=True)
    sys.exit(code)


def prepare_output(path, source):
    try:
        Path(path).mkdir(parents=True, exist_ok=True)
        probe = Path(path) / ".write-test"
        probe.write_text("")
        probe.unlink()
    except OSError as err:
        raise config.ConfigError(f"{source}: --output {path}: cannot write there: "
                                 f"{err.strerror}") from None
