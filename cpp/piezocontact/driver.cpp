#include "driver.h"
#include "diagnostics.h"
#include "mesh.h"
#include "output.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>

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

/// The summary.json of an interrupted or failed run in DIR, to continue it,
/// with its config. `--set time.T=... --set time.steps=...` extend a run
/// (completed or not) at the same step size.
std::pair<json, json> resumable_summary(const std::filesystem::path& dir,
                                        const std::vector<std::string>& overrides,
                                        const std::string& solver)
{
  const auto path = dir / "summary.json";
  const std::string where = path.string() + ": cannot resume: ";
  std::ifstream in(path);
  if (!in)
    throw ConfigError(where + "no such file");
  json summary;
  try
  {
    summary = json::parse(in);
  }
  catch (const json::exception& e)
  {
    throw ConfigError(where + "not valid JSON");
  }
  if (!summary.is_object() or summary.value("solver", "") != solver)
  {
    const auto theirs = summary.is_object() ? summary.value("solver", json(nullptr))
                                            : json(nullptr);
    throw ConfigError(where + "solver = " + theirs.dump() + ", this is the \"" + solver
                      + "\" solver");
  }
  if (!summary.contains("checkpoint") or !summary.contains("config"))
    throw ConfigError(where + "no checkpoint (an older version wrote it)");
  for (const auto& o : overrides)
  {
    const std::string key = o.substr(0, o.find('='));
    if (key != "time.T" and key != "time.steps")
      throw ConfigError(path.string() + ": --set " + key
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
void prepare_output(const std::filesystem::path& dir, const std::string& source,
                    MPI_Comm comm)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0)
  {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    const auto probe = dir / ".write-test";
    if (!ec)
    {
      std::ofstream out(probe);
      if (!out)
        ec = std::make_error_code(std::errc::permission_denied);
    }
    std::filesystem::remove(probe, ec);
    if (!std::filesystem::is_directory(dir) or !std::ofstream(probe))
      error = source + ": --output " + dir.string()
              + ": cannot write there: " + std::strerror(errno);
    std::filesystem::remove(probe, ec);
  }
  bcast_error(error, comm);
}
json run_config(const RunRequest& request, MPI_Comm comm, const ModelFactory& make_model,
                const Engine& engine, const StepObserver& observer)
{
  const json& cfg = request.cfg;
  std::optional<std::filesystem::path> mesh_file;
  if (!request.resume)
    mesh_file = prepare_mesh(cfg, request.source, request.output, comm);
  else if (!(*request.resume)["mesh_file"].is_null())
    mesh_file = (*request.resume)["mesh_file"].get<std::string>();
  if (mesh_file)
    mesh_file = std::filesystem::absolute(*mesh_file);
  const NamedMesh mesh = build_mesh(cfg, comm, mesh_file, request.source);
  Model model = make_model(mesh, cfg);
  set_constants(cfg, mesh.tag_of, model.constants, request.source);
  const RunSettings settings = run_settings(cfg);
  Problem problem(std::move(model), settings.dirichlet, request.source);

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
               {"config_file", std::filesystem::absolute(request.source).string()},
               {"mesh_file", mesh_file ? json(mesh_file->string()) : json(nullptr)},
               {"boundary_lengths", boundary_measures(problem)}};
  }
  if (engine)
    return engine(problem, settings, request.output, summary, request.resume != nullptr,
                  request.progress);
  return run(problem, settings, request.output, summary, request.resume != nullptr,
             request.progress, observer);
}

int command_line(const std::string& program, const std::vector<std::string>& args,
                 MPI_Comm comm, const std::vector<EngineChoice>& engines)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string config_path, output_dir;
  std::vector<std::string> overrides;
  bool quiet = false, resume = false;
  std::string engine_name = engines.at(0).name;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& a = args[i];
    const bool has_value = i + 1 < args.size();
    if (a == "--config" and has_value)
      config_path = args[++i];
    else if (a == "--output" and has_value)
      output_dir = args[++i];
    else if (a == "--set" and has_value)
      overrides.push_back(args[++i]);
    else if (a == "--quiet")
      quiet = true;
    else if (a == "--resume")
      resume = true;
    else if (a == "--engine" and has_value and engines.size() > 1)
      engine_name = args[++i];
    else if (a == "-h" or a == "--help")
    {
      if (rank == 0)
        std::cout << usage_of(program, engines);
      return 0;
    }
  }
  const auto chosen = std::find_if(engines.begin(), engines.end(),
                                   [&](const auto& e) { return e.name == engine_name; });
  std::string bad_args;
  if (chosen == engines.end())
    bad_args = "--engine " + engine_name + ": not one of the engines above";
  else if (output_dir.empty())
    bad_args = "--output is required";
  else if (resume and !config_path.empty())
    bad_args = "--resume takes the config from DIR/summary.json: no --config";
  else if (!resume and config_path.empty())
    bad_args = "--config is required";
  if (!bad_args.empty())
  {
    if (rank == 0)
      std::cerr << usage_of(program, engines) << "error: " << bad_args << "\n";
    return exit_config_error;
  }

  const InterruptScope interrupts;
  int code = 0;
  const auto& [name, solver, make_model, engine] = *chosen;
  try
  {
    RunRequest request{json(), output_dir, config_path, solver, !quiet};
    if (resume)
    {
      const auto [summary, cfg] = resumable_summary(output_dir, overrides, solver);
      request.cfg = cfg;
      request.source = summary["config_file"].get<std::string>();
      request.resume = &summary;
      run_config(request, comm, make_model, engine);
    }
    else
    {
      request.cfg = load_config(config_path, overrides);
      prepare_output(output_dir, config_path, comm);
      run_config(request, comm, make_model, engine);
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
