"""piezocontact.Problem: the model on a dolfinx mesh and its tags, solved in
memory by the C++ time loop or the reference engine, the state returned as
dolfinx Functions.

    problem = piezocontact.Problem(mesh, facet_tags, boundary_names={...},
                                   material=piezocontact.Material(...),
                                   boundaries={...}, time=piezocontact.Time(1.0, 10))
    solution = problem.solve(observer=lambda step: print(step.t, step.u.x.array.max()))

The config file is one front end of this: Problem.from_config(path) builds
the same Problem from a config (its mesh made by the core), and both run
through the one driver of the core (cpp.run_config)."""

import json
import shutil
import tempfile
from dataclasses import dataclass

import numpy as np
from dolfinx import fem
from mpi4py import MPI

from . import _compat as compat
from . import cpp, mesh_tools, model
from .data import as_function_of_x_t, is_ufl, plain

SOURCE = "piezocontact.Problem"


@dataclass
class Step:
    """An accepted step as the observer receives it: its number (1, 2, ...),
    time t (s), the converged u (m) and phi (V) as new dolfinx Functions
    (theirs to keep), and the step's record (the summary's entry)."""
    n: int
    t: float
    u: fem.Function
    phi: fem.Function
    record: dict


@dataclass
class Solution:
    """A finished run: the summary (as summary.json holds it) and the final
    state u (m), phi (V) as dolfinx Functions on the problem's mesh."""
    summary: dict
    u: fem.Function
    phi: fem.Function


def _state(x):
    """(u, phi): new Functions holding the mixed state x's parts."""
    u, phi = (x.sub(i).collapse() for i in (0, 1))
    u.name, phi.name = "u", "phi"
    return u, phi


def _config_error(source, key, message):
    return cpp.ConfigError(f"{source}: {key}: {message}")


def _json(cfg, source):
    """The config as JSON text; a value JSON cannot hold (a UFL value inside
    a history, an object) is bad input"""
    try:
        return json.dumps(cfg)
    except (TypeError, ValueError) as e:
        raise cpp.ConfigError(f"{source}: a value that is not a number, string, list or dict "
                              f"({e}): UFL values go directly under their key") from None


