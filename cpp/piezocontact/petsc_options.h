// solver.petsc_options: checked before a run, so that a value PETSc refuses
// is bad input naming its key (not a PETSc error dump and MPI_Abort), and
// PETSc's errors during a run made exceptions without the dump.
#pragma once

#include "settings.h"

#include <mpi.h>
#include <string>
#include <utility>
#include <vector>

namespace piezocontact
{
/// The options prefix of the C++ loop's linear solver
inline const std::string petsc_prefix = "piezocontact_";

using PetscOptionList = std::vector<std::pair<std::string, std::string>>;

/// The C++ loop's linear solver unless the config's options say otherwise:
/// LU by MUMPS, or GMRES with a u/phi block preconditioner
PetscOptionList loop_defaults(LinearSolver linear);

/// Set up and solve a small two-field system with the loop's defaults and
/// these options (keys without prefix or dash), on each process alone: an
/// unknown type, a malformed number or a solver that cannot be set up is a
/// ConfigError naming `source`, the first such key and its value. Options
/// the toy system does not reach are checked when the run's solver is set up.
void check_petsc_options(const PetscOptionList& options, LinearSolver linear,
                         const std::string& source);

/// Options set under `prefix` while alive: the options database is global,
/// and a later run in the same process must not inherit them
class ScopedPetscOptions
{
public:
  ScopedPetscOptions(const std::string& prefix, const PetscOptionList& options);
  ~ScopedPetscOptions();
  ScopedPetscOptions(const ScopedPetscOptions&) = delete;
  ScopedPetscOptions& operator=(const ScopedPetscOptions&) = delete;

private:
  std::vector<std::string> _names;
};

/// While alive, a failing PETSc call returns its error code (which dolfinx
/// and the library turn into exceptions) instead of printing PETSc's
/// traceback on every rank
class QuietPetscErrors
{
public:
  QuietPetscErrors();
  ~QuietPetscErrors();
  QuietPetscErrors(const QuietPetscErrors&) = delete;
  QuietPetscErrors& operator=(const QuietPetscErrors&) = delete;
};

/// PETSc's description of the last error (one line)
std::string last_petsc_error(int code);
} // namespace piezocontact
