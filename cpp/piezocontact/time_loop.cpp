#include "time_loop.h"

#include <limits>
#include "diagnostics.h"
#include "fieldwise.h"
#include "json_input.h"
#include "newton.h"
#include "nonlinear_system.h"
#include "petsc_options.h"
#include "step_control.h"

#include <cmath>
#include <cstdio>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/petsc.h>
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

/// %g, as the messages print times and steps
std::string fmt_g(double v)
{
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", v);
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
/// (data spanning more orders of magnitude than double precision resolves).
/// `brief`: the message already asks about the conditioning (unbalanced
/// forces): the fields only, so that the line stays short
std::string stalled(const std::vector<std::map<std::string, FieldNorms>>& history, double rtol,
                    bool brief)
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
  if (out.empty())
    return "";
  if (brief)
    return " (" + out + " stalled at round-off)";
  return " (" + out + " stalled at round-off for " + std::to_string(window)
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
          {"linear_solver", sys.linear.iterative() ? "iterative" : "direct"},
          {"factorisation", sys.linear.factorisations()},
          {"ldlt_pivoting", sys.linear.pivoting()},
          {"factor_entries", sys.linear.factor_entries},
          {"factor_ordering", sys.linear.factor_ordering},
          {"symmetry_defect", sys.linear.symmetry_defect}};
}

/// The backward Euler loop of one run: configure the solver, then per step
/// predict, try a Newton solve, and accept or reject it; each accepted step
/// goes to the Record. One object per run (run() below).
class TimeLoop
{
public:
  TimeLoop(Problem& problem, const RunSettings& settings, const std::filesystem::path& out_dir,
           json summary, bool resume, bool progress, const StepObserver& observer)
      : _problem(problem), _settings(settings), _comm(problem.comm),
        _record(problem, settings, out_dir, std::move(summary), resume, progress, observer),
        _monitor({{"u", problem.u_dofs}, {"phi", problem.phi_dofs}}, problem.bc_dofs(),
                 problem.W->dofmap()->index_map->size_local()
                     * problem.W->dofmap()->index_map_bs(),
                 settings.newton.rtol, settings.newton.atol, problem.comm),
        _x_vec(la::petsc::create_vector_wrap(*problem.x->x()), false),
        _options(petsc_prefix, solver_options(settings)),
        _newton(problem.comm, petsc_prefix, settings.newton.max_iterations),
        _system(configured(_newton, problem, _monitor, settings)),
        _steps(settings.T, settings.steps, settings.newton.max_step_halvings),
        _xa(compat::mutable_values(*problem.x->x())), _xp(compat::mutable_values(*problem.x_prev->x())),
        _x_prev2(_xp.begin(), _xp.end()), _progress(progress)
  {
    set_callbacks();
    if (resume)
      restore();
    else
      first_jacobian("at the first Jacobian"); // initial scaling D (and first factorisation)
    _record.begin(state_now(), states());
    _callbacks_before = callback_seconds(*_system);
  }

  json run()
  {
    while (!_steps.done() and !(_signal = agreed_interrupt(_comm)))
    {
      const auto [t, k] = _steps.attempt();
      predict(t, k);
      const Attempt attempt = solve(t, k);
      if (_signal or !attempt.converged)
        restart_from_last_state();
      if (_signal)
        break;
      if (attempt.converged)
        accept(attempt.report);
      else
        reject(attempt);
    }
    if (_signal)
      _record.interrupt(_signal, timing_now());
    return _record.summary();
  }

private:
  /// One Newton solve of a step
  struct Attempt
  {
    SolveReport report;
    bool converged = false;
    std::string linear_failure; ///< a failed linear solve, if that ended it
  };

  /// Our defaults (LU by MUMPS, or the iterative solver), then the config's
  static PetscOptionList solver_options(const RunSettings& settings)
  {
    PetscOptionList options = loop_defaults(settings.linear);
    options.insert(options.end(), settings.petsc_options.begin(), settings.petsc_options.end());
    return options;
  }

  /// LDL^T is ours to choose unless the user chose the factorisation
  static bool symmetric_allowed(const RunSettings& settings)
  {
    for (const auto& [key, value] : settings.petsc_options)
      if (key == "pc_type" or key == "pc_factor_mat_solver_type" or key == "ksp_type")
        return false;
    return settings.symmetric and settings.linear == LinearSolver::direct;
  }

  /// The system on the Newton iteration's KSP
  static std::unique_ptr<NonlinearSystem> configured(const Newton& newton, Problem& problem,
                                                     FieldwiseConvergence& monitor,
                                                     const RunSettings& settings)
  {
    return std::make_unique<NonlinearSystem>(problem, monitor, newton.ksp(),
                                             settings.reuse_factorisation, settings.linear,
                                             symmetric_allowed(settings));
  }

