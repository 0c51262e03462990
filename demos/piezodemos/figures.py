"""Pictures of a run, as PNG (matplotlib, headless), after the paper's
Figures 5-7: drawn from what a solver wrote (nodal values, summary.json),
with D, the stress and the nodal contact forces evaluated by the forms of
forms/piezo_forms.py on those values, not re-derived here."""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import dolfinx.fem.petsc  # noqa: E402, F401  (0.9 does not import it with dolfinx.fem)
import numpy as np  # noqa: E402
import ufl  # noqa: E402
from dolfinx import fem  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

from piezocontact._compat import dofmap_array, functionspace  # noqa: E402
from piezocontact.model import model_constants, pf, set_constants  # noqa: E402

from piezocontact import compare  # noqa: E402


class RunState:
    """The final state of a run on its mesh: u, phi, and what the forms give."""

    def __init__(self, out_dir, summary):
        cfg = summary["config"]
        self.summary, self.cfg = summary, cfg
        fields = compare.FieldComparer(cfg, summary.get("mesh_file"))
        msh = fields.mesh
        n = len(summary["steps"])
        nodal = Path(out_dir) / "nodal"
        u = fields.function(nodal / f"u_{n:04d}.npy", "u")
        phi = fields.function(nodal / f"phi_{n:04d}.npy", "phi")
        previous = nodal / f"u_{n - 1:04d}.npy"
        # the viscous stress needs u_{N-1}; without it (output.nodal=final) the
        # stress shown is the elastic + piezoelectric part only
        self.viscous = previous.exists() or n == 1
        u_prev = fields.function(previous, "u") if previous.exists() else u
        data, materials, loads = model_constants(msh, fields.named)
        set_constants(cfg, data, materials, loads)
        (mat,) = materials.values()  # the contactor: one material

        V, Vu = fields.V["phi"], fields.V["u"]
        cells = dofmap_array(V)
        assert np.array_equal(cells, dofmap_array(Vu)), \
            "scalar and vector P1 dofmaps differ"
        self.x = V.tabulate_dof_coordinates()[:, :2]
        self.cells = cells
        self.u = u.x.array.reshape(-1, 2).copy()
        self.phi = phi.x.array.copy()

        midpoint = np.array([[1.0 / 3.0, 1.0 / 3.0]])
        D = fem.Function(functionspace(msh, ("DG", 0, (2,))))
        D.interpolate(fem.Expression(pf.electric_displacement(u, phi, mat), midpoint))
        self.D = D.x.array.reshape(-1, 2).copy()
        stress = fem.Function(functionspace(msh, ("DG", 0, (3,))))
        sigma = pf.stress_voigt(u, pf.velocity(u, u_prev, data), phi, mat)
        stress.interpolate(fem.Expression(sigma, midpoint))
        s = stress.x.array.reshape(-1, 3)
        # von Mises of the in-plane total stress (the plane model carries no s_zz)
        self.von_mises = np.sqrt(s[:, 0] ** 2 - s[:, 0] * s[:, 1] + s[:, 1] ** 2
                                 + 3 * s[:, 2] ** 2)

        ds = ufl.Measure("ds", domain=msh, subdomain_data=fields.facet_tags)
        gamma_c = tuple(fields.tag_of[b] for b, bc in cfg["boundaries"].items() if bc.get("contact"))
        contact = pf.contact_term(u, ufl.TestFunction(Vu), ufl.FacetNormal(msh), ds(gamma_c), data)
        self.contact_force = -fem.petsc.assemble_vector(fem.form(contact)).array.reshape(-1, 2)
        # length of Gamma_C where u.nu > g (fine quadrature: the indicator is discontinuous)
        n = ufl.FacetNormal(msh)
        fine = ds(metadata={"quadrature_degree": 10})
        self.contact_length = fem.assemble_scalar(fem.form(
            ufl.conditional(ufl.gt(pf.gap_function(u, n, data), 0), 1.0, 0.0) * fine(gamma_c)))

    def deformed(self, scale):
        return self.x + scale * self.u

    def amplification(self, fraction=0.1):
        """A power of ten that shows the largest displacement as up to
        `fraction` of the body's size."""
        umax = np.abs(self.u).max()
        if umax == 0:
            return 1.0
        return float(10 ** np.floor(np.log10(fraction * np.ptp(self.x, axis=0).max() / umax)))


