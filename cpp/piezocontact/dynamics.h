// Dynamic analyses linearised about a state (config "analysis"; SPEC:
// dynamics): natural modes (modal.h) or the response to time-harmonic data
// (harmonic.h), reported in summary.json ("modes", "harmonic") and in XDMF
// files (modes.xdmf, harmonic.xdmf).
#pragma once

#include "problem.h"
#include "record.h"
#include "settings.h"

#include <filesystem>
#include <string>

namespace piezocontact
{
/// The eigensolver converged fewer modes than asked (exit 3, as a Newton
/// failure: the solver, not the input); the summary keeps those found
struct AnalysisFailure : NewtonFailure
{
  using NewtonFailure::NewtonFailure;
};

/// Run the analysis of `settings.analysis` about the Problem's state and
/// add its results to `summary` (written to DIR/summary.json). `source`
/// names the config in messages. Throws ConfigError, AnalysisFailure,
/// LinearSolveFailure, OutputError. Collective.
json analyse(Problem& p, const RunSettings& settings, const std::filesystem::path& dir,
             json summary, const std::string& source);
} // namespace piezocontact
