#include "driver.h"
#include "output_lock.h"
#include "diagnostics.h"
#include "json_input.h"
#include "materials.h"
#include "petsc_options.h"
#include "mesh.h"
#include "output.h"

#include <algorithm>
#include <cerrno>
#include <fcntl.h>
#include <cstring>
#include <fstream>
#include <iostream>
#include <set>
#include <unistd.h>

namespace piezocontact
{
namespace
{
const char* usage
    = "usage: %1$s --config FILE --output DIR [--set KEY.PATH=VALUE ...] [--quiet]\n"
      "       %1$s --output DIR --resume [--set time.T=... --set time.steps=...] [--quiet]\n";

std::string usage_of(const std::string& program, const std::vector<EngineChoice>& engines)
{
  char buf[512];
  std::snprintf(buf, sizeof(buf), usage, program.c_str());
  std::string out = buf;
  if (engines.size() > 1)
  {
    out += "       --engine " + engines[0].name;
    for (std::size_t i = 1; i < engines.size(); ++i)
      out += "|" + engines[i].name;
    out += " (default " + engines[0].name + ")\n";
  }
  return out;
}
} // namespace

namespace
{
/// dolfinx 0.5 cannot collapse a sub-space on a process that owns no cell
/// (a segmentation fault): refuse such a distribution. Collective.
void check_every_rank_has_cells(const NamedMesh& mesh, MPI_Comm comm, const std::string& source)
{
  const auto& topology = compat::topology(*mesh.mesh);
  const auto cells = topology.index_map(topology.dim());
  const int mine = cells->size_local();
  int fewest = 0, size = 0;
  MPI_Allreduce(&mine, &fewest, 1, MPI_INT, MPI_MIN, comm);
  MPI_Comm_size(comm, &size);
  if (fewest == 0)
    throw ConfigError(printable(source, 200) + ": mesh: " + std::to_string(cells->size_global())
                      + " cells for " + std::to_string(size)
                      + " processes leave a process without a cell, which is not supported "
                        "(dolfinx 0.5 cannot collapse a space there): use a finer mesh or "
                        "fewer processes");
}

/// What the summary's integrated quantities are: per unit thickness in
/// the plane formulations, per full revolution in axisymmetry
json units_of(const json& cfg, int d)
{
  if (d == 3)
    return {{"forces", "N"}, {"charges", "C"}, {"currents", "A"}, {"measures", "m^2"}};
  if (cfg.value("formulation", "") == "axisymmetric")
    return {{"forces", "N, per full revolution (x: the radial traction integrated over the "
                       "surface of revolution)"},
            {"charges", "C, per full revolution"},
            {"currents", "A, per full revolution"},
            {"measures", "m^2, the areas of the surfaces of revolution"}};
  return {{"forces", "N/m, per unit thickness"},
          {"charges", "C/m, per unit thickness"},
          {"currents", "A/m, per unit thickness"},
          {"measures", "m"}};
}

/// An axisymmetric mesh lies in the half-plane x = r >= 0 (its points on
/// the axis may be off by round-off)
void check_half_plane(const json& cfg, const NamedMesh& mesh, MPI_Comm comm,
                      const std::string& source)
{
  if (cfg.value("formulation", "") != "axisymmetric")
    return;
  const auto& geometry = mesh.mesh->geometry();
  const double* x = geometry.x().data(); // (num_nodes, 3), row-major
  const std::size_t n = geometry.x().size();
  double range[2] = {0.0, 0.0}; // -min x, max |coordinate|
  for (std::size_t i = 0; i < n; ++i)
  {
    range[1] = std::max(range[1], std::abs(x[i]));
    if (i % 3 == 0)
      range[0] = std::max(range[0], -x[i]);
  }
  MPI_Allreduce(MPI_IN_PLACE, range, 2, MPI_DOUBLE, MPI_MAX, comm);
  if (range[0] > 1e-12 * range[1])
    throw ConfigError(printable(source, 200) + ": formulation: axisymmetric: the mesh has "
                      + "points at x = r < 0 (down to " + printable(json(-range[0]))
                      + " m): an axisymmetric mesh lies in the half-plane x >= 0, y the axis");
}
} // namespace

/// The summary.json of an interrupted or failed run in DIR, to continue it,
/// with its config. `--set time.T=... --set time.steps=...` extend a run
/// (completed or not) at the same step size.
std::pair<json, json> resumable_summary(const std::filesystem::path& dir,
                                        const std::vector<std::string>& overrides,
                                        const std::string& solver)
{
  const auto path = dir / "summary.json";
  const std::string where = printable(path.string(), 200) + ": cannot resume: ";
  if (!std::filesystem::exists(path))
    throw ConfigError(where + "no such file");
  json summary;
  try
  {
    summary = read_json_file(path, max_summary_bytes);
  }
  catch (const ConfigError& e)
  {
    throw ConfigError(where + std::string(e.what()).substr(printable(path.string(), 200).size() + 2));
  }
  const json theirs = summary.is_object() ? summary.value("solver", json(nullptr)) : json();
  if (theirs != solver)
    throw ConfigError(where + "solver = " + printable(theirs) + ", this is the \"" + solver
                      + "\" solver");
  if (!summary.contains("checkpoint") or !summary.contains("config"))
    throw ConfigError(where + "no checkpoint (an older version wrote it)");
  for (const auto& o : overrides)
  {
    const std::string key = o.substr(0, o.find('='));
    if (key != "time.T" and key != "time.steps")
      throw ConfigError(printable(path.string(), 200) + ": --set " + printable(key)
                               + ": only time.T and time.steps can change on --resume "
                                 "(to extend the run)");
  }
  const json& old = summary["config"];
  const json cfg = configure(old, overrides, path.string());
  const double k_old = old["time"]["T"].get<double>() / old["time"]["steps"].get<double>();
  const double k_new = cfg["time"]["T"].get<double>() / cfg["time"]["steps"].get<double>();
  if (k_new != k_old)
    throw ConfigError(path.string() + ": time.T / time.steps = " + json(k_new).dump()
                             + ": an extended run keeps its step T/steps = "
                             + json(k_old).dump());
  const int done = summary["checkpoint"].value("nominal_steps", 0);
  if (cfg["time"]["steps"].get<int>() < done)
    throw ConfigError(path.string() + ": time.steps = " + cfg["time"]["steps"].dump()
                             + ": the run has done " + std::to_string(done) + " steps already");
  if (summary.value("status", "") == "completed"
      and cfg["time"]["steps"] == old["time"]["steps"])
    throw ConfigError(where + "status = \"completed\" (to extend it, --set time.T "
                                     "and time.steps)");
  return {summary, cfg};
}

/// Create DIR and check that it can be written, on rank 0; every rank then
/// gets the same error, so that none waits for the others forever.
namespace
{
/// Why files cannot be created in `dir` (made if missing), in the OS's
/// words; empty if they can
std::string unwritable(const std::filesystem::path& dir)
{
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) and !std::filesystem::is_directory(dir, ec))
    return "it exists and is not a directory";
  std::filesystem::create_directories(dir, ec);
  if (ec)
    return ec.message();
  const auto probe = dir / ".write-test";
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0)
    return std::strerror(errno);
  ::close(fd);
  ::unlink(probe.c_str());
  return "";
}
} // namespace