  void set_callbacks()
  {
    NonlinearSystem& system = *_system;
    _newton.set_callbacks(
        {.F = [&system](const Vec x, Vec r) { system.F(x, r); },
         .b = system.b.vec(),
         .J = [&system](const Vec x, Mat A) { system.J(x, A); },
         .A = system.A.mat(),
         // A signal on any rank ends the solve too ("converged"; the loop
         // then abandons the step), so that every rank stops at the same
         // iteration.
         .converged = [this](const Vec r) { return converged(r); },
         // x <- x - dx, and the floating potentials with it (floating.h),
         // once the solve is checked
         .update = [&system](const Vec dx, Vec x) { system.update(dx, x); }});
  }

  /// The acceptance rule (acceptance.h) at an iterate
  std::pair<double, bool> converged(const Vec r)
  {
    PetscInt n;
    VecGetLocalSize(r, &n);
    const PetscScalar* ra;
    VecGetArrayRead(r, &ra);
    _acceptance.fields = _monitor.check(compat::values(*_problem.x->x()).subspan(0, n),
                                        std::span<const double>(ra, n));
    VecRestoreArrayRead(r, &ra);
    // an update that solved a locally linear problem exactly needs no
    // second one to bound its error (fieldwise.h)
    if (!_acceptance.fields and _monitor.residuals_converged())
      _acceptance.fields = _system->exact_update();
    if (!_system->floating.empty())
    {
      const double relative = _system->floating.relative_residual();
      _monitor.history.back()["charge"] = {_system->floating.residual_norm(), relative, relative};
      _acceptance.charges = relative;
    }
    _acceptance.imbalance = force_imbalance(_problem, _system->balance);
    PetscReal norm;
    VecNorm(r, NORM_2, &norm);
    _signal = agreed_interrupt(_problem.comm);
    return {norm, _acceptance.accepted(_settings.newton.rtol) or _signal != 0};
  }

  /// The Jacobian made before the loop (and its factorisation, or the
  /// floating electrodes' first solves): a failed linear solve there ends
  /// the run as one inside it would after its last halving
  void first_jacobian(const std::string& when)
  {
    try
    {
      _system->J(_x_vec.vec(), _system->A.mat());
    }
    catch (const LinearSolveFailure& e)
    {
      _record.fail(std::string(e.what()) + " " + when + (e.hint.empty() ? "" : ": " + e.hint));
    }
  }

  /// --resume: the states of the checkpoint, and the Jacobian in use there
  /// rebuilt where it was assembled (the same LU and convergence scaling as
  /// if never stopped)
  void restore()
  {
    const StepState& state = _record.checkpoint();
    std::vector<double> xJ(_xa.size());
    _record.read_states({_xp, _x_prev2, xJ});
    std::copy(xJ.begin(), xJ.end(), _xa.begin());
    _problem.model.constants.at("k")->value[0] = state.k_J;
    first_jacobian("at the resumed Jacobian");
    std::copy(_xp.begin(), _xp.end(), _xa.begin());
    _steps.restore(state.nominal, state.t, state.k, state.k_last, state.step);
    int rank;
    MPI_Comm_rank(_comm, &rank);
    if (_progress and rank == 0)
      std::printf("[%s] resuming at step %d, t = %.6g\n", _record.label().c_str(), state.step,
                  state.t);
  }

  /// k, loads and Dirichlet data at t_n; the predictor u^0 = u_{n-1} + k
  /// du_{n-1}, phi^0 = phi_{n-1}; then the BCs
  void predict(double t, double k)
  {
    try
    {
      _problem.set_time(t, k);
    }
    catch (const ConfigError& e) // an expression of t not finite now
    {
      _record.refuse(e.what());
    }
    for (auto d : _problem.u_dofs)
      _xa[d] = _xp[d] + k / _steps.k_last * (_xp[d] - _x_prev2[d]);
    _problem.hold_floating_potentials(_xp); // phi^0 = phi_{n-1} there too
    for (const auto& bc : _problem.bcs())
      compat::set_bc_values(*bc, _xa);
    _problem.x->x()->scatter_fwd();
  }

