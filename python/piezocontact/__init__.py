"""piezocontact: quasistatic contact of viscoelastic piezoelectric bodies with
a normal-compliance foundation (Barboteu, Fernandez & Ouafik 2008), a
FEniCSx plugin: the C++ core (piezocontact.cpp) drives forms that Python
JIT-compiles from the UFL of forms/.

    summary = piezocontact.solve("demos/square.json", output="out/square")
"""

from .api import load, solve
from .cpp import ConfigError, Interrupted, NewtonFailure, OutputError

__all__ = ["solve", "load", "ConfigError", "NewtonFailure", "OutputError", "Interrupted"]
