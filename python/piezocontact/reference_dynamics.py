"""Dynamic analyses in the reference engine: an independent check of the
C++ core's (cpp/piezocontact/dynamics.h).

The same linearisation (the forms: JitModel.linearised_whole, one form each
for K, C and M, summed by UFL), assembled by stock dolfinx (or dolfinx_mpc
with floating electrodes: the multi-point constraint of floating_mpc.py,
where the C++ core merges dofs with a prolongation P^T K P), solved by
slepc4py and petsc4py with choices of its own:
  * modal: K with its electric rows negated (a Hermitian pencil, as the
    core's), shift-and-invert at the target or just below 0 (a shift of
    its own scale), Krylov-Schur; a non-Hermitian one condensed on the dofs
    with mass by a petsc4py Python matrix;
  * harmonic: the real block system built by petsc4py's MatNest, lifted
    from unconstrained matrices by dolfinx's own set_bc.
Nothing is shared with the core but the forms, the electrodes' dofs, the
reaction charges (a sum over them) and the probes."""

import json
import math
import os

import dolfinx.fem.petsc  # noqa: F401
import numpy as np
from dolfinx import fem
from petsc4py import PETSc

from . import cpp
from ._compat import create_petsc_vector, dirichletbcs, mpc_backsubstitution, petsc_vec

TWO_PI = 2 * math.pi


class _Assembly:
    """The linearisation's matrices and vectors, constrained as the
    reference engine constrains them (dolfinx bcs; dolfinx_mpc for floating
    electrodes), and unconstrained on the full space (reactions)."""

    def __init__(self, model, problem):
        self.model, self.problem = model, problem
        model.x_dot.x.array[:] = 0.0  # the state at rest
        self.K_form, self.C_form, self.M_form = model.linearised_whole()
        self.floating = None
        self.bcs = dirichletbcs(problem.fixed_bcs)
        if any(e.floating for e in problem.electrodes):
            from .floating_mpc import FloatingConstraint
            self.floating = FloatingConstraint(model.x, problem, None, None)

    def matrix(self, form, diagonal):
        """A constrained matrix: Dirichlet (and slave) rows and columns
        zero, `diagonal` on them."""
        if self.floating:
            import dolfinx_mpc
            A = dolfinx_mpc.assemble_matrix(form, self.floating.mpc, bcs=self.bcs,
                                            diagval=diagonal)
        else:
            A = fem.petsc.assemble_matrix(form, self.bcs, diagonal)  # keyword: _compat
        A.assemble()
        return A

    def full_matrix(self, form):
        """Unconstrained, on the full space."""
        A = fem.petsc.assemble_matrix(form)
        A.assemble()
        return A

    def matrix_unconstrained(self, form):
        """On the constrained space, without Dirichlet conditions (the
        lifting of prescribed values)."""
        if self.floating:
            import dolfinx_mpc
            A = dolfinx_mpc.assemble_matrix(form, self.floating.mpc, bcs=[], diagval=0.0)
            A.assemble()
            return A
        return self.full_matrix(form)

    def full_load(self):
        """The applied loads on the full space (owned entries)."""
        out = np.zeros(self.owned())
        for f in self.model.L:
            b = fem.petsc.assemble_vector(f)
            b.ghostUpdate(PETSc.InsertMode.ADD, PETSc.ScatterMode.REVERSE)
            out += b.getArray(readonly=True)[:out.size]
        return out

    def vector(self, forms):
        """The sum of linear forms, constrained space (ghosts added)."""
        if self.floating:
            import dolfinx_mpc
            b = self.floating.create_vector()
            for f in forms:
                b.axpy(1.0, dolfinx_mpc.assemble_vector(f, self.floating.mpc))
        else:
            b = create_petsc_vector(self.model.W.dofmap.index_map,
                                       self.model.W.dofmap.index_map_bs)
            b.set(0.0)
            for f in forms:
                b.axpy(1.0, fem.petsc.assemble_vector(f))
        b.ghostUpdate(PETSc.InsertMode.ADD, PETSc.ScatterMode.REVERSE)
        return b

    def full(self, z):
        """The full x (owned entries) of a vector of the constrained space."""
        f = self.floating
        if not f:
            return z.getArray(readonly=True).copy()
        full = petsc_vec(f._full)
        z.copy(full)
        full.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        mpc_backsubstitution(f.mpc, f._full)
        return full.getArray(readonly=True)[:self.owned()].copy()

    def owned(self):
        imap = self.model.W.dofmap.index_map
        return imap.size_local * self.model.W.dofmap.index_map_bs

    def reactions(self, K0, x, L=None):
        """K0 x - L on the full space (owned entries)."""
        v = K0.createVecRight()
        v.setArray(x)
        r = K0.createVecLeft()
        K0.mult(v, r)
        out = r.getArray(readonly=True).copy()
        return out - L if L is not None else out