  Attempt solve(double t, double k)
  {
    _monitor.history.clear();
    _acceptance = {};
    const int f0 = _system->factorisation.count;
    compat::Timer newton_timer("piezocontact: Newton solve");
    std::pair<int, bool> outcome;
    Attempt attempt;
    try
    {
      outcome = _newton.solve(_x_vec.vec());
    }
    catch (const LinearSolveFailure& e)
    {
      if (!e.retry)
        _record.fail(std::string(e.what()) + " at t = " + json(t).dump()
                     + (e.hint.empty() ? "" : ": " + e.hint));
      outcome = {_newton.iteration(), false};
      attempt.linear_failure = e.what();
    }
    catch (const std::runtime_error& e) // a PETSc call failed (QuietPetscErrors)
    {
      _record.fail("the linear solver failed at t = " + json(t).dump() + ": "
                   + printable(std::string(e.what()), 300));
    }
    const auto [its, converged] = outcome;
    _problem.x->x()->scatter_fwd();
    _newton_s += newton_timer.stop();
    _newton_its += its;
    attempt.converged = converged;
    attempt.report = {t,
                      k,
                      its,
                      _system->factorisation.count - f0,
                      _newton.krylov_iterations(),
                      _monitor.history,
                      std::span<const double>(_system->unconstrained),
                      _acceptance};
    return attempt;
  }

  /// Back to the last accepted state
  void restart_from_last_state()
  {
    std::copy(_xp.begin(), _xp.end(), _xa.begin());
    _problem.x->x()->scatter_fwd();
  }

  void accept(const SolveReport& report)
  {
    _steps.accept();
    // Recorded while x_prev is still u_{n-1}: the stress holds the velocity
    _record.accept(state_now(), report,
                   {std::span<const double>(_xa), _xp, _system->x_assembled}, _steps.done(),
                   timing_now());
    std::copy(_xp.begin(), _xp.end(), _x_prev2.begin());
    std::copy(_xa.begin(), _xa.end(), _xp.begin());
  }

  /// A failed solve: retry with k halved, or stop (exit 3) after the last
  /// halving
  void reject(const Attempt& attempt)
  {
    const std::string what = failure(attempt);
    const std::string action = _steps.reject();
    _record.reject(attempt.report, action);
    if (action == "stop")
      _record.fail(what + stalled(_monitor.history, _settings.newton.rtol, !_acceptance.balanced())
                   + "; gave up after "
                   + std::to_string(_steps.max_halvings) + " halvings of the time step");
    int rank;
    MPI_Comm_rank(_comm, &rank);
    if (rank == 0)
      std::printf("[%s] %s: retrying with k = %g\n", _record.label().c_str(), what.c_str(),
                  _steps.k);
  }

  /// What a failed solve left: the residuals, updates, charges and balance
  std::string failure(const Attempt& attempt) const
  {
    const auto& last = _monitor.history.back();
    const SolveReport& r = attempt.report;
    std::string what = "Newton did not converge at t = " + fmt_g(r.t) + " (k = " + fmt_g(r.k)
                       + ") in " + std::to_string(r.newton_iterations) + " iterations: "
                       + (attempt.linear_failure.empty() ? "" : attempt.linear_failure + "; ")
                       + "relative residuals u = " + sci(last.at("u").relative)
                       + ", phi = " + sci(last.at("phi").relative) + "; relative updates u = "
                       + sci(last.at("u").update) + ", phi = " + sci(last.at("phi").update);
    if (last.contains("charge"))
      what += ", floating charges = " + sci(last.at("charge").relative);
    return what + imbalance_clause(_acceptance, _problem);
  }

  StepState state_now() const
  {
    StepState s;
    s.step = _steps.accepted;
    s.nominal = _steps.nominal_steps();
    s.t = _steps.t;
    s.k = _steps.k;
    s.k_last = _steps.k_last;
    s.k_J = _system->k_assembled;
    return s;
  }

  StateViews states() const
  {
    return {std::span<const double>(_xp), _x_prev2, _system->x_assembled};
  }

  json timing_now() const
  {
    return timing(*_system, _total.elapsed(), _newton_s,
                  callback_seconds(*_system) - _callbacks_before, _newton_its);
  }

  const compat::Timer _total{"piezocontact: run"};
  Problem& _problem;
  const RunSettings& _settings;
  const MPI_Comm _comm;
  Record _record;
  FieldwiseConvergence _monitor;
  la::petsc::Vector _x_vec;
  const ScopedPetscOptions _options; ///< before the Newton's KSP reads them
  Newton _newton;
  std::unique_ptr<NonlinearSystem> _system;
  StepControl _steps;
  std::span<double> _xa, _xp;
  std::vector<double> _x_prev2; ///< u_{n-2}, for the predictor
  const bool _progress;
  int _signal = 0;
  Acceptance _acceptance; ///< the rule at the last iterate
  double _callbacks_before = 0.0, _newton_s = 0.0;
  int _newton_its = 0;
};
} // namespace

json run(Problem& problem, const RunSettings& settings, const std::filesystem::path& out_dir,
         json summary, bool resume, bool progress, const StepObserver& observer)
{
  return TimeLoop(problem, settings, out_dir, std::move(summary), resume, progress, observer)
      .run();
}
} // namespace piezocontact