def _finish(fig, ax, path, title):
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def deformed_mesh(state, path, note=""):
    """Figure 5: initial and amplified deformed mesh, contact forces on Gamma_C."""
    A = state.amplification()
    fig, ax = plt.subplots(figsize=(6.4, 7.2))
    ax.triplot(Triangulation(*state.x.T, state.cells), color="0.75", lw=0.4)
    xd = state.deformed(A)
    ax.triplot(Triangulation(*xd.T, state.cells), color="tab:blue", lw=0.5)
    f = state.contact_force
    active = np.linalg.norm(f, axis=1) > 0
    if active.any():
        q = ax.quiver(*xd[active].T, *f[active].T, color="tab:red", angles="xy",
                      scale_units="xy", scale=np.abs(f[active]).max() / 0.25, width=0.004)
        ax.quiverkey(q, 0.75, 0.04, np.abs(f[active]).max(),
                     f"{np.abs(f[active]).max():.2g} N/m nodal contact force",
                     labelpos="W", fontproperties={"size": 8})
    ax.text(0.02, 0.98, f"displacements amplified x {A:.0e}\n{note}", transform=ax.transAxes,
            va="top", fontsize=9, bbox={"fc": "white", "ec": "0.7"})
    _finish(fig, ax, path, "Initial (grey) and deformed (blue) mesh, contact forces (red)")


def electric(state, path):
    """Figure 6: D as arrows over phi in colour, on the deformed body."""
    A = state.amplification()
    xd = state.deformed(A)
    tri = Triangulation(*xd.T, state.cells)
    fig, ax = plt.subplots(figsize=(6.4, 7.2))
    pc = ax.tripcolor(tri, state.phi, shading="gouraud", cmap="viridis")
    fig.colorbar(pc, ax=ax, label="electric potential phi (V)", shrink=0.8)
    mid = xd[state.cells].mean(axis=1)
    step = max(1, len(mid) // 350)
    ax.quiver(*mid[::step].T, *state.D[::step].T, color="white", angles="xy",
              pivot="mid", width=0.003)
    ax.text(0.02, 0.98, f"displacements amplified x {A:.0e}\n"
            f"|D| up to {np.linalg.norm(state.D, axis=1).max():.2e} C/m^2",
            transform=ax.transAxes, va="top", fontsize=9, bbox={"fc": "white", "ec": "0.7"})
    _finish(fig, ax, path, "Electric displacement D (arrows) and potential (colour)")


def stress(state, path):
    """Figure 7: von Mises of the in-plane total stress on the deformed body."""
    A = state.amplification()
    xd = state.deformed(A)
    fig, ax = plt.subplots(figsize=(6.4, 7.2))
    pc = ax.tripcolor(Triangulation(*xd.T, state.cells), facecolors=state.von_mises,
                      cmap="inferno")
    fig.colorbar(pc, ax=ax, label="von Mises stress (Pa)", shrink=0.8)
    what = "total" if state.viscous else "elastic + piezoelectric"
    ax.text(0.02, 0.98, f"displacements amplified x {A:.0e}\nin-plane {what} stress\n"
            "sqrt(sxx^2 - sxx syy + syy^2 + 3 sxy^2)", transform=ax.transAxes, va="top",
            fontsize=8, bbox={"fc": "white", "ec": "0.7"})
    _finish(fig, ax, path, "Von Mises stress on the deformed body")


def history(summary, path):
    """Largest normal displacement on Gamma_C against the gap, and the
    total contact force, over time."""
    g = summary["config"]["contact"]["gap"]
    varies = isinstance(g, str)  # an expression of x: the penetration against 0
    t = [0.0] + [s["t"] for s in summary["steps"]]  # u_0 = 0
    un = np.array([0.0 if not varies else summary["steps"][0]["max_penetration"]]
                  + [s["max_penetration"] + (0.0 if varies else g) for s in summary["steps"]])
    force = [0.0] + [np.linalg.norm(s["contact_force"]) for s in summary["steps"]]
    fig, (a, b) = plt.subplots(2, 1, figsize=(6.4, 5.6), sharex=True)
    if not varies and g > 100 * un.max() > 0:  # the gap dwarfs the motion: a log axis
        a.set_yscale("log")
        t, un, force = t[1:], un[1:], force[1:]
    a.plot(t, un, label="max (u.nu - g) on Gamma_C" if varies else "max u.nu on Gamma_C")
    a.axhline(0.0 if varies else g, color="tab:red", ls="--",
              label=f"contact, g = {g}" if varies else f"gap g = {g:g} m")
    a.set_ylabel("normal displacement (m)")
    a.legend(fontsize=8)
    b.plot(t, force, color="tab:green")
    b.set_ylabel("|contact force| (N/m)")
    b.set_xlabel("t (s)")
    a.set_title("Gamma_C over time", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def all_figures(out_dir, summary, fig_dir, note=""):
    fig_dir = Path(fig_dir)
    fig_dir.mkdir(parents=True, exist_ok=True)
    state = RunState(out_dir, summary)
    paths = {name: fig_dir / f"{name}.png" for name in
             ("deformed_mesh", "electric", "stress", "history")}
    deformed_mesh(state, paths["deformed_mesh"], note)
    electric(state, paths["electric"])
    stress(state, paths["stress"])
    history(summary, paths["history"])
    return state, paths
