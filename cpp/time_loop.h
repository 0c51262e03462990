// Backward Euler time loop with dolfinx's NewtonSolver on the compiled forms,
// the step-by-step procedure of the Python twin (demos/piezocontact/twin.py).
#pragma once

#include "config.h"

#include <filesystem>
#include <mpi.h>

namespace piezo
{
/// Newton did not converge; the message names the time and the residuals
struct NewtonFailure : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Run the time loop, write DIR/summary.json etc.; return the summary
json run(const json& cfg, const std::filesystem::path& out_dir, MPI_Comm comm,
         bool progress, const std::string& source);
} // namespace piezo
