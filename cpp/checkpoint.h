// What --resume needs to continue a run exactly as if never stopped: the
// states x_n and x_{n-1} (the predictor extrapolates from both), the iterate
// x_J at which the Jacobian in use was assembled (its LU and the convergence
// test's scaling are rebuilt from it, bit for bit) and the step control.
//
// The states are stored by input vertex (rows) and [u_x, u_y, phi] of x_n,
// x_{n-1}, x_J (columns), gathered on rank 0 into one .npy file: a run can
// be resumed on any number of processes.
#pragma once

#include "problem.h"

#include <array>
#include <filesystem>
#include <span>

namespace piezo
{
struct StepState
{
  int step = 0;       ///< steps accepted
  int nominal = 0;    ///< nominal steps t = n T/N completed
  double t = 0.0, k = 0.0, k_last = 0.0;
  double k_J = 0.0;   ///< k at which the Jacobian in use was assembled
  std::size_t events = 0; ///< length of summary["events"] at this step
  std::string file;   ///< the states, relative to the output directory

  json to_json() const;
  static StepState from_json(const json& j);
};

/// x_n, x_{n-1}, x_J: arrays of problem.W's local dofs (owned and ghost)
using States = std::array<std::span<double>, 3>;

/// Gather the states by input vertex and write them (rank 0). Collective.
void write_states(const std::filesystem::path& path, const Problem& problem,
                  std::array<std::span<const double>, 3> states);

/// Read what write_states wrote into owned and ghost dofs. Collective.
void read_states(const std::filesystem::path& path, const Problem& problem,
                 const States& states);
} // namespace piezo
