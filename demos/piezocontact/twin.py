"""The Python twin: backward Euler + the stock dolfinx NonlinearProblem and
NewtonSolver on the forms of forms/piezo_forms.py, driven step by step
exactly as the C++ time loop (cpp/time_loop.cpp) drives the compiled kernels."""

import os
import signal
import sys
import time

from pathlib import Path

import numpy as np
from dolfinx import fem
from dolfinx.fem.petsc import NonlinearProblem
from dolfinx.nls.petsc import NewtonSolver
from mpi4py import MPI
from petsc4py import PETSc

from . import checkpoint, diagnostics, meshing, output
from .config import ConfigError
from .fieldwise import FieldwiseConvergence
from .problem import Problem


class NewtonFailure(RuntimeError):
    pass


class Interrupted(RuntimeError):
    """A signal (SIGINT, SIGTERM) ended the run; the summary says "interrupted"."""

    def __init__(self, signum, steps, t):
        super().__init__(f"interrupted by {signal.Signals(signum).name} after step {steps} "
                         f"(t = {t!r}); continue with --resume")
        self.signum = signum


_received = 0


def _record_signal(signum, frame):
    global _received
    _received = signum


def install_interrupt_handlers():
    """SIGINT and SIGTERM only set a flag (no KeyboardInterrupt): the time loop
    asks at every Newton iteration and between steps whether any rank was
    signalled, so that all ranks stop at the same point. After petsc4py's
    import, whose PETSc handler would print a dump and abort."""
    signal.signal(signal.SIGINT, _record_signal)
    signal.signal(signal.SIGTERM, _record_signal)


def agreed_interrupt(comm):
    """The signal received on any rank, 0 if none. Collective."""
    return comm.allreduce(_received, op=MPI.MAX)


class _Problem(NonlinearProblem):
    """The stock NonlinearProblem (its Jacobian refactorised at every
    iteration) with the per-field convergence test, the reactions and timings.

    dolfinx 0.5.2's Python NewtonSolver cannot take a convergence callback,
    so the test runs here, right after the residual is assembled: when every
    field has converged the residual handed back is zero, which the stock test
    (rtol = 0, atol = tiny) reads as converged. That vector is never solved
    with, because the loop stops there."""

    def __init__(self, problem, monitor):
        super().__init__(problem.F_ufl, problem.x, problem.bcs, problem.J_ufl)
        self.problem, self.monitor = problem, monitor
        self.ops = {name: {"count": 0, "seconds": 0.0} for name in ("residual", "jacobian")}
        self.reactions = {}
        self.signal = 0
        # The iterate and k of the last Jacobian: a resumed run rebuilds the
        # convergence test's scaling from them
        self.x_assembled, self.k_assembled = problem.x.x.array.copy(), 0.0

    def _timed(self, name, t0):
        self.ops[name]["count"] += 1
        self.ops[name]["seconds"] += time.perf_counter() - t0

    def F(self, x, b):
        """NonlinearProblem.F, reading the reactions before set_bc."""
        t0 = time.perf_counter()
        with b.localForm() as b_local:
            b_local.set(0.0)
        fem.petsc.assemble_vector(b, self._L)
        fem.petsc.apply_lifting(b, [self._a], bcs=[self.bcs], x0=[x], scale=-1.0)
        b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        self._record_reactions(b)
        fem.petsc.set_bc(b, self.bcs, x, -1.0)
        self._timed("residual", t0)
        converged = self.monitor.check(x.array_r, b.array_r)
        # A signal on any rank ends the solve too ("converged"; the loop then
        # abandons the step), so that every rank stops at the same iteration
        self.signal = agreed_interrupt(self.problem.comm)
        if converged or self.signal:
            b.zeroEntries()

    def _record_reactions(self, b):
        """At a Dirichlet row the residual before set_bc is the unconstrained
        one (the lifting adds A(g - x), zero once x holds the boundary values)."""
        owned = b.array_r
        comm = self.problem.comm
        self.reactions = {
            name: [comm.allreduce(float(np.sum(owned[d[d < len(owned)]])), op=MPI.SUM)
                   for d in comps]
            for name, comps in self.problem.clamped_dofs.items()}

    def J(self, x, A):
        t0 = time.perf_counter()
        super().J(x, A)
        self._timed("jacobian", t0)
        self.monitor.set_scaling(A)
        self.x_assembled[:] = self.problem.x.x.array
        self.k_assembled = float(self.problem.data["k"].value)


