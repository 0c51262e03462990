// What --resume needs to continue a run exactly as if never stopped: the
// states x_n and x_{n-1} (the predictor extrapolates from both), the iterate
// x_J at which the Jacobian in use was assembled (its LU and the convergence
// test's scaling are rebuilt from it, bit for bit) and the step control.
//
// The states are stored by node (rows) and [u_x, u_y, phi] of x_n, x_{n-1},
// x_J (columns), gathered on rank 0 into one .npy file: a run can be resumed
// on any number of processes. A vertex's row is its input index (P1: the
// whole table); the other nodes of a higher degree (on edges, faces, inside
// cells) follow, ordered by where they sit (the input vertices of their
// entity and their barycentric coordinates on it): every dof is stored.
#pragma once

#include "config.h"
#include "problem.h"

#include <array>
#include <filesystem>
#include <span>

namespace piezocontact
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

/// The states' file: which table entry each dof goes to is worked out once
class StateFile
{
public:
  explicit StateFile(const Problem& problem); // collective

  /// Gather the states by input vertex and write them (rank 0). Collective.
  void write(const std::filesystem::path& path,
             std::array<std::span<const double>, 3> states) const;

  /// Read what write() wrote into owned and ghost dofs. Collective.
  void read(const std::filesystem::path& path, const States& states) const;

private:
  MPI_Comm _comm;
  std::size_t _rows;  ///< largest input vertex index + 1, + the other nodes
  std::size_t _width; ///< d + 1: u and phi at one vertex
  /// W-dofs and their table slot (row * 9 + column of x_n): all local ones
  /// (to read), and the owned ones first (to write)
  std::vector<std::int32_t> _dofs;
  std::vector<std::int64_t> _slots;
  std::size_t _num_owned;
  std::vector<int> _counts, _offsets;   ///< rank 0: values per rank
  std::vector<std::int64_t> _all_slots; ///< rank 0: every rank's owned slots
};
} // namespace piezocontact