void prepare_output(const std::filesystem::path& dir, const std::string& source,
                    MPI_Comm comm)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0)
  {
    if (const std::string why = unwritable(dir); !why.empty())
      error = printable(source, 200) + ": --output " + printable(dir.string(), 200)
              + ": cannot write there: " + why;
  }
  bcast_error(error, comm);
}
namespace
{
/// The factory's model; degrees it has no kernels for are the config's error
Model model_of(const ModelFactory& make_model, const NamedMesh& mesh, const ModelSpec& spec,
               const std::string& source)
{
  try
  {
    return make_model(mesh, spec);
  }
  catch (const DegreesNotCarried& e)
  {
    throw ConfigError(printable(source, 200) + ": elements: u " + std::to_string(spec.degrees[0])
                      + ", phi " + std::to_string(spec.degrees[1]) + ": " + e.what());
  }
}
} // namespace

json checked_config(const json& cfg, const NamedMesh& mesh, MPI_Comm comm,
                    const std::string& source)
{
  check_every_rank_has_cells(mesh, comm, source);
  const int d = mesh.mesh->geometry().dim();
  const json checked = check_dimension(cfg, d, source);
  check_names(checked, mesh, source);
  check_half_plane(checked, mesh, comm, source);
  return resolve_materials(checked, d, source);
}

