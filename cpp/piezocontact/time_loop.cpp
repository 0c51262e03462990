#include "time_loop.h"
#include "diagnostics.h"
#include "fieldwise.h"
#include "nonlinear_system.h"
#include "checkpoint.h"
#include "interrupt.h"
#include "output.h"
#include "problem.h"
#include "step_control.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/nls/NewtonSolver.h>
#include <iostream>
#include <petscksp.h>

namespace piezocontact
{
using namespace dolfinx;
namespace
{
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// With pc_type fieldsplit, PETSc is told which dofs are u and which phi
/// (fieldsplit_u_*, fieldsplit_phi_* options then configure each block)
void set_field_splits(KSP ksp, const Problem& problem)
{
  PC pc;
  KSPGetPC(ksp, &pc);
  PetscBool is_fieldsplit;
  PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &is_fieldsplit);
  if (!is_fieldsplit)
    return;
  const auto& imap = *problem.W->dofmap()->index_map;
  const std::int32_t owned = imap.size_local() * problem.W->dofmap()->index_map_bs();
  const std::int64_t offset = imap.local_range()[0] * problem.W->dofmap()->index_map_bs();
  for (const auto& [name, dofs] : {std::pair{"u", &problem.u_dofs},
                                    std::pair{"phi", &problem.phi_dofs}})
  {
    std::vector<PetscInt> global;
    for (auto d : *dofs)
      if (d < owned)
        global.push_back(offset + d);
    std::sort(global.begin(), global.end());
    IS is;
    ISCreateGeneral(problem.comm, global.size(), global.data(), PETSC_COPY_VALUES, &is);
    // u comes in (x, y) pairs per node: say so, for nodal AMG on that block
    bool pairs = std::string(name) == "u" and global.size() % 2 == 0;
    for (std::size_t i = 0; pairs and i < global.size(); i += 2)
      pairs = global[i + 1] == global[i] + 1 and global[i] % 1 == 0;
    int all_pairs = pairs;
    MPI_Allreduce(MPI_IN_PLACE, &all_pairs, 1, MPI_INT, MPI_LAND, problem.comm);
    if (all_pairs)
      ISSetBlockSize(is, 2);
    PCFieldSplitSetIS(pc, name, is);
    ISDestroy(&is);
  }
}

json fields_json(const std::map<std::string, FieldNorms>& norms,
                 double FieldNorms::*member)
{
  json out = json::object();
  for (const char* f : {"u", "phi"})
  {
    const double v = norms.at(f).*member;
    out[f] = std::isnan(v) ? json(nullptr) : json(v); // undefined while x_f = 0
  }
  return out;
}

json step_record(const Problem& problem, const Probes& probes,
                 const ContactGeometry& contact, const FieldwiseConvergence& monitor,
                 const NonlinearSystem& system, double t, int its, int factorisations)
{
  const auto& final = monitor.history.back();
  json step = json::object();
  step["t"] = t;
  step["newton_iterations"] = its;
  step["factorisations"] = factorisations;
  step["residual_norms"] = fields_json(final, &FieldNorms::residual);
  step["relative_residuals"] = fields_json(final, &FieldNorms::relative);
  step["residual_history"] = json::array();
  for (const auto& h : monitor.history)
    step["residual_history"].push_back(fields_json(h, &FieldNorms::relative));
  step["probes"] = json::array();
  const auto values = probes.evaluate(problem);
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    step["probes"].push_back({{"point", {probes.points[i][0], probes.points[i][1]}},
                              {"u", {values[i][0], values[i][1]}},
                              {"phi", values[i][2]}});
  }
  step["contact_force"] = contact_force(problem);
  const auto gap = contact.max_normal_gap(problem, problem.model.constants.at("g")->value[0]);
  step["max_penetration"] = gap ? json(*gap) : json(nullptr);
  step["reactions"] = json::object();
  for (const auto& [name, r] : system.reactions) // of the converged iterate
    step["reactions"][name] = {r[0], r[1]};
  return step;
}

std::string numbered(const char* format, int n)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, n);
  return buf;
}

std::string sci(double v)
{
  if (std::isnan(v))
    return "undefined";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3e", v);
  return buf;
}

json stats(const OperationStats& s) { return {{"count", s.count}, {"seconds", s.seconds}}; }

double callback_seconds(const NonlinearSystem& sys)
{
  return sys.residual.seconds + sys.jacobian.seconds + sys.contact_jacobian.seconds
         + sys.factorisation.seconds;
}

