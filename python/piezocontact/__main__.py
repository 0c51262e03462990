"""python3 -m piezocontact: the command line of piezo-contact, on JIT-compiled
forms, plus --engine cpp|reference (default cpp)."""

import logging
import sys

from mpi4py import MPI

from . import api, cpp, model


def _warnings_only(record):
    return record.levelno >= logging.WARNING


def main(argv):
    # the JIT's compiler (distutils, via cffi) lowers the root logger to
    # INFO and logs every compiler command: a command line shows warnings only
    if _warnings_only not in logging.getLogger().filters:
        logging.getLogger().addFilter(_warnings_only)
    keep = []  # the Python model objects of the run (the reference engine's)
    engines = [(name, solver, model.factory(keep=keep), api.engine_loop(name, keep))
               for name, solver in api.ENGINES.items()]
    return cpp.command_line("python3 -m piezocontact", argv, MPI.COMM_WORLD, engines)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
