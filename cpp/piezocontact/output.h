// Run outputs, one layout for every engine (written through Record). Every
// file is complete whenever a step has been reported, whatever instant a
// kill lands:
//   DIR/summary.json             the run's record (write-then-rename each step)
//   DIR/solution.xdmf            index for ParaView (write-then-rename each step)
//   DIR/solution.h5              the mesh, written once
//   DIR/solution/step_NNNNNN.h5  u, phi (vertex), D, stress (cell) of one step:
//                                a new file per step, never reopened, so a
//                                write cut short cannot damage earlier steps
//   DIR/nodal/{u,phi}_NNNN.npy   nodal values [x, y, value...] on rank 0
//   DIR/checkpoint/state_NNNNNN.npy  what --resume needs (checkpoint.h)
// Files of steps after the last one in summary.json (a kill came before the
// summary) are dropped by --resume, which writes them again.
#pragma once

#include "output_mesh.h"

#include "config.h"
#include "problem.h"

#include <dolfinx/io/XDMFFile.h>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>

namespace pugi
{
class xml_document;
}

namespace piezocontact
{
/// An output file could not be written (disk full, permissions); the message
/// names the file and the system's reason
struct OutputError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

constexpr int exit_output_error = 4;

/// Write-then-rename: an interrupted run never leaves a half-written file.
/// Throws OutputError naming `path`.
void write_file_atomic(const std::filesystem::path& path,
                       const std::function<void(std::ostream&)>& write);

void write_json_atomic(const std::filesystem::path& path, const json& value);

/// A 2D float64 array (row-major) in NumPy's .npy format, written atomically
void write_npy(const std::filesystem::path& path, const std::vector<double>& data,
               std::size_t rows, std::size_t cols);

/// Read what write_npy wrote: (data, rows, cols). Throws std::runtime_error.
std::tuple<std::vector<double>, std::size_t, std::size_t>
read_npy(const std::filesystem::path& path);

/// Run `action` on the ranks given; if it failed on any rank, throw the same
/// OutputError everywhere (the lowest failing rank's message). Collective.
void collectively(MPI_Comm comm, bool on_this_rank, const std::function<void()>& action);

/// Turn HDF5's error-stack printing off: write failures become one line
void silence_hdf5_errors();

class Writer
{
public:
  /// A fresh run (no resumed step) clears earlier outputs of DIR; a run
  /// resumed at step n (0 too: killed before its first step) keeps steps
  /// 1..n and the checkpoint of step n, and drops anything written after.
  Writer(const Problem& problem, const OutputSettings& settings,
         const std::filesystem::path& dir, std::optional<int> resumed_step);
  ~Writer();

  /// Write the state of problem.u, problem.phi (updated by the caller)
  void write_step(int step, double t, bool final);

private:
  /// Write one HDF5 file through dolfinx (XML beside it); on failure on any
  /// rank, remove it and throw OutputError everywhere
  void write_hdf5(const std::filesystem::path& xdmf,
                  const std::function<void(dolfinx::io::XDMFFile&)>& write) const;
  void load_index(int last_step);
  void write_xdmf_step(int step, double t);
  void publish_index() const;
  const Problem& _problem;
  std::filesystem::path _dir;
  std::string _nodal;
  bool _xdmf;
  std::unique_ptr<pugi::xml_document> _index; ///< rank 0: solution.xdmf
  std::shared_ptr<dolfinx::fem::Function<double>> _D, _stress;
  /// The stress by Voigt component (scalar, cell-centred in XDMF), and
  /// where each takes its values in _stress
  std::vector<std::shared_ptr<dolfinx::fem::Function<double>>> _stress_components;
  std::vector<std::vector<std::int32_t>> _stress_maps;
  /// The mesh of the files (refined at a degree above 1)
  std::unique_ptr<OutputMesh> _out;
};
} // namespace piezocontact