/// Where the time went. Triangular solves: the Newton time not spent in the
/// callbacks (one KSPSolve per iteration, plus vector updates); the first
/// Jacobian and factorisation, made before the loop, count in theirs.
/// Time spent writing outputs, per kind: what the safe writes cost
struct OutputStats
{
  OperationStats step_files, checkpoint, summary;
};

/// Run `action`, adding its wall time to `s`
template <typename F>
void timed(OperationStats& s, F&& action)
{
  const auto t0 = Clock::now();
  action();
  s.seconds += seconds_since(t0);
  ++s.count;
}

json timing(const NonlinearSystem& sys, const OutputStats& out, double total_s,
            double newton_s, double callbacks_in_newton, int newton_its)
{
  const double solves = std::max(0.0, newton_s - callbacks_in_newton);
  return {{"total_s", total_s},
          {"output_s", out.step_files.seconds + out.checkpoint.seconds + out.summary.seconds},
          {"output",
           {{"step_files", stats(out.step_files)},
            {"checkpoint", stats(out.checkpoint)},
            {"summary", stats(out.summary)}}},
          {"assembly_s", sys.residual.seconds + sys.jacobian.seconds + sys.contact_jacobian.seconds},
          {"solve_s", sys.factorisation.seconds + solves},
          {"operations",
           {{"residual", stats(sys.residual)},
            {"jacobian", stats(sys.jacobian)},
            {"contact_jacobian", stats(sys.contact_jacobian)},
            {"factorisation", stats(sys.factorisation)},
            {"triangular_solve", {{"count", newton_its}, {"seconds", solves}}},
            {"reused_factorisation", sys.reused}}}};
}

void print_progress(const std::string& label, int n, const json& step)
{
  const json& r = step["relative_residuals"];
  auto e = [](const json& v, int digits, const char* missing)
  {
    if (v.is_null())
      return std::string(missing);
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.*e", digits, v.get<double>());
    return std::string(buf);
  };
  std::printf("[%s] step %4d  t = %.4g  newton %d  rel. residual u %s phi %s"
              "  max(u.nu - g) = %s\n",
              label.c_str(), n, step["t"].get<double>(), step["newton_iterations"].get<int>(),
              e(r["u"], 1, "undefined").c_str(), e(r["phi"], 1, "undefined").c_str(),
              e(step["max_penetration"], 3, "n/a").c_str());
  std::fflush(stdout);
}
} // namespace

