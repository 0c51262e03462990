"""piezocontact: quasistatic contact of viscoelastic piezoelectric bodies with
a normal-compliance foundation (Barboteu, Fernandez & Ouafik 2008), a
FEniCSx plugin: the C++ core (piezocontact.cpp) drives forms that Python
JIT-compiles from the UFL of forms/.

    summary = piezocontact.solve("demos/square.json", output="out/square")
    solution = piezocontact.Problem(mesh, facet_tags, boundary_names=..., ...).solve()
"""

import sys


def _run_as_command_line():
    """Imported by `python3 [options] -m piezocontact` (not a submodule)"""
    argv = getattr(sys, "orig_argv", [])
    return sys.argv[:1] == ["-m"] and "-m" in argv \
        and argv[argv.index("-m") + 1:][:1] == ["piezocontact"]


if _run_as_command_line():
    from . import _signals
    _signals.quiet_until_run()

from . import _quiet  # noqa: E402

_quiet.install()  # before anything JIT-compiles

from .api import load, solve  # noqa: E402
from .cpp import ConfigError, Interrupted, NewtonFailure, OutputError  # noqa: E402
from .data import Boundary, Contact, Material, Time  # noqa: E402
from .problem import Problem, Solution, Step  # noqa: E402

__all__ = ["Problem", "Solution", "Step", "Material", "Boundary", "Contact", "Time", "solve",
           "load", "ConfigError", "NewtonFailure", "OutputError", "Interrupted"]