def _set_petsc_options(ksp, options):
    """After the NewtonSolver constructor, which writes its own nls_solve_
    defaults into the options database."""
    opts = PETSc.Options()
    prefix = ksp.getOptionsPrefix()
    for key, value in options.items():
        opts[f"{prefix}{key}"] = value if not isinstance(value, bool) else str(value).lower()
    ksp.setFromOptions()


def run(cfg, out_dir, comm, progress=True, source="config", resume=None):
    """Run the time loop; write DIR/summary.json etc.; return the summary.
    With `resume` (a summary.json of DIR), continue from its checkpoint."""
    t_start = time.perf_counter()
    out_dir = Path(out_dir)
    if resume is None:
        mesh_file = meshing.prepare(cfg, source, out_dir, comm)
    else:
        mesh_file = resume["mesh_file"]
    if mesh_file is not None:
        mesh_file = os.path.abspath(mesh_file)
    problem = Problem(cfg, comm, source, mesh_file)
    probes = diagnostics.Probes(problem, cfg["probes"], source)
    contact = diagnostics.ContactGeometry(problem)
    newton_cfg = cfg["solver"]["newton"]
    monitor = FieldwiseConvergence(problem.W, {"u": problem.u_dofs, "phi": problem.phi_dofs},
                                   problem.bc_dofs, newton_cfg["rtol"], newton_cfg["atol"], comm)
    nl = _Problem(problem, monitor)
    newton = NewtonSolver(comm, nl)
    newton.rtol = 0.0                 # convergence is decided by the monitor
    newton.atol = np.finfo(float).tiny
    newton.max_it = newton_cfg["max_iterations"]
    newton.report = False
    newton.error_on_nonconvergence = False
    _set_petsc_options(newton.krylov_solver, cfg["solver"]["petsc_options"])

    if resume is not None:
        summary = resume
        state = summary["checkpoint"]
        # What came after the checkpoint is done again
        del summary["steps"][state["step"]:]
        del summary["events"][state["events"]:]
        summary.pop("error", None)
        summary.pop("signal", None)
        summary["config"] = cfg  # a later T, when extended
        summary.setdefault("resumed", []).append(
            {"step": state["step"], "t": state["t"], "mpi_size": comm.size})
        summary["mpi_size"] = comm.size
    else:
        W_map = problem.W.dofmap.index_map
        summary = {"solver": "python",
                   "dofs": W_map.size_global * problem.W.dofmap.index_map_bs,
                   "mpi_size": comm.size, "config": cfg,
                   "config_file": os.path.abspath(source), "mesh_file": mesh_file,
                   "boundary_lengths": meshing.boundary_lengths(
                       problem.mesh, problem.facet_tags, problem.tag_of, comm),
                   "steps": [], "events": [], "timing": {}}
        state = None
    summary["status"] = "running"

    # time spent writing outputs, per kind: what the safe writes cost
    output_stats = {k: {"count": 0, "seconds": 0.0}
                    for k in ("step_files", "checkpoint", "summary")}

    def timed(kind, action):
        t0 = time.perf_counter()
        result = action()
        output_stats[kind]["seconds"] += time.perf_counter() - t0
        output_stats[kind]["count"] += 1
        return result

    def write_summary():
        timed("summary", lambda: output.collectively(
            comm, comm.rank == 0,
            lambda: output.write_json_atomic(out_dir / "summary.json", summary)))

    def fail_on_output(err):
        """A write error ends the run; the summary says so if it still can."""
        summary["status"], summary["error"] = "failed", str(err)
        try:
            write_summary()
        except output.OutputError:
            pass
        raise err

    T, N = cfg["time"]["T"], cfg["time"]["steps"]
    steps = StepControl(T, N, cfg["solver"]["newton"]["max_step_halvings"])
    x, x_prev = problem.x, problem.x_prev
    x_prev2 = x_prev.x.array.copy()   # u_{n-2}, for the predictor
    u = problem.u_dofs

    state_file = checkpoint.StateFile(problem)

    def save_checkpoint():
        s = checkpoint.step_state(steps, nl.k_assembled, len(summary["events"]),
                                  f"checkpoint/state_{steps.accepted:06d}.npy")
        if comm.rank == 0:
            (out_dir / "checkpoint").mkdir(exist_ok=True)
        timed("checkpoint", lambda: state_file.write(
            out_dir / s["file"], (x_prev.x.array, x_prev2, nl.x_assembled)))
        return s

    try:
        writer = output.Writer(problem, out_dir, cfg, state["step"] if state else 0)
        if resume is not None:
            # The Jacobian in use at the checkpoint, rebuilt where it was
            # assembled: the same convergence scaling as if never stopped
            x_J = np.zeros_like(x.x.array)
            try:
                state_file.read(out_dir / state["file"], (x_prev.x.array, x_prev2, x_J))
            except (OSError, ValueError) as err:
                raise ConfigError(f"cannot resume: {err}") from None
            x.x.array[:] = x_J
            problem.data["k"].value = state["k_J"]
            nl.J(x.vector, newton.A)
            x.x.array[:] = x_prev.x.array
            steps.restore(state["nominal_steps"], state["t"], state["k"], state["k_last"],
                          state["step"])
            if comm.rank == 0 and progress:
                print(f"[python] resuming at step {state['step']}, t = {state['t']:.6g}",
                      flush=True)
        else:
            nl.J(x.vector, newton.A)  # initial scaling D for the first test
            state = save_checkpoint()
        summary["checkpoint"] = state
        write_summary()
    except output.OutputError as err:
        fail_on_output(err)

    newton_s, newton_its, callbacks_in_newton = 0.0, 0, 0.0
    signum = 0
    while not steps.done():
        signum = agreed_interrupt(comm)
        if signum:
            break
        t, k = steps.attempt()
        problem.data["k"].value = k
        if problem.manufactured:
            problem.manufactured.set_time(t)  # loads and Dirichlet data at t_n
        # Predictor u^0 = u_{n-1} + k du_{n-1}, phi^0 = phi_{n-1}; then the BCs
        x.x.array[u] = x_prev.x.array[u] + k / steps.k_last * (x_prev.x.array[u] - x_prev2[u])
        fem.petsc.set_bc(x.vector, problem.bcs)
        x.x.scatter_forward()
        monitor.history = []
        j0 = nl.ops["jacobian"]["count"]
        c0 = sum(op["seconds"] for op in nl.ops.values())
        t0 = time.perf_counter()
        its, converged = newton.solve(x)
        newton_s += time.perf_counter() - t0
        newton_its += its
        callbacks_in_newton += sum(op["seconds"] for op in nl.ops.values()) - c0
        if nl.signal:
            signum = nl.signal
            x.x.array[:] = x_prev.x.array  # the step is abandoned
            break
        if not converged:
            last = monitor.history[-1]["relative"]
            what = (f"Newton did not converge at t = {t:g} (k = {k:g}) in {its} iterations: "
                    f"relative residuals u = {_e(last['u'])}, phi = {_e(last['phi'])}")
            x.x.array[:] = x_prev.x.array  # back to the last accepted state
            event = steps.reject()
            summary["events"].append({"t": t, "k": k, "newton_iterations": its,
                                      "relative_residuals": last, "action": event})
            if event == "stop":
                summary["status"] = "failed"
                summary["error"] = (f"{what}; gave up after {steps.max_halvings} halvings "
                                    "of the time step")
                try:
                    write_summary()
                except output.OutputError:
                    pass
                raise NewtonFailure(summary["error"])
            if comm.rank == 0:
                print(f"[python] {what}: retrying with k = {steps.k:g}", flush=True)
            continue
        steps.accept()
        problem.update_fields()
        step = _step_record(problem, probes, contact, monitor, nl, t, its,
                            nl.ops["jacobian"]["count"] - j0)
        step["k"] = k
        if problem.manufactured:
            step["errors"] = problem.manufactured.errors(comm)
        x_prev2[:] = x_prev.x.array
        x_prev.x.array[:] = x.x.array
        # Step files, then its checkpoint, then the summary that points to
        # both: a kill at any instant leaves a summary whose every step is on disk
        previous = state
        try:
            timed("step_files", lambda: writer.write_step(steps.accepted, t,
                                                          final=steps.done()))
            state = save_checkpoint()
            summary["steps"].append(step)
            summary["checkpoint"] = state
            summary["status"] = "completed" if steps.done() else "running"
            summary["timing"] = _timing(nl, output_stats, time.perf_counter() - t_start, newton_s,
                                        callbacks_in_newton, newton_its)
            write_summary()
        except output.OutputError as err:
            del summary["steps"][previous["step"]:]
            summary["checkpoint"] = previous
            if comm.rank == 0 and state is not previous:
                # unreferenced: its space may let the summary say what went wrong
                output.remove_quietly(out_dir / state["file"])
            fail_on_output(err)
        if comm.rank == 0:
            output.remove_quietly(out_dir / previous["file"])
            if progress:
                _progress(steps.accepted, N, step)
    if signum:
        summary["status"], summary["signal"] = "interrupted", signal.Signals(signum).name
        summary["timing"] = _timing(nl, output_stats, time.perf_counter() - t_start, newton_s,
                                    callbacks_in_newton, newton_its)
        try:
            write_summary()
        except output.OutputError as err:
            fail_on_output(err)
        raise Interrupted(signum, steps.accepted, steps.t)
    writer.close()
    return summary


