// Typed settings of a run: what the JSON config (config.h) turns into at
// the edge. Nothing below the config layer reads JSON input.
#pragma once

#include "expressions.h"

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace piezocontact
{
/// How a prescribed datum varies in time: datum(t) = value * factor(t)
struct History
{
  enum class Kind
  {
    constant, ///< factor 1 (t > 0, the first step's time and on)
    ramp,     ///< min(t / t_r, 1)
    sine,     ///< sin(2 pi frequency t + phase)
    table     ///< piecewise linear in (t, factor), constant beyond the ends
  };
  Kind kind = Kind::constant;
  double ramp_time = 0.0, frequency = 0.0, phase = 0.0;
  std::vector<std::pair<double, double>> table;
  double factor(double t) const;
};

/// A runtime Constant of the forms scaled by a history: `boundary` names
/// the boundary whose load it is (empty: a Constant shared by every term)
struct TimedConstant
{
  std::string boundary, name;
  History history;
};

/// A datum that varies in space: the field it is interpolated into is
/// `components` (numbers or expressions) times `history`, at every step.
/// `key`: where the config gives it (messages)
struct SpatialDatum
{
  std::string key;
  std::vector<Value> components;
  History history;
};

/// A datum of the forms given by expressions: the field of `name`
/// (Model::data_fields, or load_data_fields of `boundary` when not empty)
struct SpatialLoad
{
  std::string boundary, name;
  SpatialDatum datum;
};

/// Dirichlet data on one named boundary; "exact" takes the model's exact
/// field at the current time
struct DirichletSettings
{
  std::string boundary;
  /// one value per component (a number or an expression); an empty one is
  /// free (rollers, symmetry planes)
  std::optional<std::vector<std::optional<Value>>> displacement;
  bool displacement_exact = false;
  std::optional<Value> potential;
  bool potential_exact = false;
  History displacement_history, potential_history;
  /// a floating electrode: phi is one unknown on the boundary, uniform,
  /// and the charge int D.nu ds on it is `charge` (times its history)
  bool floating = false;
  double charge = 0.0;
  History charge_history;
};

struct NewtonSettings
{
  double rtol = 1e-10, atol = 1e-12;
  int max_iterations = 25;
  int max_step_halvings = 4;
};

struct OutputSettings
{
  bool xdmf = true;
  std::string nodal = "final"; ///< "none", "final" or "all" steps as .npy
};

/// solver.linear: LU (MUMPS), or GMRES with a u/phi block preconditioner
/// (linear_solver.h)
enum class LinearSolver
{
  direct,
  iterative
};

/// A dynamic analysis linearised about a state (config "analysis";
/// dynamics.h)
struct AnalysisSettings
{
  enum class Kind
  {
    none,
    modal,
    harmonic
  };
  Kind kind = Kind::none;
  /// Linearise about the last converged state of the quasistatic run (else
  /// about the initial state, with no time loop)
  bool at_end = false;
  /// modal: how many modes, nearest `target` (Hz; none: the lowest)
  int modes = 0;
  std::optional<double> target;
  /// harmonic: the frequencies (Hz), in the order given
  std::vector<double> frequencies;
};

struct RunSettings
{
  double T = 1.0;
  int steps = 1;
  NewtonSettings newton;
  bool reuse_factorisation = true;
  LinearSolver linear = LinearSolver::direct;
  /// solver.symmetric = "auto": LDL^T when the Jacobian with its electric
  /// rows negated is symmetric (direct solver, PC not set by the user)
  bool symmetric = true;
  /// PETSc options of the linear solver, without our prefix
  std::vector<std::pair<std::string, std::string>> petsc_options;
  std::vector<std::array<double, 3>> probes;
  OutputSettings output;
  std::vector<DirichletSettings> dirichlet;
  AnalysisSettings analysis;
};
} // namespace piezocontact
