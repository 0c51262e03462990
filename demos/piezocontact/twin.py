"""The Python twin: backward Euler + the stock dolfinx NonlinearProblem and
NewtonSolver on the forms of forms/piezo_forms.py, driven step by step
exactly as the C++ time loop (cpp/time_loop.cpp) drives the compiled kernels."""

import sys
import time

import numpy as np
from dolfinx import fem
from dolfinx.fem.petsc import NonlinearProblem
from dolfinx.nls.petsc import NewtonSolver
from petsc4py import PETSc

from . import diagnostics, meshing, output
from .fieldwise import FieldwiseConvergence
from .problem import Problem


class NewtonFailure(RuntimeError):
    pass


class _Problem(NonlinearProblem):
    """NonlinearProblem with the per-field convergence test and timings.

    dolfinx 0.5.2's Python NewtonSolver cannot take a convergence callback,
    so the test runs here, right after the residual is assembled: when every
    field has converged the residual handed back is zero, which the stock test
    (rtol = 0, atol = tiny) reads as converged. That vector is never solved
    with, because the loop stops there."""

    def __init__(self, problem, monitor):
        super().__init__(problem.F_ufl, problem.x, problem.bcs, problem.J_ufl)
        self.monitor = monitor
        self.assembly_s = 0.0

    def F(self, x, b):
        t0 = time.perf_counter()
        super().F(x, b)
        self.assembly_s += time.perf_counter() - t0
        if self.monitor.check(x.array_r, b.array_r):
            b.zeroEntries()

    def J(self, x, A):
        t0 = time.perf_counter()
        super().J(x, A)
        self.assembly_s += time.perf_counter() - t0
        self.monitor.set_scaling(A)


def _set_petsc_options(ksp, options):
    """After the NewtonSolver constructor, which writes its own nls_solve_
    defaults into the options database."""
    opts = PETSc.Options()
    prefix = ksp.getOptionsPrefix()
    for key, value in options.items():
        opts[f"{prefix}{key}"] = value if not isinstance(value, bool) else str(value).lower()
    ksp.setFromOptions()


def run(cfg, out_dir, comm, progress=True, source="config"):
    """Run the time loop; write DIR/summary.json etc.; return the summary."""
    t_start = time.perf_counter()
    mesh_file = meshing.prepare(cfg, source, out_dir, comm)
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

    writer = output.Writer(problem, out_dir, cfg)
    W_map = problem.W.dofmap.index_map
    summary = {"solver": "python", "dofs": W_map.size_global * problem.W.dofmap.index_map_bs,
               "mpi_size": comm.size, "config": cfg, "mesh_file": mesh_file,
               "boundary_lengths": meshing.boundary_lengths(problem.mesh, problem.facet_tags,
                                                            problem.tag_of, comm),
               "steps": [], "timing": {}}

    T, N = cfg["time"]["T"], cfg["time"]["steps"]
    k = T / N
    x, x_prev = problem.x, problem.x_prev
    x_prev2 = x_prev.x.array.copy()   # u_{n-2}, for the predictor
    u = problem.u_dofs
    nl.J(x.vector, newton.A)          # initial scaling D for the first test
    solve_s = 0.0
    for n in range(1, N + 1):
        t = n * k
        # Predictor u^0 = u_{n-1} + k du_{n-1}, phi^0 = phi_{n-1}; then the BCs
        x.x.array[u] = 2.0 * x_prev.x.array[u] - x_prev2[u]
        fem.petsc.set_bc(x.vector, problem.bcs)
        x.x.scatter_forward()
        monitor.history = []
        a0 = nl.assembly_s
        t0 = time.perf_counter()
        its, converged = newton.solve(x)
        solve_s += time.perf_counter() - t0 - (nl.assembly_s - a0)
        if not converged:
            last = monitor.history[-1]["relative"]
            raise NewtonFailure(f"Newton did not converge at t = {t:g} (step {n}) in {its} "
                                f"iterations: relative residuals u = {_e(last['u'])}, "
                                f"phi = {_e(last['phi'])}")
        problem.update_fields()
        step = _step_record(problem, probes, contact, monitor, t, its)
        x_prev2[:] = x_prev.x.array
        x_prev.x.array[:] = x.x.array
        writer.write_step(n, t, final=(n == N))
        summary["steps"].append(step)
        summary["timing"] = {"total_s": time.perf_counter() - t_start,
                             "assembly_s": nl.assembly_s, "solve_s": solve_s}
        if comm.rank == 0:
            output.write_json_atomic(f"{out_dir}/summary.json", summary)
            if progress:
                _progress(n, N, step)
    writer.close()
    return summary


def _step_record(problem, probes, contact, monitor, t, its):
    final = monitor.history[-1]
    values = probes.evaluate(problem.u, problem.phi)
    return {
        "t": t,
        "newton_iterations": its,
        "residual_norms": final["residual"],
        "relative_residuals": final["relative"],
        "residual_history": [h["relative"] for h in monitor.history],
        "probes": [{"point": list(map(float, p[:2])), "u": [float(v[0]), float(v[1])],
                    "phi": float(v[2])} for p, v in zip(probes.points, values)],
        "contact_force": diagnostics.contact_force(problem),
        "max_penetration": contact.max_normal_gap(problem.u, problem.cfg["contact"]["gap"]),
        "reactions": diagnostics.reactions(problem),
    }


def _e(value, digits=3, missing="undefined"):
    return missing if value is None else f"{value:.{digits}e}"


def _progress(n, N, step):
    r = step["relative_residuals"]
    print(f"[python] step {n:4d}/{N}  t = {step['t']:.4g}  newton {step['newton_iterations']}"
          f"  rel. residual u {_e(r['u'], 1)} phi {_e(r['phi'], 1)}"
          f"  max(u.nu - g) = {_e(step['max_penetration'], 3, 'n/a')}", flush=True)
    sys.stdout.flush()
