// piezo-contact: quasistatic frictionless contact of a viscoelastic
// piezoelectric body with a normal-compliance foundation (Barboteu,
// Fernandez & Ouafik 2008), on the ffcx-compiled forms of forms/.
//
//   piezo-contact --config FILE --output DIR [--set key.path=value ...] [--quiet]
//   piezo-contact --output DIR --resume [--set time.T=X --set time.steps=N] [--quiet]
//
// Exit codes: 0 success, 2 bad input (config, output directory, nothing to
// resume), 3 the solver failed (Newton did not converge), 4 an output file
// could not be written (disk full), 128 + signal number when stopped by
// SIGINT (130) or SIGTERM (143).
#include "config.h"
#include "interrupt.h"
#include "output.h"
#include "time_loop.h"

#include <dolfinx/common/log.h>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <petscsys.h>

namespace
{
const char* usage
    = "usage: piezo-contact --config FILE --output DIR [--set KEY.PATH=VALUE ...] "
      "[--quiet]\n"
      "       piezo-contact --output DIR --resume [--set time.T=... --set time.steps=...] "
      "[--quiet]\n";

/// The summary.json of an interrupted or failed run in DIR, to continue it,
/// with its config. `--set time.T=... --set time.steps=...` extend a run
/// (completed or not) at the same step size.
std::pair<piezo::json, piezo::json> resumable_summary(const std::filesystem::path& dir,
                                                      const std::vector<std::string>& overrides)
{
  const auto path = dir / "summary.json";
  const std::string where = path.string() + ": cannot resume: ";
  std::ifstream in(path);
  if (!in)
    throw piezo::ConfigError(where + "no such file");
  piezo::json summary;
  try
  {
    summary = piezo::json::parse(in);
  }
  catch (const piezo::json::exception& e)
  {
    throw piezo::ConfigError(where + "not valid JSON");
  }
  if (!summary.is_object() or summary.value("solver", "") != "cpp")
  {
    const auto solver = summary.is_object() ? summary.value("solver", piezo::json(nullptr))
                                            : piezo::json(nullptr);
    throw piezo::ConfigError(where + "solver = " + solver.dump()
                             + ", this is the \"cpp\" solver");
  }
  if (!summary.contains("checkpoint") or !summary.contains("config"))
    throw piezo::ConfigError(where + "no checkpoint (an older version wrote it)");
  for (const auto& o : overrides)
  {
    const std::string key = o.substr(0, o.find('='));
    if (key != "time.T" and key != "time.steps")
      throw piezo::ConfigError(path.string() + ": --set " + key
                               + ": only time.T and time.steps can change on --resume "
                                 "(to extend the run)");
  }
  const piezo::json& old = summary["config"];
  const piezo::json cfg = piezo::configure(old, overrides, path.string());
  const double k_old = old["time"]["T"].get<double>() / old["time"]["steps"].get<double>();
  const double k_new = cfg["time"]["T"].get<double>() / cfg["time"]["steps"].get<double>();
  if (k_new != k_old)
    throw piezo::ConfigError(path.string() + ": time.T / time.steps = " + piezo::json(k_new).dump()
                             + ": an extended run keeps its step T/steps = "
                             + piezo::json(k_old).dump());
  const int done = summary["checkpoint"].value("nominal_steps", 0);
  if (cfg["time"]["steps"].get<int>() < done)
    throw piezo::ConfigError(path.string() + ": time.steps = " + cfg["time"]["steps"].dump()
                             + ": the run has done " + std::to_string(done) + " steps already");
  if (summary.value("status", "") == "completed"
      and cfg["time"]["steps"] == old["time"]["steps"])
    throw piezo::ConfigError(where + "status = \"completed\" (to extend it, --set time.T "
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
  int len = error.size();
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  error.resize(len);
  MPI_Bcast(error.data(), len, MPI_CHAR, 0, comm);
  if (!error.empty())
    throw piezo::ConfigError(error);
}
} // namespace

int main(int argc, char* argv[])
{
  dolfinx::init_logging(argc, argv);
  PetscInitialize(&argc, &argv, nullptr, nullptr);
  piezo::install_interrupt_handlers(); // after PETSc's, which would abort
  piezo::silence_hdf5_errors();        // failures are reported in one line
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int code = 0;
  std::string config_path, output_dir;
  std::vector<std::string> overrides;
  bool quiet = false, resume = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--config" and i + 1 < argc)
      config_path = argv[++i];
    else if (a == "--output" and i + 1 < argc)
      output_dir = argv[++i];
    else if (a == "--set" and i + 1 < argc)
      overrides.push_back(argv[++i]);
    else if (a == "--quiet")
      quiet = true;
    else if (a == "--resume")
      resume = true;
    else if (a == "-h" or a == "--help")
    {
      if (rank == 0)
        std::cout << usage;
      PetscFinalize();
      return 0;
    }
    else if (a.rfind("-dolfinx_", 0) == 0 or a.rfind("-", 0) == 0)
      continue; // PETSc / dolfinx options are read from the database
  }
  const char* bad_args = nullptr;
  if (output_dir.empty())
    bad_args = "--output is required";
  else if (resume and !config_path.empty())
    bad_args = "--resume takes the config from DIR/summary.json: no --config";
  else if (!resume and config_path.empty())
    bad_args = "--config is required";
  if (bad_args)
  {
    if (rank == 0)
      std::cerr << usage << "error: " << bad_args << "\n";
    PetscFinalize();
    return piezo::exit_config_error;
  }

  try
  {
    if (resume)
    {
      const auto [summary, cfg] = resumable_summary(output_dir, overrides);
      piezo::run(cfg, output_dir, MPI_COMM_WORLD, !quiet,
                 summary["config_file"].get<std::string>(), &summary);
    }
    else
    {
      const piezo::json cfg = piezo::load_config(config_path, overrides);
      prepare_output(output_dir, config_path, MPI_COMM_WORLD);
      piezo::run(cfg, output_dir, MPI_COMM_WORLD, !quiet, config_path);
    }
  }
  catch (const piezo::ConfigError& e)
  {
    if (rank == 0)
      std::cerr << "error: " << e.what() << std::endl;
    code = piezo::exit_config_error;
  }
  catch (const piezo::NewtonFailure& e)
  {
    if (rank == 0)
      std::cerr << "error: " << e.what() << std::endl;
    code = piezo::exit_run_error;
  }
  catch (const piezo::OutputError& e)
  {
    if (rank == 0)
      std::cerr << "error: " << e.what() << std::endl;
    code = piezo::exit_output_error;
  }
  catch (const piezo::Interrupted& e)
  {
    if (rank == 0)
      std::cerr << e.what() << std::endl;
    code = piezo::exit_code_of_signal(e.signum);
  }
  catch (const std::exception& e)
  {
    // Unexpected, perhaps on one rank only: the others may be waiting in a
    // collective call, so end the whole job rather than hang
    std::cerr << "error (rank " << rank << "): " << e.what() << std::endl;
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  PetscFinalize();
  return code;
}
