"""python3 -m piezocontact: the command line of piezo-contact, on JIT-compiled
forms, plus --engine cpp|reference (default cpp)."""

import logging
import sys

from mpi4py import MPI

from . import api, cpp, model


def main(argv):
    args, engine = [], "cpp"
    i = 0
    while i < len(argv):
        if argv[i] == "--engine" and i + 1 < len(argv):
            engine = argv[i + 1]
            i += 2
            continue
        args.append(argv[i])
        i += 1
    if engine not in api.ENGINES:
        if MPI.COMM_WORLD.rank == 0:
            print(f"error: --engine {engine}: expected one of {', '.join(api.ENGINES)}",
                  file=sys.stderr)
        return cpp.exit_config_error
    # the JIT's compiler (distutils, via cffi) lowers the root logger to
    # INFO and logs every compiler command: a command line shows warnings only
    logging.getLogger().addFilter(lambda record: record.levelno >= logging.WARNING)
    keep = []
    return cpp.command_line("python3 -m piezocontact", args, MPI.COMM_WORLD,
                            api.ENGINES[engine], model.factory(keep=keep),
                            api.engine_loop(engine, keep))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