class StepControl:
    """Backward Euler steps of the config's size k = T/steps; when Newton
    fails, the step is retried with k halved (at most max_halvings times in
    a row) and the smaller k is kept until the next nominal time t_n = n k.
    cpp/step_control.h does the same."""

    def __init__(self, T, N, max_halvings):
        self.T, self.N, self.max_halvings = T, N, max_halvings
        self.k_nominal = T / N
        self.n = 0             # nominal steps completed
        self.t = 0.0           # time of the last accepted state
        self.k = self.k_nominal
        self.k_last = self.k_nominal  # size of the last accepted step
        self.halvings = 0      # consecutive failures
        self.accepted = 0

    def done(self):
        return self.n == self.N

    def attempt(self):
        """(t, k) of the next try; lands exactly on the next nominal time."""
        target = (self.n + 1) * self.k_nominal
        if self.t + self.k >= target - 1e-9 * self.k_nominal:
            return target, target - self.t
        return self.t + self.k, self.k

    def accept(self):
        t, k = self.attempt()
        self.t, self.k_last, self.halvings = t, k, 0
        self.accepted += 1
        if t == (self.n + 1) * self.k_nominal:
            self.n += 1
            self.k = self.k_nominal

    def restore(self, nominal_steps, t, k, k_last, accepted):
        """Continue from a checkpoint: the state right after an accepted step."""
        self.n, self.halvings = nominal_steps, 0
        self.t, self.k, self.k_last, self.accepted = t, k, k_last, accepted

    def reject(self):
        """'halve k' or, past the limit, 'stop'."""
        if self.halvings == self.max_halvings:
            return "stop"
        self.halvings += 1
        self.k /= 2
        return "halve k"


