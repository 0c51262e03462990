"""Compare two runs (e.g. the C++ engine and the reference) of the same config: probe values at
every step and the relative L2 difference of the u and phi fields.

Fields are compared as finite element functions: the nodal values each solver
wrote (DIR/nodal) are matched to the dofs of the config's mesh by coordinates
(so serial and MPI runs compare too) and ||a - b||_L2 / ||b||_L2 is assembled.
"""

import json
from pathlib import Path

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from . import cpp
from ._compat import functionspace, meshtags
from .model import python_mesh


def load_summary(out_dir):
    return json.loads((Path(out_dir) / "summary.json").read_text())


def rel(a, b):
    """|a - b| / |b| with a floor so that two zeros agree."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.max(np.abs(a - b) / np.maximum(np.abs(b), 1e-300)))


def probe_differences(run, ref):
    """Largest relative difference of each probe quantity over all steps,
    relative to the largest magnitude of that quantity at that probe."""
    out = []
    for i, p in enumerate(ref["steps"][0]["probes"]):
        worst = {"point": p["point"], "u": 0.0, "phi": 0.0}
        for key in ("u", "phi"):
            a = np.array([s["probes"][i][key] for s in run["steps"]], float)
            b = np.array([s["probes"][i][key] for s in ref["steps"]], float)
            scale = max(np.max(np.abs(b)), 1e-300)
            worst[key] = float(np.max(np.abs(a - b)) / scale)
        out.append(worst)
    return out


# Agreement of two engines: each quantity against its run-wide size (the
# largest magnitude it takes over the run's steps: probes per field, a force,
# a reaction, an electrode's charge), and value by value against the value,
# floored at VALUE_FLOOR of that size (a value at the round-off of its
# quantity, phi on a grounded electrode, has no relative difference)
VALUE_FLOOR = 1e-3


def step_quantities(summary):
    """{quantity: array (steps, components)} of every compared output."""
    steps = summary.get("steps", [])
    if not steps:  # an analysis about the initial state: no time loop
        return {}
    out = {"probes.u": [[c for p in s["probes"] for c in p["u"]] for s in steps],
           "probes.phi": [[p["phi"] for p in s["probes"]] for s in steps],
           "contact_force": [s["contact_force"] for s in steps]}
    if steps[0].get("max_penetration") is not None:  # null without a contact boundary
        out["max_penetration"] = [[s["max_penetration"]] for s in steps]
    for name, c in steps[0].get("contacts", {}).items():  # each obstacle's
        for key in c:
            out[f"contacts.{name}.{key}"] = [np.ravel([s["contacts"][name][key]]) for s in steps]
    for name in steps[0].get("spring_force", {}):
        out[f"spring_force.{name}"] = [s["spring_force"][name] for s in steps]
    for name in steps[0].get("reactions", {}):
        out[f"reactions.{name}"] = [s["reactions"][name] for s in steps]
    for name, e in steps[0].get("electrodes", {}).items():
        for key in ("potential", "charge", "reaction_charge", "current"):
            if key in e:
                out[f"electrodes.{name}.{key}"] = [[s["electrodes"][name][key]] for s in steps]
    return {k: np.asarray(v, float).reshape(len(steps), -1) for k, v in out.items()}


def analysis_quantities(summary):
    """{quantity: array} of a dynamic analysis's outputs: each mode's
    omega^2 (a rigid mode's is round-off of 0: measured against the
    largest), and per frequency each electrode's complex charge, potential
    and admittance and the probes' complex u and phi ([re, im] columns).
    The modes' charges per unit amplitude are not compared here: their sign
    follows each engine's shape."""
    out = {}
    if "modes" in summary:
        out["modes.eigenvalue"] = [[m["eigenvalue"]] for m in summary["modes"]]
    harmonic = summary.get("harmonic", [])
    if harmonic:
        for name, e in harmonic[0]["electrodes"].items():
            for key in ("charge", "potential", "admittance"):
                if key in e:
                    out[f"harmonic.{name}.{key}"] = [h["electrodes"][name][key] for h in harmonic]
        out["harmonic.probes.u"] = [np.ravel([p["u"] for p in h["probes"]]) for h in harmonic]
        out["harmonic.probes.phi"] = [np.ravel([p["phi"] for p in h["probes"]]) for h in harmonic]
    return {k: np.asarray(v, float).reshape(len(v), -1) for k, v in out.items()}