def _write_summary(comm, output, summary):
    if comm.rank == 0 and output:  # '': a run kept in memory
        path = os.path.join(output, "summary.json")
        with open(path + ".tmp", "w") as f:
            json.dump(summary, f, indent=1)
        os.replace(path + ".tmp", path)


def _negate_electric_rows(a, K):
    """K with its electric rows negated (its Dirichlet rows after: their
    diagonal stays 1): symmetric, so that the pencil is Hermitian and
    SLEPc purifies the eigenvectors of M's null space (phi, the removed
    dofs). Without it (a non-Hermitian pencil, M singular), Krylov-Schur's
    vectors carry components of the infinite eigenvalues' Jordan chains:
    measured, 0.2 % off on the first mode and 7 % on the second."""
    sign = K.createVecLeft()
    sign.set(1.0)
    n = sign.getLocalSize()
    phi = np.asarray(a.problem.phi_dofs)
    values = sign.getArray()
    values[phi[phi < n]] = -1.0
    sign.setArray(values)
    K.diagonalScale(L=sign)  # a removed phi dof's diagonal becomes -1: still infinite
    return K


def _symmetric(K):
    D = K.copy()
    D.axpy(-1.0, K.transpose(PETSc.Mat()),  # a new matrix: transpose() alone is in place
           structure=PETSc.Mat.Structure.DIFFERENT_NONZERO_PATTERN)
    return D.norm(PETSc.NormType.FROBENIUS) <= 1e-12 * K.norm(PETSc.NormType.FROBENIUS)


class _Condensed:
    """A non-Hermitian pencil (Nitsche on a piezoelectric contact boundary)
    as a standard problem on the dofs with mass: v -> R (K - sigma M)^-1 M E v
    (a petsc4py Python matrix; the core has its own, modal.cpp)."""

    def __init__(self, K, M, sigma):
        A = K.copy()
        A.axpy(-sigma, M, structure=PETSc.Mat.Structure.DIFFERENT_NONZERO_PATTERN)
        self.ksp = PETSc.KSP().create(K.getComm())
        self.ksp.setOptionsPrefix("piezocontact_reference_condensed_")
        self.ksp.setType("preonly")
        self.ksp.getPC().setType("lu")
        self.ksp.getPC().setFactorSolverType("mumps")
        self.ksp.setOperators(A)
        self.M, self.A = M, A
        start = M.getOwnershipRange()[0]
        d = M.getDiagonal().getArray()
        self.U = PETSc.IS().createGeneral((start + np.flatnonzero(d > 0)).astype(PETSc.IntType),
                                          comm=K.getComm())
        self.full_in, self.full_out = K.createVecs()
        self.Min = K.createVecLeft()

    def mult(self, mat, v, y):
        self.full_in.set(0.0)
        self.full_in.isaxpy(self.U, 1.0, v)
        self.M.mult(self.full_in, self.Min)
        self.ksp.solve(self.Min, self.full_out)
        if self.ksp.getConvergedReason() < 0:
            raise RuntimeError("singular K - sigma M")
        y.array_w[:] = self.full_out.getValues(self.U.getIndices())

    def matrix(self):
        n = self.U.getLocalSize()
        S = PETSc.Mat().createPython(((n, None), (n, None)), self, comm=self.M.getComm())
        S.setUp()
        return S


