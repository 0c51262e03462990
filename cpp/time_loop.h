// Backward Euler time loop with dolfinx's NewtonSolver on the compiled forms,
// the step-by-step procedure of the Python twin (demos/piezocontact/twin.py).
#pragma once

#include "config.h"
#include "interrupt.h"

#include <filesystem>
#include <mpi.h>

namespace piezo
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

/// Run the time loop, write DIR/summary.json etc.; return the summary.
/// With `resume` (a summary.json of DIR), continue from its checkpoint.
json run(const json& cfg, const std::filesystem::path& out_dir, MPI_Comm comm,
         bool progress, const std::string& source, const json* resume = nullptr);
} // namespace piezo