class Problem:
    """The model of piezocontact (docs/api.md) on a dolfinx mesh.

    mesh: a dolfinx Mesh of affine triangles (2D) or tetrahedra (3D); under
      MPI, ghosted by shared facets (GhostMode.shared_facet).
    facet_tags, cell_tags: dolfinx MeshTags naming boundaries and regions
      through boundary_names, region_names ({name: tag value}).
    material (one for the body) or regions ({region name: material}): a
      Material or a dict of the config's material keys.
    boundaries: {boundary name: Boundary or dict}.
    time: Time(T, steps) or {"T": s, "steps": n}.
    contact: Contact or dict, the law of boundaries with contact=True.
    loads: {"body_force": N/m^3, "charge_density": C/m^3}.
    formulation: "plane_strain" (default in 2D), "plane_stress", "axisymmetric".
    degree: the Lagrange degree of u and phi, or (u degree, phi degree).
    solver, probes, analysis, output, manufactured: the config's sections.
    extra_residual, contact_law: physics hooks (piezocontact.solve's).
    data: {config key: f(x, t)} (piezocontact.solve's), beside the UFL
      values given in loads and boundaries.

    Raises ConfigError with the config's one-line message (the key named as
    in a config) at construction: the C++ rules of the config and those of a
    config against its mesh."""

    def __init__(self, mesh, facet_tags=None, cell_tags=None, *, boundary_names=None,
                 region_names=None, boundaries, time, material=None, regions=None,
                 contact=None, loads=None, formulation=None, degree=None, solver=None,
                 probes=None, analysis=None, output=None, manufactured=None,
                 extra_residual=None, contact_law=None, data=None, source=SOURCE):
        self.source = source
        self.data = dict(data or {})
        cfg = {"mesh": {"type": "dolfinx"}}
        sections = dict(material=material, regions=regions, contact=contact,
                        formulation=formulation, solver=solver, probes=probes,
                        analysis=analysis, output=output, manufactured=manufactured)
        cfg.update({k: plain(v) for k, v in sections.items() if v is not None})
        cfg["time"] = plain(time)
        d = mesh.geometry.dim
        if loads is not None:
            cfg["loads"] = self._split_ufl(dict(loads), "loads", d)
        cfg["boundaries"] = {name: self._split_ufl(plain_boundary(b), f"boundaries.{name}", d)
                             for name, b in dict(boundaries).items()}
        if degree is not None:
            cfg["elements"] = ({"degree": degree} if isinstance(degree, int)
                               else dict(zip(("u", "phi"), degree)))
        # the mesh first: the config's rules may name what it lacks
        self.named = cpp.name_mesh(compat.cpp(mesh),
                                   None if facet_tags is None else compat.cpp(facet_tags),
                                   None if cell_tags is None else compat.cpp(cell_tags),
                                   dict(boundary_names or {}), dict(region_names or {}), source)
        self.config = json.loads(cpp.configure(_json(cfg, source), [], source))
        self._adopt(mesh, extra_residual, contact_law)

    def _adopt(self, mesh, extra_residual, contact_law):
        """The checks of the config against the mesh, and the hooks."""
        cpp.checked_config(json.dumps(self.config), self.named, mesh.comm, self.source)
        self.mesh = mesh
        self.extra_residual, self.contact_law = extra_residual, contact_law

    def _split_ufl(self, block, key, d):
        """The block with its UFL values moved to the data hook (a zero in
        their place, to which the hook's expression adds)."""
        taken = model.ufl_keys(d)
        generic = "boundaries.NAME" if key.startswith("boundaries.") else key
        out = {}
        for k, v in block.items():
            if not is_ufl(v):
                out[k] = plain(v)
                continue
            if f"{generic}.{k}" not in taken:
                raise _config_error(self.source, f"{key}.{k}",
                                    f"a UFL value is taken by {', '.join(taken)} only (else: "
                                    "a number, a history or an expression string)")
            self.data[f"{key}.{k}"] = as_function_of_x_t(v)
            out[k] = np.zeros(taken[f"{generic}.{k}"]).tolist()  # the UFL part adds to it
        return out

    @classmethod
    def from_config(cls, config, overrides=(), comm=MPI.COMM_WORLD, extra_residual=None,
                    contact_law=None, data=None):
        """The Problem of a config (a path or a dict) and its `--set`
        overrides: the mesh made as the config says (a gmsh or msh mesh in a
        temporary folder, removed once read)."""
        from .api import load
        cfg, source = load(config, overrides)
        scratch = comm.bcast(tempfile.mkdtemp(prefix="piezocontact-mesh-")
                             if comm.rank == 0 else None)
        try:
            mesh_file = cpp.prepare_mesh(json.dumps(cfg), source, scratch, comm,
                                         mesh_tools.convert)
            named = cpp.build_mesh(json.dumps(cfg), comm, mesh_file, source)
        finally:
            comm.barrier()
            if comm.rank == 0:
                shutil.rmtree(scratch, ignore_errors=True)
        problem = cls.__new__(cls)
        problem.source, problem.data, problem.config, problem.named = (
            source, dict(data or {}), cfg, named)
        problem._adopt(model.python_mesh(named), extra_residual, contact_law)
        return problem

    @property
    def facet_tags(self):
        """The boundaries' facet tags as the core numbers them (1 + the
        index of the name in sorted order): see tag_of."""
        return compat.meshtags(self.named.facet_tags)

    @property
    def cell_tags(self):
        return compat.meshtags(self.named.cell_tags)

    @property
    def tag_of(self):
        """{boundary name: its value in facet_tags}"""
        return dict(self.named.tag_of)

    @property
    def region_of(self):
        """{region name: its value in cell_tags}"""
        return dict(self.named.region_of)

    def solve(self, engine="cpp", output=None, observer=None, progress=False):
        """Run the model: engine "cpp" (the C++ time loop on JIT-compiled
        forms) or "reference" (the independent engine). output: a folder
        for the files (summary.json, XDMF, checkpoints: as
        piezocontact.solve), or None to write nothing. observer(Step):
        called after each accepted step, on every process. Returns a
        Solution; raises ConfigError, NewtonFailure, OutputError,
        Interrupted (the run's summary then says how far it came)."""
        keep = []
        summary = run(self.config, self.source, output, engine, keep, progress,
                      self._observer(observer, keep),
                      model.factory(self.extra_residual, self.contact_law, keep,
                                    self.data, self.mesh),
                      self.mesh.comm, self.named)
        return Solution(summary, *_state(keep[-1].x))

    @staticmethod
    def _observer(observer, keep):
        """The driver's observer (n, record) of a user's observer(Step)."""
        if observer is None:
            return None

        def on_step(n, record):
            observer(Step(n, record["t"], *_state(keep[-1].x), record))
        return on_step


def plain_boundary(b):
    """A Boundary or dict as a dict, its values kept (UFL ones too)."""
    if hasattr(b, "config"):
        return {k: v for k, v in vars(b).items() if v is not None}
    return dict(b)


def run(cfg, source, output, engine, keep, progress, observer, factory, comm, mesh=None):
    """The one way into the core's driver from Python: a validated config,
    on its own mesh or on `mesh` (a NamedMesh); output None: in memory.
    observer(n, record dict). Returns the summary."""
    from . import api
    loop = api.engine_loop(engine, keep, observer)
    on_step = None
    if observer is not None and loop is None:
        def on_step(n, record):
            observer(n, json.loads(record))
    if output is not None:
        cpp.prepare_output(str(output), source, comm)
    summary = cpp.run_config(json.dumps(cfg), "" if output is None else str(output), source,
                             api.ENGINES[engine], progress, None, comm, factory, mesh_tools.convert,
                             loop, on_step, api.engine_analysis(engine, keep), mesh)
    return json.loads(summary)
