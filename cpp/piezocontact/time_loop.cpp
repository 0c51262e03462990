#include "time_loop.h"

#include <limits>
#include "diagnostics.h"
#include "fieldwise.h"
#include "json_input.h"
#include "nonlinear_system.h"
#include "petsc_options.h"
#include "step_control.h"

#include <cmath>
#include <cstdio>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/nls/NewtonSolver.h>
#include <iostream>
#include <limits>
#include <petscksp.h>

namespace piezocontact
{
using namespace dolfinx;
namespace
{

std::string sci(double v)
{
  if (std::isnan(v))
    return "undefined";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3e", v);
  return buf;
}

/// What the test measures of a field: its relative residual, and its
/// relative update once there is one
double measured(const FieldNorms& f)
{
  return std::isnan(f.update) ? f.relative : std::max(f.relative, f.update);
}

/// The fields that did not converge and made no progress in the last
/// iterations: what round-off of terms far larger than the residual does
/// (data spanning more orders of magnitude than double precision resolves)
std::string stalled(const std::vector<std::map<std::string, FieldNorms>>& history, double rtol)
{
  constexpr std::size_t window = 5;
  if (history.size() < window)
    return "";
  std::string out;
  for (const auto& [name, last] : history.back())
  {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (std::size_t i = history.size() - window; i < history.size(); ++i)
    {
      lo = std::min(lo, measured(history[i].at(name)));
      hi = std::max(hi, measured(history[i].at(name)));
    }
    if (measured(last) > rtol and hi <= 10 * lo)
      out += (out.empty() ? "" : ", ") + name;
  }
  return out.empty() ? ""
                     : " (" + out + " stalled at round-off for " + std::to_string(window)
                           + " iterations: data off scale by many orders of magnitude?)";
}

double callback_seconds(const NonlinearSystem& sys)
{
  return sys.residual.seconds + sys.jacobian.seconds + sys.contact_jacobian.seconds
         + sys.factorisation.seconds + sys.floating.stats.seconds;
}

/// Where the time went. Triangular solves: the Newton time not spent in the
/// callbacks (one KSPSolve per iteration, plus vector updates); the first
/// Jacobian and factorisation, made before the loop, count in theirs.
/// Iterative: "factorisation" holds the preconditioner set-ups and
/// "triangular_solve" the Krylov solves.
json timing(const NonlinearSystem& sys, double total_s, double newton_s,
            double callbacks_in_newton, int newton_its)
{
  const double solves = std::max(0.0, newton_s - callbacks_in_newton);
  return {{"total_s", total_s},
          {"assembly_s", sys.residual.seconds + sys.jacobian.seconds + sys.contact_jacobian.seconds},
          {"solve_s", sys.factorisation.seconds + solves},
          {"operations",
           {{"residual", sys.residual.to_json()},
            {"jacobian", sys.jacobian.to_json()},
            {"contact_jacobian", sys.contact_jacobian.to_json()},
            {"factorisation", sys.factorisation.to_json()},
            {"triangular_solve", {{"count", newton_its}, {"seconds", solves}}},
            {"floating_electrodes", sys.floating.stats.to_json()},
            {"reused_factorisation", sys.reused},
            {"lagged_preconditioner", sys.lagged}}},
          {"linear_solver", sys.linear.iterative() ? "iterative" : "direct"}};
}

} // namespace

json run(Problem& problem, const RunSettings& settings, const std::filesystem::path& out_dir,
         json summary, bool resume, bool progress, const StepObserver& observer)
{
  const common::Timer total("piezocontact: run");
  const MPI_Comm comm = problem.comm;
  Record record(problem, settings, out_dir, std::move(summary), resume, progress, observer);
  const auto& imap = *problem.W->dofmap()->index_map;
  const int bs = problem.W->dofmap()->index_map_bs();
  FieldwiseConvergence monitor({{"u", problem.u_dofs}, {"phi", problem.phi_dofs}},
                               problem.bc_dofs, imap.size_local() * bs, settings.newton.rtol,
                               settings.newton.atol, comm);
  la::petsc::Vector x_vec(la::petsc::create_vector_wrap(*problem.x->x()), false);
  Vec x = x_vec.vec();
  nls::petsc::NewtonSolver newton(comm);
  // Our prefix, our defaults (LU by MUMPS, or the iterative solver), then
  // the config's options
  PetscOptionList options = loop_defaults(settings.linear);
  options.insert(options.end(), settings.petsc_options.begin(), settings.petsc_options.end());
  const ScopedPetscOptions scoped_options(petsc_prefix, options);
  newton.get_krylov_solver().set_options_prefix(petsc_prefix);
  newton.get_krylov_solver().set_from_options();
  NonlinearSystem system(problem, monitor, newton.get_krylov_solver().ksp(),
                         settings.reuse_factorisation, settings.linear);
  newton.setF([&system](const Vec x, Vec r) { system.F(x, r); }, system.b.vec());
  newton.setJ([&system](const Vec x, Mat A) { system.J(x, A); }, system.A.mat());
  newton.set_form(
      [](Vec x)
      {
        VecGhostUpdateBegin(x, INSERT_VALUES, SCATTER_FORWARD);
        VecGhostUpdateEnd(x, INSERT_VALUES, SCATTER_FORWARD);
      });
  // The built-in test keeps residual0 across solves and sees only u. A
  // signal on any rank ends the solve too ("converged"; the loop then
  // abandons the step), so that every rank stops at the same iteration.
  int signal = 0;
  double imbalance = 0.0; // force_imbalance at the last iterate
  newton.set_convergence_check(
      [&monitor, &problem, &signal, &system, &imbalance,
       monitor_rtol = settings.newton.rtol](const nls::petsc::NewtonSolver&,
                                                         const Vec r)
      {
        PetscInt n;
        VecGetLocalSize(r, &n);
        const PetscScalar* ra;
        VecGetArrayRead(r, &ra);
        const std::span<const double> residual(ra, n);
        bool ok = monitor.check(problem.x->x()->array().subspan(0, n), residual);
        // an update that solved a locally linear problem exactly needs no
        // second one to bound its error (fieldwise.h)
        if (!ok and monitor.residuals_converged())
          ok = system.exact_update();
        if (!system.floating.empty()) // the floating electrodes' charge equations
        {
          const double relative = system.floating.relative_residual();
          monitor.history.back()["charge"]
              = {system.floating.residual_norm(), relative, relative};
          ok = ok and relative <= monitor_rtol;
        }
        // The scaled test alone can pass with newtons left over where one
        // block dwarfs the rest (a huge contact penalty): balance them too
        imbalance = force_imbalance(problem, system.balance, contact_force(problem));
        VecRestoreArrayRead(r, &ra);
        PetscReal norm;
        VecNorm(r, NORM_2, &norm);
        signal = agreed_interrupt(problem.comm);
        return std::pair<double, bool>(norm, (ok and imbalance <= balance_tolerance)
                                                 or signal != 0);
      });
  // x <- x - dx, and the floating potentials with it (floating.h), once
  // the solve is checked
  newton.set_update([&system](const nls::petsc::NewtonSolver&, const Vec dx, Vec x)
                    { system.update(dx, x); });
  newton.max_it = settings.newton.max_iterations;
  newton.report = false;
  newton.error_on_nonconvergence = false;

  // The Jacobian made before the loop (and its factorisation, or the
  // floating electrodes' first solves): a failed linear solve there ends
  // the run as one inside it would after its last halving
  const auto first_jacobian = [&](const std::string& when)
  {
    try
    {
      system.J(x, system.A.mat());
    }
    catch (const LinearSolveFailure& e)
    {
      record.fail(std::string(e.what()) + " " + when + (e.hint.empty() ? "" : ": " + e.hint));
    }
  };
  StepControl steps(settings.T, settings.steps, settings.newton.max_step_halvings);
  auto xa = problem.x->x()->mutable_array();
  auto xp = problem.x_prev->x()->mutable_array();
  std::vector<double> x_prev2(xp.begin(), xp.end()); // u_{n-2}, for the predictor
  const auto state_now = [&]
  {
    StepState s;
    s.step = steps.accepted;
    s.nominal = steps.nominal_steps();
    s.t = steps.t;
    s.k = steps.k;
    s.k_last = steps.k_last;
    s.k_J = system.k_assembled;
    return s;
  };
  const auto states = [&]() -> StateViews
  { return {std::span<const double>(xp), x_prev2, system.x_assembled}; };
  if (resume)
  {
    // The Jacobian in use at the checkpoint, rebuilt where it was
    // assembled: the same LU and convergence scaling as if never stopped
    const StepState& state = record.checkpoint();
    std::vector<double> xJ(xa.size());
    record.read_states({xp, x_prev2, xJ});
    std::copy(xJ.begin(), xJ.end(), xa.begin());
    problem.model.constants.at("k")->value[0] = state.k_J;
    first_jacobian("at the resumed Jacobian");
    std::copy(xp.begin(), xp.end(), xa.begin());
    steps.restore(state.nominal, state.t, state.k, state.k_last, state.step);
    int rank;
    MPI_Comm_rank(comm, &rank);
    if (progress and rank == 0)
      std::printf("[%s] resuming at step %d, t = %.6g\n", record.label().c_str(), state.step,
                  state.t);
  }
  else
    first_jacobian("at the first Jacobian"); // initial scaling D (and first factorisation)
  record.begin(state_now(), states());

  const double callbacks_before = callback_seconds(system);
  double newton_s = 0.0;
  int newton_its = 0;
  const auto run_timing = [&]
  {
    return timing(system, total.elapsed()[0], newton_s,
                  callback_seconds(system) - callbacks_before, newton_its);
  };
  while (!steps.done() and !(signal = agreed_interrupt(comm)))
  {
    const auto [t, k] = steps.attempt();
    problem.set_time(t, k); // k, and loads and Dirichlet data at t_n
    // Predictor u^0 = u_{n-1} + k du_{n-1}, phi^0 = phi_{n-1}; then the BCs
    for (auto d : problem.u_dofs)
      xa[d] = xp[d] + k / steps.k_last * (xp[d] - x_prev2[d]);
    problem.hold_floating_potentials(xp); // phi^0 = phi_{n-1} there too
    for (const auto& bc : problem.bcs)
      compat::set_bc_values(*bc, xa);
    problem.x->x()->scatter_fwd();
    monitor.history.clear();
    const int f0 = system.factorisation.count;
    common::Timer newton_timer("piezocontact: Newton solve");
    std::pair<int, bool> outcome;
    std::string linear_failure; // a failed linear solve, if that ended the solve
    try
    {
      outcome = newton.solve(x);
    }
    catch (const LinearSolveFailure& e)
    {
      if (!e.retry)
        record.fail(std::string(e.what()) + " at t = " + json(t).dump()
                    + (e.hint.empty() ? "" : ": " + e.hint));
      outcome = {newton.iteration(), false};
      linear_failure = e.what();
    }
    catch (const std::runtime_error& e) // a PETSc call failed (QuietPetscErrors)
    {
      record.fail("the linear solver failed at t = " + json(t).dump() + ": "
                  + printable(std::string(e.what()), 300));
    }
    const auto [its, converged] = outcome;
    problem.x->x()->scatter_fwd();
    newton_s += newton_timer.stop();
    newton_its += its;
    SolveReport report{t, k, its, system.factorisation.count - f0, newton.krylov_iterations(),
                       monitor.history,
                       std::span<const double>(system.unconstrained)};
    if (signal or !converged)
    {
      std::copy(xp.begin(), xp.end(), xa.begin()); // back to the last accepted state
      problem.x->x()->scatter_fwd();
    }
    if (signal)
      break;
    if (!converged)
    {
      const auto& last = monitor.history.back();
      char what[1024];
      std::snprintf(what, sizeof(what),
                    "Newton did not converge at t = %g (k = %g) in %d iterations: %s"
                    "relative residuals u = %s, phi = %s; relative updates u = %s, phi = %s%s%s",
                    t, k, its,
                    linear_failure.empty() ? "" : (linear_failure + "; ").c_str(),
                    sci(last.at("u").relative).c_str(),
                    sci(last.at("phi").relative).c_str(),
                    sci(last.at("u").update).c_str(),
                    sci(last.at("phi").update).c_str(),
                    last.contains("charge")
                        ? (", floating charges = " + sci(last.at("charge").relative)).c_str()
                        : "",
                    imbalance <= balance_tolerance
                        ? ""
                        : (", forces unbalanced by " + sci(imbalance)
                           + " of the contact and support forces (too ill-conditioned for "
                             "double precision?"
                           + (problem.contact_pressure
                                  ? " contact.c_p = "
                                        + sci(problem.model.constants.at("c_p")->value[0])
                                  : std::string())
                           + ")")
                              .c_str());
      const std::string action = steps.reject();
      record.reject(report, action);
      if (action == "stop")
        record.fail(std::string(what) + stalled(monitor.history, settings.newton.rtol) + "; gave up after "
                    + std::to_string(steps.max_halvings) + " halvings of the time step");
      int rank;
      MPI_Comm_rank(comm, &rank);
      if (rank == 0)
        std::printf("[%s] %s: retrying with k = %g\n", record.label().c_str(), what, steps.k);
      continue;
    }
    steps.accept();
    // Recorded while x_prev is still u_{n-1}: the stress holds the velocity
    record.accept(state_now(), report, {std::span<const double>(xa), xp, system.x_assembled},
                  steps.done(), run_timing());
    std::copy(xp.begin(), xp.end(), x_prev2.begin());
    std::copy(xa.begin(), xa.end(), xp.begin());
  }
  if (signal)
    record.interrupt(signal, run_timing());
  return record.summary();
}
} // namespace piezocontact
