"""piezocontact.solve: a run from a Python script, on the C++ time loop (JIT
kernels) or on the independent reference engine."""

import json
from pathlib import Path

from mpi4py import MPI

from . import cpp, model

ENGINES = {"cpp": "cpp-jit", "reference": "reference"}


def load(config, overrides=()):
    """(validated config dict, source) of a config file path or a dict;
    raises ConfigError (the C++ validator's message)."""
    if isinstance(config, (str, Path)):
        return json.loads(cpp.load_config(str(config), list(overrides))), str(config)
    source = "config"  # a dict: relative paths in it are taken from the working directory
    return json.loads(cpp.configure(json.dumps(config), list(overrides), source)), source


def engine_loop(engine, keep, observer=None):
    """The time loop the driver runs: None for the C++ one."""
    if engine not in ENGINES:
        raise ValueError(f"engine = {engine!r}: expected one of {', '.join(ENGINES)}")
    if engine == "cpp":
        return None
    from . import reference
    return reference.engine(keep, observer)


def engine_analysis(engine, keep):
    """The dynamic analysis the driver runs: None for the C++ one."""
    if engine == "cpp":
        return None
    from . import reference_dynamics
    return reference_dynamics.analysis(keep)


def solve(config, output, engine="cpp", extra_residual=None, contact_law=None, overrides=(),
          progress=True, comm=MPI.COMM_WORLD, observer=None, data=None):
    """Run the model of `config` (a path or a dict) and write `output`
    (None: write nothing, the run kept in memory).

    engine: "cpp" (the C++ time loop on JIT-compiled forms) or "reference"
      (stock dolfinx/PETSc Newton, its own loop: the independent check).
    extra_residual(u, phi, w, psi, data): a UFL form added to the residual;
      the Jacobian follows by differentiation.
    contact_law(r, c_p): replaces the normal compliance law p.
    data: {config key: f(x, t)}: loads, charges or the gap as UFL
      expressions of x = ufl.SpatialCoordinate and the time t, added to
      the config's value of that key; "boundaries.NAME.contact.obstacle":
      the signed distance to an obstacle of any shape, replacing the
      config's obstacle geometry (model.JitModel lists the keys).
    observer(step, record): called after each accepted step.
    Returns the summary (the dict written to output/summary.json). Raises
    ConfigError, NewtonFailure, OutputError, Interrupted (piezocontact.cpp).

    A thin front end of piezocontact.Problem: with output None it is
    Problem.from_config(config).solve(); with an output folder the core
    makes the mesh there (so that `--resume` finds it) and runs the same
    driver."""
    from . import problem
    if output is None:
        p = problem.Problem.from_config(config, overrides, comm, extra_residual, contact_law, data)
        keep = []
        return problem.run(p.config, p.source, None, engine, keep, progress, observer,
                           model.factory(extra_residual, contact_law, keep, data, p.mesh),
                           comm, p.named)
    cfg, source = load(config, overrides)
    keep = []
    return problem.run(cfg, source, output, engine, keep, progress, observer,
                       model.factory(extra_residual, contact_law, keep, data), comm)
