// The record of a run, whichever loop solves it: each accepted step's
// diagnostics (probes, contact force, penetration, reactions, errors), its
// files (output.h), its checkpoint (checkpoint.h) and summary.json, in an
// order that leaves every reported step on disk whatever instant a kill
// lands. The C++ time loop and the Python reference engine both write
// through it: one summary schema.
#pragma once

#include "acceptance.h"
#include "checkpoint.h"
#include "config.h"
#include "diagnostics.h"
#include "fieldwise.h"
#include "interrupt.h"
#include "output.h"
#include "problem.h"
#include "settings.h"
#include "timing.h"

#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

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
        signum(signum), steps(steps), t(t)
  {
  }
  int signum, steps;
  double t;
};

/// Called on every rank after each accepted step with its number and record
using StepObserver = std::function<void(int step, const json& record)>;

/// How an accepted step was solved: the solver's part of its record
struct SolveReport
{
  double t = 0.0, k = 0.0;
  int newton_iterations = 0, factorisations = 0, krylov_iterations = 0;
  /// Per-field norms of each iterate's residual (the last: the accepted one)
  std::vector<std::map<std::string, FieldNorms>> history;
  /// The unconstrained residual at the accepted state (owned entries, which
  /// may be none on a rank), for reactions, balance and charges; if absent
  /// (on every rank alike), assembled for the purpose
  std::optional<std::span<const double>> residual;
  /// The acceptance rule as the loop judged the state (acceptance.h);
  /// Record judges the balance again from `residual`
  Acceptance acceptance;
};

/// x_n, x_{n-1} and x_J (the iterate the Jacobian in use was assembled at)
using StateViews = std::array<std::span<const double>, 3>;

class Record
{
public:
  /// A fresh run: `summary` is its head ("solver", config...); resumed: the
  /// summary.json of DIR, cut back to its checkpoint
  Record(Problem& problem, const RunSettings& settings, std::filesystem::path dir,
         json summary, bool resume, bool progress, StepObserver observer);
  ~Record();

  /// The step control state of the checkpoint continued from (step 0 fresh)
  const StepState& checkpoint() const { return _state; }
  /// Read the states of the checkpoint (resume). Collective.
  void read_states(const States& states) const;
  /// Start: a fresh run writes its step-0 checkpoint; then the summary
  void begin(const StepState& state, const StateViews& states);
  /// An accepted step (problem.x holds it): record, files, checkpoint,
  /// summary, progress line, observer. `state` is the step control after it.
  json accept(StepState state, const SolveReport& report, const StateViews& states,
              bool final, const json& timing);
  /// A rejected try; `action`: "halve k" or "stop"
  void reject(const SolveReport& report, const std::string& action);
  /// Number of events so far (a checkpoint remembers it)
  std::size_t events() const;
  /// The summary says "failed" with `error`; throws NewtonFailure
  [[noreturn]] void fail(const std::string& error);
  /// A datum of the config turned out bad at this step (an expression not
  /// finite at t): status "failed" with the message, then throw it as the
  /// ConfigError it is (exit 2)
  [[noreturn]] void refuse(const std::string& error);
  /// The summary says "interrupted"; throws Interrupted
  [[noreturn]] void interrupt(int signum, const json& timing);
  /// Seconds spent writing outputs, per kind, for the summary's timing
  json output_timing() const;
  const std::string& label() const { return _label; }
  /// No output folder: nothing is written (no files, checkpoint or summary)
  bool in_memory() const { return _dir.empty(); }
  const json& summary() const { return _summary; }

private:
  void write_summary();
  /// status "failed" with `error`, the summary written if it can be
  void mark_failed(const std::string& error);
  [[noreturn]] void fail_on_output(const OutputError& e);
  /// fail() unless the step meets the acceptance rule, its balance judged
  /// from the accepted state's residual
  void check_acceptance(const json& step, Acceptance acceptance, const ForceBalance& balance);
  /// Potential, charge (int D.nu and by reaction, from the unconstrained
  /// residual r: owned entries) and current of each electrode
  json electrodes_json(std::span<const double> r, double k) const;
  StepState write_checkpoint(StepState state, const StateViews& states);

  Problem& _problem;
  const double _rtol; ///< Newton's, for the acceptance rule
  std::filesystem::path _dir;
  bool _progress;
  StepObserver _observer;
  std::string _label;
  json _summary;
  StepState _state;
  Probes _probes;
  ContactGeometry _contact;
  ObstaclePenetration _obstacles;
  StateFile _state_file;
  std::optional<Writer> _writer;
  OperationStats _step_files, _checkpoints, _summaries, _diagnostics;
};
} // namespace piezocontact
