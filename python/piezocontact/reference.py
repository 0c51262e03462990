"""The reference engine: an independent check of the C++ time loop.

It solves the same forms on the same mesh with petsc4py's SNES (Newton, LU,
a fresh Jacobian at every iteration) in a loop of its own: fixed steps
t_n = n T/N, the previous state as initial guess, and its own convergence
test, on the increment of each field. It shares no solver code with the
C++ loop (no predictor, no LU reuse, no scaled residual test, no step
control); the record of each step (probes, forces, files, summary) is the
library's, so that the summaries of all engines compare key by key."""

import json
import time

import dolfinx.fem.petsc  # noqa: F401  (0.9 does not import it with dolfinx.fem)
import numpy as np
from dolfinx import fem
from petsc4py import PETSc

from . import cpp
from ._compat import create_vector, dirichletbcs, petsc_vec

# Converged when each field's increment is this small against the field;
# far below the 1e-8 at which the engines are compared
INCREMENT_RTOL = 1e-11
# What double precision can promise of a sum of many terms
ROUNDOFF = 1e3 * np.finfo(float).eps


class _Newton:
    """SNES on F(x) = 0 with the Dirichlet conditions, as dolfinx's
    NonlinearProblem assembles it (lifting, then the BC rows); floating
    electrodes by a multi-point constraint (floating_mpc.py)."""

    def __init__(self, model, problem, settings, comm):
        self.x, self.bcs, self.problem = model.x, dirichletbcs(problem.bcs), problem
        self.F_form, self.J_form = model.F_whole, model.J_whole
        self.fields = {"u": np.asarray(problem.u_dofs), "phi": np.asarray(problem.phi_dofs)}
        self.floating = None
        if any(e.floating for e in problem.electrodes):
            from .floating_mpc import FloatingConstraint
            self.floating = FloatingConstraint(self.x, problem, self.F_form, self.J_form)
            self.bcs = self.floating.bcs
            self.b, self.A = self.floating.create_vector(), self.floating.create_matrix()
        else:
            self.b = create_vector(self.F_form)
            self.A = fem.petsc.create_matrix(self.J_form)
        self.snes = PETSc.SNES().create(comm)
        self.snes.setFunction(self._F, self.b)
        self.snes.setJacobian(self._J, self.A)
        # full Newton steps, MUMPS LU; under a prefix of our own
        prefix = "piezocontact_reference_"
        options = PETSc.Options()
        for key, value in {"snes_type": "newtonls", "snes_linesearch_type": "basic",
                           "ksp_type": "preonly", "pc_type": "lu",
                           "pc_factor_mat_solver_type": "mumps"}.items():
            options[prefix + key] = value
        self.snes.setOptionsPrefix(prefix)
        self.snes.setFromOptions()
        self.snes.setTolerances(max_it=max(50, settings.newton.max_iterations))
        self.snes.setConvergenceTest(self._converged)
        self.history = []
        self.acceptance = cpp.Acceptance()  # the rule at the last iterate
        self.rtol = settings.newton.rtol
        self.assembly_s = 0.0
        # rows and columns of each field: owned, not Dirichlet (local indices)
        bc = np.asarray(problem.bc_dofs)
        self.free = {f: np.setdiff1d(d, bc) for f, d in self.fields.items()}
        self._coupling = None  # |J_fg| of the Jacobian in use, per (f, g)

    def _F(self, snes, x, F):
        t0 = time.perf_counter()
        if self.floating:
            self.floating.take(x)
            self.floating.residual(F)
        else:
            x.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
            x.copy(petsc_vec(self.x))
            petsc_vec(self.x).ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
            with F.localForm() as f:
                f.set(0.0)
            fem.petsc.assemble_vector(F, self.F_form)
            # scale = -1 (0.9 calls it alpha): positional for both
            fem.petsc.apply_lifting(F, [self.J_form], [self.bcs], [x], -1.0)
            F.ghostUpdate(PETSc.InsertMode.ADD, PETSc.ScatterMode.REVERSE)
        self.balance = self.problem.force_balance(F.getArray(readonly=True))
        fem.petsc.set_bc(F, self.bcs, petsc_vec(self.x), -1.0)
        self.assembly_s += time.perf_counter() - t0

    def _J(self, snes, x, A, P):
        t0 = time.perf_counter()
        if self.floating:
            self.floating.take(x)
            self.floating.jacobian(A)
        else:
            A.zeroEntries()
            fem.petsc.assemble_matrix(A, self.J_form, bcs=self.bcs)
            A.assemble()
        self._coupling = None
        self.assembly_s += time.perf_counter() - t0

    def _abs_blocks(self):
        """|J_fg| (entry by entry) on the free rows of f and columns of
        g != f, per (f, g), of the Jacobian in use."""
        if self._coupling is None:
            start = self.A.getOwnershipRange()[0]
            n = self.A.getLocalSize()[0]
            comm = self.A.getComm()
            index = {f: PETSc.IS().createGeneral(
                (start + d[d < n]).astype(PETSc.IntType), comm=comm)
                for f, d in self.free.items()}
            self._coupling = {}
            for f in index:
                for g in index:
                    if g == f:
                        continue
                    block = self.A.createSubMatrix(index[f], index[g])
                    ai, aj, av = block.getValuesCSR()
                    self._coupling[f, g] = PETSc.Mat().createAIJWithArrays(
                        block.getSizes(), (ai, aj, np.abs(av)), comm=comm)
        return self._coupling

    def _zero_fields(self, x, dx, failing):
        """Of the fields that failed the increment test, those zero to
        round-off (phi with every electrode grounded): their own terms,
        J_ff x_f, and the step's, J_ff dx_f, are below the round-off of the
        coupling terms in their equations, |J_fg| |x_g| (g != f, max norms,
        entry by entry: what the coupling's sum is the round-off of). Such a
        field has no size to measure an increment against. {field: size of
        its terms relative to the coupling}."""
        if self.floating or not failing:
            return {}  # the constrained layout of the floating case: no zero rule
        n = x.getLocalSize()
        values = x.getArray(readonly=True)
        comm = self.x.function_space.mesh.comm
        out = {}
        for f in failing:
            c = 0.0
            for (row, g), block in self._abs_blocks().items():
                if row != f:
                    continue
                xg = block.createVecRight()
                xg.setArray(np.abs(values[self.free[g][self.free[g] < n]]))
                y = block.createVecLeft()
                block.mult(xg, y)
                c = max(c, float(np.max(y.getArray(readonly=True), initial=0.0)))
            c = comm.allreduce(c, op=_MAX)
            own = max(self._own_terms(v, f) for v in (x, dx))
            if own <= ROUNDOFF * c:
                out[f] = own / c if c > 0 else 0.0
        return out

    def _own_terms(self, v, f):
        """||(J_ff v_f)||_inf over f's free rows."""
        n = v.getLocalSize()
        d = self.fields[f][self.fields[f] < n]
        values = np.zeros(n)
        values[d] = v.getArray(readonly=True)[d]
        masked = v.duplicate()
        masked.setArray(values)
        y = self.A.createVecLeft()
        self.A.mult(masked, y)
        rows = self.free[f][self.free[f] < n]
        local = float(np.max(np.abs(y.getArray(readonly=True)[rows]), initial=0.0))
        return self.A.getComm().tompi4py().allreduce(local, op=_MAX)

    def _norms(self, v):
        """||v_f||_inf of each field, on every rank."""
        local = v.getArray(readonly=True)
        comm = self.x.function_space.mesh.comm
        out = {}
        for name, dofs in self.fields.items():
            owned = dofs[dofs < local.size]
            out[name] = comm.allreduce(float(np.max(np.abs(local[owned]), initial=0.0)),
                                       op=_MAX)
        return out

    def _converged(self, snes, it, norms):
        F_norms = self._norms(snes.getFunction()[0])
        if it == 0:
            self.history = [{f: (F_norms[f], None) for f in F_norms}]
            self.acceptance = cpp.Acceptance()
            return 0
        # x as assembled (with floating electrodes, the solver's own vector
        # keeps stale entries at constrained dofs)
        update = snes.getSolutionUpdate()
        dx, x = self._norms(update), self._norms(petsc_vec(self.x))
        relative = {f: dx[f] / x[f] if x[f] > 0 else 0.0 for f in dx}
        relative.update(self._zero_fields(
            petsc_vec(self.x), update, [f for f in relative if relative[f] > INCREMENT_RTOL]))
        self.history.append({f: (F_norms[f], relative[f]) for f in F_norms})
        # Small increments are not enough where the penalty makes J
        # ill-conditioned: the library's acceptance rule (acceptance.h) also
        # wants the forces to balance
        self.acceptance = cpp.Acceptance()
        self.acceptance.fields = all(r <= INCREMENT_RTOL for r in relative.values())
        self.acceptance.imbalance = cpp.force_imbalance(self.problem, self.balance)
        if self.acceptance.accepted(self.rtol):
            return PETSc.SNES.ConvergedReason.CONVERGED_SNORM_RELATIVE
        if it >= snes.getTolerances()[3]:
            return PETSc.SNES.ConvergedReason.DIVERGED_MAX_IT
        return 0

    def solve(self):
        """Newton from the current x; (iterations, converged)."""
        if self.floating:
            x = self.floating.create_vector()
            petsc_vec(self.x).copy(x)  # the owned layouts agree
            self.snes.solve(None, x)
            self.floating.take(x)
        else:
            x = petsc_vec(self.x).copy()
            self.snes.solve(None, x)
            x.copy(petsc_vec(self.x))
            self.x.x.scatter_forward()
        return self.snes.getIterationNumber(), self.snes.getConvergedReason() > 0


