// Run outputs, the layout of demos/piezocontact/output.py:
//   DIR/summary.json           the run's record, rewritten atomically each step
//   DIR/solution.xdmf (+.h5)   u, phi (vertex) and D, stress (cell) for ParaView
//   DIR/nodal/{u,phi}_NNNN.npy nodal values [x, y, value...] gathered on rank 0
#pragma once

#include "problem.h"

#include <dolfinx/io/XDMFFile.h>
#include <filesystem>

namespace piezo
{
/// Write-then-rename: an interrupted run never leaves a half-written file
void write_json_atomic(const std::filesystem::path& path, const json& value);

/// Write a 2D float64 array (row-major) in NumPy's .npy format
void write_npy(const std::filesystem::path& path, const std::vector<double>& data,
               std::size_t rows, std::size_t cols);

class Writer
{
public:
  Writer(const Problem& problem, const std::filesystem::path& dir);
  /// Write the state of problem.u, problem.phi (updated by the caller)
  void write_step(int step, double t, bool final);

private:
  const Problem& _problem;
  std::filesystem::path _dir;
  std::string _nodal;
  std::filesystem::path _xdmf; ///< empty: no XDMF output
  std::shared_ptr<fem::Function<double>> _D, _stress;
};
} // namespace piezo
