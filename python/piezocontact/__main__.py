"""python3 -m piezocontact: the command line of piezo-contact, on JIT-compiled
forms, plus --engine cpp|reference (default cpp)."""

import sys

from mpi4py import MPI

from . import api, cpp, mesh_tools, model


def main(argv):
    keep = []  # the Python model objects of the run (the reference engine's)
    engines = [(name, solver, model.factory(keep=keep), api.engine_loop(name, keep),
                api.engine_analysis(name, keep)) for name, solver in api.ENGINES.items()]
    code = cpp.command_line("python3 -m piezocontact", argv, MPI.COMM_WORLD, engines,
                            mesh_tools.convert)
    from . import _signals
    _signals.run_ended()
    return code


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
