// From a config to a finished run, and the command line around it: the one
// orchestration behind `piezo-contact` (ahead-of-time kernels) and
// `python3 -m piezocontact` / piezocontact.solve (JIT kernels). The callers
// differ only in the model factory, and the Python reference engine in the
// time loop it plugs in.
#pragma once

#include "config.h"
#include "dynamics.h"
#include "mesh.h"
#include "model.h"
#include "problem.h"
#include "settings.h"
#include "time_loop.h"

#include <filesystem>
#include <functional>
#include <mpi.h>
#include <string>
#include <vector>

namespace piezocontact
{
/// Builds the forms on a mesh, their pieces as the spec says; the Constants
/// may be left at zero (the driver fills them from the config)
using ModelFactory = std::function<Model(const NamedMesh& mesh, const ModelSpec& spec)>;

/// A time loop: the library's `run` (time_loop.h) unless another is given
using Engine = std::function<json(Problem& problem, const RunSettings& settings,
                                  const std::filesystem::path& out_dir, json summary,
                                  bool resume, bool progress)>;

/// A dynamic analysis about the Problem's state: the library's `analyse`
/// (dynamics.h) unless another is given
using Analysis = std::function<json(Problem& problem, const RunSettings& settings,
                                    const std::filesystem::path& out_dir, json summary,
                                    const std::string& source)>;

struct RunRequest
{
  json cfg;                         ///< validated (configure / load_config)
  std::filesystem::path output;     ///< the output directory; empty: in memory, no file
                                    ///< written (no checkpoint, so no resume)
  std::string source = "config";    ///< names the config in messages
  std::string solver = "cpp";       ///< recorded in the summary as "solver"
  bool progress = true;             ///< one line per step on rank 0
  const json* resume = nullptr;     ///< the summary to continue (resumable_summary)
  MeshConverter convert_mesh;       ///< makes "gmsh" and "msh" meshes (mesh.h)
  const NamedMesh* mesh = nullptr;  ///< a mesh given (name_mesh), instead of the config's
};

/// The config checked against its mesh (a process without cells, the
/// dimension, the names of boundaries and regions, the axisymmetric
/// half-plane) with every material resolved to its tensors in the mesh
/// frame: what the model is built from. Throws ConfigError. Collective.
json checked_config(const json& cfg, const NamedMesh& mesh, MPI_Comm comm,
                    const std::string& source);

/// Mesh, model, Problem, time loop; the run's summary. Throws ConfigError,
/// NewtonFailure, OutputError, Interrupted.
json run_config(const RunRequest& request, MPI_Comm comm, const ModelFactory& make_model,
                const Engine& engine = nullptr, const StepObserver& observer = nullptr,
                const Analysis& analysis = nullptr);

/// The summary.json of DIR, to continue it, and the config to continue with
/// (`--set time.T=... --set time.steps=...` extend a run at the same step).
/// Only a run of the same `solver` can be resumed. Throws ConfigError.
std::pair<json, json> resumable_summary(const std::filesystem::path& dir,
                                        const std::vector<std::string>& overrides,
                                        const std::string& solver);

/// Create DIR and check that it can be written (rank 0; every rank throws
/// the same ConfigError)
void prepare_output(const std::filesystem::path& dir, const std::string& source, MPI_Comm comm);

/// A way of running that a command line offers: `--engine NAME` picks it
/// when there are several (the first is the default); `solver` is recorded
/// in the summary
struct EngineChoice
{
  std::string name;
  std::string solver;
  ModelFactory make_model;
  Engine engine = nullptr;     ///< the library's time loop if empty
  Analysis analysis = nullptr; ///< the library's dynamic analyses if empty
};

/// The command line, arguments without the program name:
///   --config FILE --output DIR [--set KEY=VALUE ...] [--quiet]
///   --output DIR --resume [--set time.T=.. --set time.steps=..] [--quiet]
///   [--engine NAME] when several engines are given
/// Prints one line per error; returns the exit code (0, 2 bad input,
/// 3 Newton failure, 4 output error, 128 + signal).
/// `convert_mesh` makes the "gmsh" and "msh" meshes (mesh.h).
int command_line(const std::string& program, const std::vector<std::string>& args,
                 MPI_Comm comm, const std::vector<EngineChoice>& engines,
                 const MeshConverter& convert_mesh);
} // namespace piezocontact