def _modes(a, settings):
    from slepc4py import SLEPc
    K, M = _negate_electric_rows(a, a.matrix(a.K_form, 1.0)), a.matrix(a.M_form, 0.0)
    target = settings.analysis.target
    sigma = ((TWO_PI * target) ** 2 if target is not None
             else -1e-6 * K.norm(PETSc.NormType.INFINITY) / M.norm(PETSc.NormType.INFINITY))
    eps = SLEPc.EPS().create(K.getComm())
    eps.setDimensions(settings.analysis.modes)
    eps.setTolerances(1e-12, 500)
    condensed = None
    if _symmetric(K):
        eps.setOptionsPrefix("piezocontact_reference_modal_")
        eps.setOperators(K, M)
        eps.setProblemType(SLEPc.EPS.ProblemType.GHEP)
        eps.setTarget(sigma)
        eps.setWhichEigenpairs(SLEPc.EPS.Which.TARGET_MAGNITUDE)
        st = eps.getST()
        st.setType(SLEPc.ST.Type.SINVERT)
        ksp = st.getKSP()
        ksp.setType("preonly")
        ksp.getPC().setType("lu")
        ksp.getPC().setFactorSolverType("mumps")
    else:
        condensed = _Condensed(K, M, sigma)
        S = condensed.matrix()
        eps.setOptionsPrefix("piezocontact_reference_condensed_")
        eps.setOperators(S)
        eps.setProblemType(SLEPc.EPS.ProblemType.NHEP)
        eps.setWhichEigenpairs(SLEPc.EPS.Which.LARGEST_MAGNITUDE)
    eps.solve()
    out = []
    Mz = K.createVecLeft()
    for i in range(min(eps.getConverged(), settings.analysis.modes)):
        if condensed is None:
            z = K.createVecRight()
            lam = eps.getEigenpair(i, z).real
        else:
            v = S.createVecRight()
            theta = eps.getEigenpair(i, v).real
            lam = sigma + 1.0 / theta
            condensed.mult(S, v, v.duplicate())
            z = condensed.full_out.copy()
            z.scale(1.0 / theta)
        M.mult(z, Mz)
        z.scale(1.0 / math.sqrt(abs(z.dot(Mz))))
        x = a.full(z)
        comm = K.getComm().tompi4py()
        big = comm.allgather((float(np.max(np.abs(x), initial=0.0)),
                              float(x[np.argmax(np.abs(x))]) if x.size else 0.0))
        sign = math.copysign(1.0, max(big, key=lambda p: p[0])[1])
        out.append((lam, sign * x, eps.computeError(i, SLEPc.EPS.ErrorType.RELATIVE)))
    out.sort(key=lambda m: m[0])
    return out


def modal(a, problem, settings, output, summary):
    K0 = a.full_matrix(a.K_form)
    modes = _modes(a, settings)
    names = [e.name for e in problem.electrodes]
    listed = []
    for lam, x, error in modes:
        Q = problem.reaction_charges(a.reactions(K0, x))
        V = problem.electrode_potentials(x)
        listed.append({"frequency": math.copysign(math.sqrt(abs(lam)), lam) / TWO_PI,
                       "eigenvalue": lam, "error": error,
                       "electrodes": {n: {"charge": q, "potential": v}
                                      for n, q, v in zip(names, Q, V)}})
    summary["modes"] = listed
    if len(modes) < settings.analysis.modes:
        summary["status"] = "failed"
        summary["error"] = (f"the eigensolver converged {len(modes)} of the "
                            f"{settings.analysis.modes} modes asked for (reference engine)")
    return summary


def _block_solve(Kw, Cw, b_re, b_im):
    """[Kw -Cw; Cw Kw] [x_re; x_im] = [b_re; b_im] by MUMPS."""
    minus = Cw.copy()
    minus.scale(-1.0)
    nest = PETSc.Mat().createNest([[Kw, minus], [Cw, Kw]], comm=Kw.getComm())
    A = nest.convert("aij")
    # the nest's numbering: on each rank, its rows of block 0, then of block 1
    start, n = A.getOwnershipRange()[0], Kw.getLocalSize()[0]
    rows = [PETSc.IS().createStride(n, start + k * n, 1, comm=Kw.getComm()) for k in (0, 1)]
    b, x = A.createVecLeft(), A.createVecRight()
    for part, v in zip(rows, (b_re, b_im)):
        sub = b.getSubVector(part)
        v.copy(sub)
        b.restoreSubVector(part, sub)
    ksp = PETSc.KSP().create(Kw.getComm())
    ksp.setOptionsPrefix("piezocontact_reference_harmonic_")
    ksp.setType("preonly")
    ksp.getPC().setType("lu")
    ksp.getPC().setFactorSolverType("mumps")
    ksp.setOperators(A)
    ksp.solve(b, x)
    if ksp.getConvergedReason() < 0:
        raise cpp.NewtonFailure("the harmonic system is singular (reference engine)")
    parts = []
    for part in rows:
        sub = x.getSubVector(part)
        parts.append(sub.copy())
        x.restoreSubVector(part, sub)
    return parts