namespace
{
/// The mesh of a run: the one given, or the config's (made by its tool
/// into the output folder, or named by the summary resumed)
std::pair<NamedMesh, std::optional<std::filesystem::path>> mesh_of(const RunRequest& request,
                                                                   MPI_Comm comm)
{
  if (request.mesh)
    return {*request.mesh, std::nullopt};
  std::optional<std::filesystem::path> mesh_file;
  if (!request.resume)
    mesh_file = prepare_mesh(request.cfg, request.source, request.output, comm,
                             request.convert_mesh);
  else if (!(*request.resume)["mesh_file"].is_null())
    mesh_file = (*request.resume)["mesh_file"].get<std::string>();
  if (mesh_file)
    mesh_file = std::filesystem::absolute(*mesh_file);
  return {build_mesh(request.cfg, comm, mesh_file, request.source), mesh_file};
}
} // namespace

json run_config(const RunRequest& request, MPI_Comm comm, const ModelFactory& make_model,
                const Engine& engine, const StepObserver& observer, const Analysis& analysis)
{
  const bool in_memory = request.output.empty();
  if (in_memory and request.resume)
    throw ConfigError(printable(request.source, 200) + ": cannot resume a run kept in memory");
  const json& type = request.cfg["mesh"]["type"];
  if (in_memory and !request.mesh and (type == "gmsh" or type == "msh"))
    throw ConfigError(printable(request.source, 200) + ": mesh.type = " + type.dump()
                      + ": a run kept in memory is given its mesh (the mesh tool writes into "
                        "the output folder; piezocontact.Problem.from_config makes it in a "
                        "temporary one)");
  std::optional<OutputLock> lock;
  if (!in_memory)
    lock.emplace(request.output, request.source, comm);
  const RunSettings settings = run_settings(request.cfg);
  check_petsc_options(settings.petsc_options, settings.linear, request.source);
  const QuietPetscErrors quiet; // PETSc failures become exceptions, not dumps
  const auto [mesh, mesh_file] = mesh_of(request, comm);
  const int d = mesh.mesh->geometry().dim();
  // from here on, every material is its tensors in the mesh frame
  const json cfg = checked_config(request.cfg, mesh, comm, request.source);
  const ModelSpec spec = model_spec(cfg);
  Model model = model_of(make_model, mesh, spec, request.source);
  set_constants(cfg, model);
  const auto timed = timed_constants(cfg, model);
  const auto spatial = spatial_loads(cfg, model);
  Problem problem(std::move(model), settings.dirichlet, request.source, timed, spatial);

  json summary;
  if (request.resume)
  {
    summary = *request.resume;
    summary["config"] = cfg; // a later T, when extended
  }
  else
  {
    summary = {{"solver", request.solver},
               {"config", cfg},
               {"config_file", request.mesh ? request.source
                                            : std::filesystem::absolute(request.source).string()},
               {"mesh_file", mesh_file ? json(mesh_file->string()) : json(nullptr)},
               {"boundary_lengths", boundary_measures(problem)},
               {"units", units_of(cfg, d)}};
  }
  const auto& a = settings.analysis;
  if (a.kind == AnalysisSettings::Kind::none or a.at_end)
    summary = engine ? engine(problem, settings, request.output, summary,
                              request.resume != nullptr, request.progress)
                     : run(problem, settings, request.output, summary, request.resume != nullptr,
                           request.progress, observer);
  if (a.kind == AnalysisSettings::Kind::none)
    return summary;
  if (!a.at_end) // about the initial state: x = 0, the Constants at t = 0
    problem.set_time(0.0, settings.T / settings.steps);
  return analysis ? analysis(problem, settings, request.output, summary, request.source)
                  : analyse(problem, settings, request.output, summary, request.source);
}