def _timing(nl, output_stats, total_s, newton_s, callbacks_in_newton, newton_its):
    """As the C++ solver reports it. Stock Newton: every Jacobian is
    factorised inside KSPSolve, so factorisation and triangular solves are
    one figure here (the Newton time not spent assembling)."""
    solves = max(0.0, newton_s - callbacks_in_newton)
    ops = nl.ops
    return {"total_s": total_s,
            "output_s": sum(v["seconds"] for v in output_stats.values()),
            "output": output_stats,
            "assembly_s": ops["residual"]["seconds"] + ops["jacobian"]["seconds"],
            "solve_s": solves,
            "operations": {"residual": ops["residual"], "jacobian": ops["jacobian"],
                           "factorisation_and_solve": {"count": newton_its, "seconds": solves},
                           "factorisations": ops["jacobian"]["count"]}}


def _step_record(problem, probes, contact, monitor, nl, t, its, factorisations):
    final = monitor.history[-1]
    values = probes.evaluate(problem.u, problem.phi)
    return {
        "t": t,
        "newton_iterations": its,
        "factorisations": factorisations,
        "residual_norms": final["residual"],
        "relative_residuals": final["relative"],
        "residual_history": [h["relative"] for h in monitor.history],
        "probes": [{"point": list(map(float, p[:2])), "u": [float(v[0]), float(v[1])],
                    "phi": float(v[2])} for p, v in zip(probes.points, values)],
        "contact_force": diagnostics.contact_force(problem),
        "max_penetration": contact.max_normal_gap(problem.u, problem.cfg["contact"]["gap"]),
        "reactions": nl.reactions,  # of the converged iterate
    }


def _e(value, digits=3, missing="undefined"):
    return missing if value is None else f"{value:.{digits}e}"


def _progress(n, N, step):
    r = step["relative_residuals"]
    print(f"[python] step {n:4d}  t = {step['t']:.4g}  newton {step['newton_iterations']}"
          f"  rel. residual u {_e(r['u'], 1)} phi {_e(r['phi'], 1)}"
          f"  max(u.nu - g) = {_e(step['max_penetration'], 3, 'n/a')}", flush=True)
    sys.stdout.flush()