def harmonic(a, problem, settings, output, summary, source):
    model = a.model
    K, C, M = (a.matrix(f, d) for f, d in ((a.K_form, 1.0), (a.C_form, 0.0), (a.M_form, 0.0)))
    K0, C0, M0 = (a.matrix_unconstrained(f) for f in (a.K_form, a.C_form, a.M_form))
    L = a.vector(model.L) if model.L else None
    # the prescribed values, by dolfinx's set_bc on a zero vector
    g = K.createVecRight()
    g.set(0.0)
    fem.petsc.set_bc(g, a.bcs)
    charges = problem.target_charges()
    F = g.duplicate()
    F.set(0.0)
    if L is not None:
        L.copy(F)
    if a.floating:
        for i, row in zip(a.floating.index, a.floating.master_row):
            if row is not None:
                with F.localForm() as local:
                    local.array_w[row] -= charges[i]
    if F.norm(PETSc.NormType.INFINITY) == 0 and g.norm(PETSc.NormType.INFINITY) == 0:
        raise cpp.ConfigError(f"{source}: analysis.harmonic: nothing is driven (give a load, a "
                              "prescribed displacement or potential, or a floating electrode's "
                              "charge: their values are the amplitudes)")
    Kg, Cg, Mg = (A.createVecLeft() for A in (K0, C0, M0))
    for A, v in ((K0, Kg), (C0, Cg), (M0, Mg)):
        A.mult(g, v)
    K_full = a.full_matrix(a.K_form)
    L_full = a.full_load()
    names = [e.name for e in problem.electrodes]
    fixed_V = problem.electrode_potentials(g.getArray(readonly=True)[:a.owned()].copy()
                                           if not a.floating else a.full(g))
    probes = cpp.Probes(problem, settings.probes, source)
    listed = []
    for f in settings.analysis.frequencies:
        w = TWO_PI * f
        Kw = K.copy()
        Kw.axpy(-w * w, M, structure=PETSc.Mat.Structure.DIFFERENT_NONZERO_PATTERN)
        Cw = C.copy()
        Cw.scale(w)
        b_re = F.copy()
        b_re.axpy(-1.0, Kg)
        b_re.axpy(w * w, Mg)
        b_im = Cg.copy()
        b_im.scale(-w)
        fem.petsc.set_bc(b_re, a.bcs)   # x = g on Dirichlet dofs
        fem.petsc.set_bc(b_im, a.bcs, None, 0.0)  # scale (0.5), alpha (0.9): positional
        x_re, x_im = _block_solve(Kw, Cw, b_re, b_im)
        x_re, x_im = a.full(x_re), a.full(x_im)
        Qr = problem.reaction_charges(a.reactions(K_full, x_re, L_full))
        Qi = problem.reaction_charges(a.reactions(K_full, x_im))
        Vr, Vi = problem.electrode_potentials(x_re), problem.electrode_potentials(x_im)
        electrodes = {}
        for e, name in enumerate(names):
            Q = complex(Qr[e], Qi[e])
            current = 1j * w * Q
            entry = {"charge": [Q.real, Q.imag], "current": [current.real, current.imag],
                     "potential": [Vr[e], Vi[e]]}
            if not problem.electrodes[e].floating and fixed_V[e] != 0.0:
                Y = -current / fixed_V[e]  # the circuit's (dynamics.cpp)
                entry["admittance"] = [Y.real, Y.imag]
            electrodes[name] = entry
        values = []
        for x in (x_re, x_im):
            model.x.x.array[:x.size] = x
            model.x.x.scatter_forward()
            problem.update_fields()
            values.append(probes.evaluate(problem))
        d = model.mesh.geometry.dim
        listed.append({"frequency": f, "electrodes": electrodes, "probes": [
            {"point": list(p[:d]), "u": [[values[0][i][c], values[1][i][c]] for c in range(d)],
             "phi": [values[0][i][d], values[1][i][d]]}
            for i, p in enumerate(probes.points)]})
    summary["harmonic"] = listed
    return summary


def analysis(keep):
    """The driver's Analysis: on the model the factory built last."""
    def analyse(problem, settings, output, summary, source):
        summary = json.loads(summary)
        a = _Assembly(keep[-1], problem)
        summary["analysis_state"] = "end" if settings.analysis.at_end else "start"
        if settings.analysis.kind == "modal":
            summary = modal(a, problem, settings, output, summary)
        else:
            summary = harmonic(a, problem, settings, output, summary, source)
        summary.setdefault("status", "completed")
        if summary["status"] != "failed":
            summary["status"] = "completed"
        _write_summary(keep[-1].mesh.comm, output, summary)
        if summary["status"] == "failed":
            raise cpp.NewtonFailure(summary["error"])
        return json.dumps(summary)
    return analyse
