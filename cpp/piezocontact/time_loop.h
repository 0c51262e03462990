// Backward Euler time loop on a Problem's forms with dolfinx's NewtonSolver:
// predictor, per-field convergence, exact LU reuse, step halving, signals,
// checkpoints and --resume; each accepted step goes to the outputs, the
// summary and an observer.
#pragma once

#include "config.h"
#include "interrupt.h"
#include "problem.h"
#include "settings.h"

#include <filesystem>
#include <functional>
#include <mpi.h>

namespace piezocontact
{
/// Newton did not converge; the message names the time and the residuals
struct NewtonFailure : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// A signal (SIGINT, SIGTERM) ended the run after `steps` accepted steps;
/// the summary says "interrupted"
struct Interrupted : std::runtime_error
{
  Interrupted(int signum, int steps, double t)
      : std::runtime_error("interrupted by " + signal_name(signum) + " after step "
                           + std::to_string(steps) + " (t = " + json(t).dump()
                           + "); continue with --resume"),
        signum(signum)
  {
  }
  int signum;
};

/// Called on every rank after each accepted step with its number and its
/// record in the summary
using StepObserver = std::function<void(int step, const json& record)>;

/// Run the time loop on `problem`, writing DIR (output.h). `summary` is
/// either the head of a fresh run's summary ("solver" and what the caller
/// records: config, files...) or, with `resume`, the summary.json of DIR to
/// continue from its checkpoint. Returns the final summary. Throws
/// NewtonFailure, Interrupted, OutputError (the summary says so first).
json run(Problem& problem, const RunSettings& settings, const std::filesystem::path& out_dir,
         json summary, bool resume, bool progress, const StepObserver& observer = nullptr);
} // namespace piezocontact
