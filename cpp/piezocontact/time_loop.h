// Backward Euler time loop on a Problem's forms with Newton (newton.h):
// predictor, per-field convergence, exact LU reuse, step halving, signals,
// checkpoints and --resume; each accepted step goes to the outputs, the
// summary and an observer.
#pragma once

#include "config.h"
#include "interrupt.h"
#include "problem.h"
#include "record.h"
#include "settings.h"

#include <filesystem>
#include <functional>
#include <mpi.h>

namespace piezocontact
{
/// Run the time loop on `problem`, writing DIR (output.h). `summary` is
/// either the head of a fresh run's summary ("solver" and what the caller
/// records: config, files...) or, with `resume`, the summary.json of DIR to
/// continue from its checkpoint. Returns the final summary. Throws
/// NewtonFailure, Interrupted, OutputError (the summary says so first).
json run(Problem& problem, const RunSettings& settings, const std::filesystem::path& out_dir,
         json summary, bool resume, bool progress, const StepObserver& observer = nullptr);
} // namespace piezocontact