namespace
{
struct Arguments
{
  std::string config, output, engine;
  std::vector<std::string> overrides;
  bool quiet = false, resume = false, help = false;
};

/// Strict: every argument is one of ours (PETSc options go in the config's
/// solver.petsc_options). Throws std::invalid_argument naming the argument.
Arguments parse_arguments(const std::vector<std::string>& args,
                          const std::vector<EngineChoice>& engines)
{
  Arguments out;
  std::vector<std::string> flags = {"--config", "--output", "--set", "--quiet", "--resume",
                                    "--help"};
  if (engines.size() > 1)
    flags.push_back("--engine");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& a = args[i];
    const auto value = [&]
    {
      if (i + 1 == args.size() or args[i + 1].empty() or args[i + 1].rfind("--", 0) == 0)
        throw std::invalid_argument(a + " needs a value");
      return args[++i];
    };
    if (a != "--set" and std::find(flags.begin(), flags.end(), a) != flags.end()
        and !seen.insert(a).second)
      throw std::invalid_argument(a + " given twice");
    if (a == "--config")
      out.config = value();
    else if (a == "--output")
      out.output = value();
    else if (a == "--set")
      out.overrides.push_back(value());
    else if (a == "--engine" and engines.size() > 1)
      out.engine = value();
    else if (a == "--quiet")
      out.quiet = true;
    else if (a == "--resume")
      out.resume = true;
    else if (a == "-h" or a == "--help")
      out.help = true;
    else
    {
      const std::string near = a.rfind("-", 0) == 0 ? closest_key(a, flags) : "";
      throw std::invalid_argument("unknown argument '" + printable(a) + "'"
                                  + (near.empty() ? "" : " (did you mean " + near + "?)"));
    }
  }
  if (out.engine.empty())
    out.engine = engines.at(0).name;
  if (std::none_of(engines.begin(), engines.end(),
                   [&](const auto& e) { return e.name == out.engine; }))
    throw std::invalid_argument("--engine " + printable(out.engine) + ": not one of the engines above");
  if (out.help)
    return out;
  if (out.output.empty())
    throw std::invalid_argument("--output is required");
  if (out.resume and !out.config.empty())
    throw std::invalid_argument("--resume takes the config from DIR/summary.json: no --config");
  if (!out.resume and out.config.empty())
    throw std::invalid_argument("--config is required");
  return out;
}
} // namespace

int command_line(const std::string& program, const std::vector<std::string>& args,
                 MPI_Comm comm, const std::vector<EngineChoice>& engines,
                 const MeshConverter& convert_mesh)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  // Our messages say what went wrong; dolfinx's warnings (e.g. Newton's, at
  // each step that is then halved) would only repeat it
  compat::log_errors_only();
  Arguments arguments;
  try
  {
    arguments = parse_arguments(args, engines);
  }
  catch (const std::invalid_argument& e)
  {
    if (rank == 0)
      std::cerr << usage_of(program, engines) << "error: " << e.what() << "\n";
    return exit_config_error;
  }
  if (arguments.help)
  {
    if (rank == 0)
      std::cout << usage_of(program, engines);
    return 0;
  }
  const auto& [config_path, output_dir, engine_name, overrides, quiet, resume, help]
      = arguments;
  const auto chosen = std::find_if(engines.begin(), engines.end(),
                                   [&](const auto& e) { return e.name == engine_name; });

  const InterruptScope interrupts;
  int code = 0;
  const auto& [name, solver, make_model, engine, analysis] = *chosen;
  try
  {
    RunRequest request{json(), output_dir, config_path, solver, !quiet, nullptr, convert_mesh};
    if (resume)
    {
      const auto [summary, cfg] = resumable_summary(output_dir, overrides, solver);
      request.cfg = cfg;
      request.source = summary["config_file"].get<std::string>();
      request.resume = &summary;
      run_config(request, comm, make_model, engine, nullptr, analysis);
    }
    else
    {
      request.cfg = load_config(config_path, overrides);
      prepare_output(output_dir, config_path, comm);
      run_config(request, comm, make_model, engine, nullptr, analysis);
    }
  }
  catch (const ConfigError& e)
  {
    if (rank == 0)
      std::cerr << "error: " << e.what() << std::endl;
    code = exit_config_error;
  }
  catch (const NewtonFailure& e)
  {
    if (rank == 0)
      std::cerr << "error: " << e.what() << std::endl;
    code = exit_run_error;
  }
  catch (const OutputError& e)
  {
    if (rank == 0)
      std::cerr << "error: " << e.what() << std::endl;
    code = exit_output_error;
  }
  catch (const Interrupted& e)
  {
    if (rank == 0)
      std::cerr << e.what() << std::endl;
    code = exit_code_of_signal(e.signum);
  }
  catch (const std::exception& e)
  {
    // Unexpected, perhaps on one rank only: the others may be waiting in a
    // collective call, so end the whole job rather than hang
    std::cerr << "error (rank " << rank << "): " << e.what() << std::endl;
    MPI_Abort(comm, 1);
  }
  return code;
}
} // namespace piezocontact