def agreement(run, ref):
    """{quantity: (largest |a - b| / run-wide size, largest value-by-value
    relative difference)} over every step of two runs of one config. A force
    (contact force, a reaction, a bed's force) is a sum of nodal forces: its size is at
    least that of the forces the supports carry (`support_force`, the sum
    of |nodal reaction|), of which its round-off is (a clamp that holds a
    body loaded only electrically has a net reaction of 1e-15 N/m)."""
    qa = {**step_quantities(run), **analysis_quantities(run)}
    qb = {**step_quantities(ref), **analysis_quantities(ref)}
    if len(run.get("steps", [])) != len(ref.get("steps", [])) or set(qa) != set(qb) \
            or any(qa[k].shape != qb[k].shape for k in qb):
        raise ValueError("the runs have different steps or outputs")
    supported = max((s.get("support_force", 0.0) for s in ref.get("steps", [])), default=0.0)
    # an electrode quantity is measured against the largest of its kind
    # (an open circuit's charge is zero to the round-off of the others')
    kind = {key: key.rsplit(".", 1)[1].replace("reaction_charge", "charge")
            for key in qb if key.startswith("electrodes.")}
    kind_size = {}
    for key, k in kind.items():
        kind_size[k] = max(kind_size.get(k, 0.0), float(np.max(np.abs(qb[key]))))
    out = {}
    for key, b in qb.items():
        a = qa[key]
        size = float(np.max(np.abs(b), initial=0.0))
        if key == "contact_force" or key.startswith(("reactions.", "spring_force.")) \
                or key.endswith(".force"):
            size = max(size, supported)
        if key in kind:
            size = kind_size[kind[key]]
        if key.endswith("max_penetration"):  # ~0 under Nitsche: measured against u's size
            size = max(size, float(np.max(np.abs(qb["probes.u"]), initial=0.0)))
        diff = np.abs(a - b)
        if size == 0.0:
            out[key] = (float(np.max(diff, initial=0.0)), float(np.max(diff, initial=0.0)))
            continue
        floor = np.maximum(np.abs(b), VALUE_FLOOR * size)
        out[key] = (float(np.max(diff)) / size, float(np.max(diff / floor)))
    return out


def worst_agreement(run, ref):
    """(quantity, of size, value by value): the largest of each metric."""
    table = agreement(run, ref)
    of_size = max(table.items(), key=lambda kv: kv[1][0])
    by_value = max(table.items(), key=lambda kv: kv[1][1])
    return of_size[0], of_size[1][0], by_value[0], by_value[1][1]


class FieldComparer:
    """P1 functions on the config's mesh filled from nodal files."""

    def __init__(self, cfg, mesh_file=None, comm=MPI.COMM_SELF):
        self.named = cpp.build_mesh(json.dumps(cfg), comm, mesh_file)
        self.mesh = python_mesh(self.named)
        self.facet_tags, self.tag_of = meshtags(self.named.facet_tags), self.named.tag_of
        self.dim = self.mesh.geometry.dim
        degree_u, degree_phi = cpp.model_spec(json.dumps(cfg)).degrees  # the core's reading
        self.V = {"u": functionspace(self.mesh, ("Lagrange", degree_u, (self.dim,))),
                  "phi": functionspace(self.mesh, ("Lagrange", degree_phi))}
        self._order = {f: self._lexorder(V.tabulate_dof_coordinates()[:, :self.dim])
                       for f, V in self.V.items()}

    @staticmethod
    def _lexorder(x):
        key = np.round(x, 12)
        return np.lexsort(key.T[::-1])

    def function(self, nodal_file, field):
        rows = np.load(nodal_file)
        V = self.V[field]
        f = fem.Function(V)
        dofs = self._order[field]
        d = self.dim
        src = self._lexorder(rows[:, :d])
        if len(src) != len(dofs) or not np.allclose(
                rows[src, :d], V.tabulate_dof_coordinates()[dofs, :d], atol=1e-12):
            raise ValueError(f"{nodal_file}: nodes do not match the mesh of the config")
        bs = V.dofmap.index_map_bs
        f.x.array.reshape(-1, bs)[dofs] = rows[src, d:]
        return f

    def relative_l2(self, file_a, file_b, field):
        a, b = self.function(file_a, field), self.function(file_b, field)
        diff = fem.form(ufl.inner(a - b, a - b) * ufl.dx)
        norm = fem.form(ufl.inner(b, b) * ufl.dx)
        d, n = fem.assemble_scalar(diff), fem.assemble_scalar(norm)
        return float(np.sqrt(d / n)) if n > 0 else float(np.sqrt(d))


def field_differences(dir_a, dir_b, summary):
    """{step: {"u": rel L2, "phi": rel L2}} for every step both runs wrote,
    on the mesh of run `summary` (the reference's)."""
    comparer = FieldComparer(summary["config"], summary.get("mesh_file"))
    out = {}
    for fa in sorted((Path(dir_a) / "nodal").glob("u_*.npy")):
        step = fa.stem.split("_")[1]
        if not (Path(dir_b) / "nodal" / fa.name).exists():
            continue
        out[int(step)] = {f: comparer.relative_l2(Path(dir_a) / "nodal" / f"{f}_{step}.npy",
                                                  Path(dir_b) / "nodal" / f"{f}_{step}.npy", f)
                          for f in ("u", "phi")}
    return out


def table(run, ref, names=("C++", "reference")):
    """Side-by-side probe values at the final time, as text."""
    a, b = run["steps"][-1], ref["steps"][-1]
    lines = [f"probe values at t = {b['t']:g}",
             f"{'point':>12} {'quantity':>8} {names[0]:>24} {names[1]:>24} {'rel. diff':>10}"]
    for pa, pb in zip(a["probes"], b["probes"]):
        pt = f"({pb['point'][0]:g}, {pb['point'][1]:g})"
        for label, va, vb in (("u_x", pa["u"][0], pb["u"][0]), ("u_y", pa["u"][1], pb["u"][1]),
                              ("phi", pa["phi"], pb["phi"])):
            lines.append(f"{pt:>12} {label:>8} {va:>24.16e} {vb:>24.16e} "
                         f"{abs(va - vb) / max(abs(vb), 1e-300):>10.1e}")
    return "\n".join(lines)