json run(Problem& problem, const RunSettings& settings, const std::filesystem::path& out_dir,
         json summary, bool resume, bool progress, const StepObserver& observer)
{
  const auto t_start = Clock::now();
  const MPI_Comm comm = problem.comm;
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const std::string label = summary.value("solver", "cpp");
  Probes probes(problem, settings.probes, summary.value("config_file", "config"));
  ContactGeometry contact(problem);
  const auto& imap = *problem.W->dofmap()->index_map;
  const int bs = problem.W->dofmap()->index_map_bs();
  FieldwiseConvergence monitor({{"u", problem.u_dofs}, {"phi", problem.phi_dofs}},
                               problem.bc_dofs, imap.size_local() * bs, settings.newton.rtol,
                               settings.newton.atol, comm);
  Vec x = la::petsc::create_vector_wrap(*problem.x->x());
  nls::petsc::NewtonSolver newton(comm);
  NonlinearSystem system(problem, monitor, newton.get_krylov_solver().ksp(),
                         settings.reuse_factorisation);
  newton.setF([&system](const Vec x, Vec r) { system.F(x, r); }, system.b);
  newton.setJ([&system](const Vec x, Mat A) { system.J(x, A); }, system.A);
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
  newton.set_convergence_check(
      [&monitor, &problem, &signal](const nls::petsc::NewtonSolver&, const Vec r)
      {
        PetscInt n;
        VecGetLocalSize(r, &n);
        const PetscScalar* ra;
        VecGetArrayRead(r, &ra);
        const bool ok = monitor.check(problem.x->x()->array().subspan(0, n),
                                      std::span<const double>(ra, n));
        VecRestoreArrayRead(r, &ra);
        PetscReal norm;
        VecNorm(r, NORM_2, &norm);
        signal = agreed_interrupt(problem.comm);
        return std::pair<double, bool>(norm, ok or signal != 0);
      });
  newton.max_it = settings.newton.max_iterations;
  newton.report = false;
  newton.error_on_nonconvergence = false;
  // After the constructor, which writes its own nls_solve_ defaults
  for (const auto& [key, value] : settings.petsc_options)
    la::petsc::options::set("nls_solve_" + key, value);
  newton.get_krylov_solver().set_from_options();
  set_field_splits(newton.get_krylov_solver().ksp(), problem);

  StepState state;
  if (resume)
  {
    state = StepState::from_json(summary["checkpoint"]);
    // What came after the checkpoint is done again
    auto& steps = summary["steps"];
    steps.erase(steps.begin() + state.step, steps.end());
    auto& events = summary["events"];
    events.erase(events.begin() + state.events, events.end());
    summary.erase("error");
    summary.erase("signal");
    if (!summary.contains("resumed"))
      summary["resumed"] = json::array();
    summary["resumed"].push_back({{"step", state.step}, {"t", state.t}, {"mpi_size", size}});
    summary["mpi_size"] = size;
  }
  else
  {
    json head = std::move(summary);
    summary = {{"solver", label}, {"dofs", imap.size_global() * bs}, {"mpi_size", size}};
    for (auto& [key, value] : head.items())
      summary[key] = value;
    summary["steps"] = json::array();
    summary["events"] = json::array();
    summary["timing"] = json::object();
  }
  summary["status"] = "running";
  OutputStats output_stats;
  const auto write_summary = [&]
  {
    timed(output_stats.summary,
          [&]
          {
            collectively(comm, rank == 0,
                         [&] { write_json_atomic(out_dir / "summary.json", summary); });
          });
  };
  // A write error ends the run; the summary says so if it can still be written
  const auto fail_on_output = [&](const OutputError& e)
  {
    summary["status"] = "failed";
    summary["error"] = e.what();
    try
    {
      write_summary();
    }
    catch (const OutputError&)
    {
    }
    VecDestroy(&x);
    throw e;
  };

  StepControl steps(settings.T, settings.steps, settings.newton.max_step_halvings);
  auto xa = problem.x->x()->mutable_array();
  auto xp = problem.x_prev->x()->mutable_array();
  std::vector<double> x_prev2(xp.begin(), xp.end()); // u_{n-2}, for the predictor
  const StateFile state_file(problem);
  const auto checkpoint = [&]
  {
    StepState s{steps.accepted, steps.nominal_steps(), steps.t, steps.k, steps.k_last,
                system.k_assembled, summary["events"].size(),
                "checkpoint/" + numbered("state_%06d.npy", steps.accepted)};
    if (rank == 0)
      std::filesystem::create_directories(out_dir / "checkpoint");
    timed(output_stats.checkpoint,
          [&]
          {
            state_file.write(out_dir / s.file,
                             {std::span<const double>(xp), x_prev2, system.x_assembled});
          });
    return s;
  };
  std::optional<Writer> writer;
  try
  {
    writer.emplace(problem, settings.output, out_dir, state.step);
    if (resume)
    {
      // The Jacobian in use at the checkpoint, rebuilt where it was
      // assembled: the same LU and convergence scaling as if never stopped
      std::vector<double> xJ(xa.size());
      try
      {
        state_file.read(out_dir / state.file, {xp, x_prev2, xJ});
      }
      catch (const std::runtime_error& e)
      {
        throw ConfigError(std::string("cannot resume: ") + e.what());
      }
      std::copy(xJ.begin(), xJ.end(), xa.begin());
      problem.model.constants.at("k")->value[0] = state.k_J;
      system.J(x, system.A);
      std::copy(xp.begin(), xp.end(), xa.begin());
      steps.restore(state.nominal, state.t, state.k, state.k_last, state.step);
      if (rank == 0 and progress)
        std::printf("[%s] resuming at step %d, t = %.6g\n", label.c_str(), state.step, state.t);
    }
    else
    {
      system.J(x, system.A); // initial scaling D (and first factorisation)
      state = checkpoint();
    }
    summary["checkpoint"] = state.to_json();
    write_summary();
  }
  catch (const OutputError& e)
  {
    fail_on_output(e);
  }
  const double callbacks_before = callback_seconds(system);
  double newton_s = 0.0;
  int newton_its = 0;
  while (!steps.done() and !(signal = agreed_interrupt(comm)))
  {
    const auto [t, k] = steps.attempt();
    problem.set_time(t, k); // k, and loads and Dirichlet data at t_n
    // Predictor u^0 = u_{n-1} + k du_{n-1}, phi^0 = phi_{n-1}; then the BCs
    for (auto d : problem.u_dofs)
      xa[d] = xp[d] + k / steps.k_last * (xp[d] - x_prev2[d]);
    for (const auto& bc : problem.bcs)
      bc->set(xa);
    problem.x->x()->scatter_fwd();
    monitor.history.clear();
    const int f0 = system.factorisation.count;
    const auto t0 = Clock::now();
    const auto [its, converged] = newton.solve(x);
    problem.x->x()->scatter_fwd();
    newton_s += seconds_since(t0);
    newton_its += its;
    if (signal)
    {
      std::copy(xp.begin(), xp.end(), xa.begin()); // the step is abandoned
      problem.x->x()->scatter_fwd();
      break;
    }
    if (!converged)
    {
      const auto& last = monitor.history.back();
      char what[256];
      std::snprintf(what, sizeof(what),
                    "Newton did not converge at t = %g (k = %g) in %d iterations: "
                    "relative residuals u = %s, phi = %s",
                    t, k, its, sci(last.at("u").relative).c_str(),
                    sci(last.at("phi").relative).c_str());
      std::copy(xp.begin(), xp.end(), xa.begin()); // back to the last accepted state
      problem.x->x()->scatter_fwd();
      const std::string event = steps.reject();
      summary["events"].push_back({{"t", t},
                                   {"k", k},
                                   {"newton_iterations", its},
                                   {"relative_residuals", fields_json(last, &FieldNorms::relative)},
                                   {"action", event}});
      if (event == "stop")
      {
        summary["status"] = "failed";
        summary["error"] = std::string(what) + "; gave up after "
                           + std::to_string(steps.max_halvings)
                           + " halvings of the time step";
        try
        {
          write_summary();
        }
        catch (const OutputError&)
        {
        }
        VecDestroy(&x);
        throw NewtonFailure(summary["error"].get<std::string>());
      }
      if (rank == 0)
        std::printf("[%s] %s: retrying with k = %g\n", label.c_str(), what, steps.k);
      continue;
    }
    steps.accept();
    problem.update_fields();
    json step = step_record(problem, probes, contact, monitor, system, t, its,
                            system.factorisation.count - f0);
    step["krylov_iterations"] = newton.krylov_iterations(); // 1 per solve with LU
    step["k"] = k;
    if (!problem.model.squared_errors.empty())
      step["errors"] = problem.errors();
    std::copy(xp.begin(), xp.end(), x_prev2.begin());
    std::copy(xa.begin(), xa.end(), xp.begin());
    // Step files, then its checkpoint, then the summary that points to both:
    // a kill at any instant leaves a summary whose every step is on disk
    const StepState previous = state;
    try
    {
      timed(output_stats.step_files,
            [&] { writer->write_step(steps.accepted, t, steps.done()); });
      state = checkpoint();
      summary["steps"].push_back(step);
      summary["checkpoint"] = state.to_json();
      summary["status"] = steps.done() ? "completed" : "running";
      summary["timing"] = timing(system, output_stats, seconds_since(t_start), newton_s,
                                 callback_seconds(system) - callbacks_before, newton_its);
      write_summary();
    }
    catch (const OutputError& e)
    {
      if (summary["steps"].size() > std::size_t(previous.step))
        summary["steps"].erase(summary["steps"].end() - 1);
      summary["checkpoint"] = previous.to_json();
      if (rank == 0 and state.file != previous.file)
      {
        // unreferenced: its space may let the summary say what went wrong
        std::error_code ec;
        std::filesystem::remove(out_dir / state.file, ec);
      }
      fail_on_output(e);
    }
    if (rank == 0)
    {
      std::error_code ec;
      std::filesystem::remove(out_dir / previous.file, ec);
      if (progress)
        print_progress(label, steps.accepted, step);
    }
    if (observer)
      observer(steps.accepted, step);
  }
  if (signal)
  {
    summary["status"] = "interrupted";
    summary["signal"] = signal_name(signal);
    summary["timing"] = timing(system, output_stats, seconds_since(t_start), newton_s,
                               callback_seconds(system) - callbacks_before, newton_its);
    try
    {
      write_summary();
    }
    catch (const OutputError& e)
    {
      fail_on_output(e);
    }
    VecDestroy(&x);
    throw Interrupted(signal, steps.accepted, steps.t);
  }
  VecDestroy(&x);
  return summary;
}
} // namespace piezocontact