from mpi4py import MPI  # noqa: E402

_MAX = MPI.MAX


def _stalled(history, window=5):
    """The fields whose increments did not get small and made no progress in
    the last iterations: round-off of an ill-conditioned solve."""
    if len(history) < window + 1:
        return ""
    last = history[-window:]
    stalled = [f for f in last[-1] if last[-1][f][1] > INCREMENT_RTOL
               and max(h[f][1] for h in last) <= 10 * min(h[f][1] for h in last)]
    return (f" ({', '.join(stalled)} stalled at round-off for {window} iterations: data off "
            "scale by many orders of magnitude?)") if stalled else ""


def _report(t, k, its, history):
    nan = float("nan")
    report = cpp.SolveReport()
    report.t, report.k = t, k
    report.newton_iterations = its
    report.factorisations = its
    report.krylov_iterations = its
    report.history = [{f: cpp.FieldNorms(r, float("nan"), nan if rel is None else rel,
                                         nan if rel is None else rel)
                       for f, (r, rel) in h.items()} for h in history]
    return report


def run(model, problem, settings, output, summary, progress, observer=None):
    """The reference loop; returns the summary (JSON text)."""
    t_start = time.perf_counter()
    comm = model.mesh.comm
    newton = _Newton(model, problem, settings, comm)
    on_step = None
    if observer is not None:
        def on_step(n, record):
            observer(n, json.loads(record))
    record = cpp.Record(problem, settings, output, summary, progress, on_step)
    x, x_prev = model.x.x.array, model.x_prev.x.array
    k = settings.T / settings.steps
    record.begin(cpp.StepState(0, 0, 0.0, k, k, k), x_prev, x_prev, x_prev)
    solve_s, iterations = 0.0, 0

    def timing():
        total = time.perf_counter() - t_start
        stats = {"count": iterations, "seconds": 0.0}
        return json.dumps({
            "total_s": total, "assembly_s": newton.assembly_s,
            "solve_s": max(0.0, solve_s - newton.assembly_s),
            "operations": {"residual": stats, "jacobian": stats,
                           "contact_jacobian": {"count": 0, "seconds": 0.0},
                           "factorisation": stats, "triangular_solve": stats,
                           "reused_factorisation": 0}})

    for n in range(1, settings.steps + 1):
        signum = cpp.agreed_interrupt(comm)
        if signum:
            record.interrupt(signum, timing())
        t = n * k
        try:
            problem.set_time(t, k)
        except cpp.ConfigError as e:  # an expression of t not finite now
            record.refuse(str(e))
        x[:] = x_prev
        fem.petsc.set_bc(petsc_vec(model.x), newton.bcs)
        model.x.x.scatter_forward()
        t0 = time.perf_counter()
        its, converged = newton.solve()
        solve_s += time.perf_counter() - t0
        iterations += its
        report = _report(t, k, its, newton.history)
        report.acceptance = newton.acceptance
        if not converged:
            record.reject(report, "stop")
            record.fail(f"Newton did not converge at t = {t:g} (k = {k:g}) in {its} "
                        f"iterations (reference engine)"
                        f"{cpp.imbalance_clause(newton.acceptance, problem)}"
                        f"{_stalled(newton.history)}")
        # recorded while x_prev is u_{n-1}: the stress holds the velocity
        record.accept(cpp.StepState(n, n, t, k, k, k), report, x, x_prev, x,
                      n == settings.steps, timing())
        x_prev[:] = x
    return record.summary


def engine(keep, observer=None):
    """The driver's Engine: runs on the model the factory built last."""
    def loop(problem, settings, output, summary, resume, progress):
        if resume:
            raise cpp.ConfigError(f"{output}: cannot resume: the reference engine runs whole")
        return run(keep[-1], problem, settings, output, summary, progress, observer)
    return loop
