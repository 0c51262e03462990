// piezo-contact: quasistatic frictionless contact of a viscoelastic
// piezoelectric body with a normal-compliance foundation (Barboteu,
// Fernandez & Ouafik 2008), on the kernels ffcx compiled from forms/.
//
//   piezo-contact --config FILE --output DIR [--set key.path=value ...] [--quiet]
//   piezo-contact --output DIR --resume [--set time.T=X --set time.steps=N] [--quiet]
//
// Exit codes: 0 success, 2 bad input (config, output directory, nothing to
// resume), 3 the solver failed (Newton did not converge), 4 an output file
// could not be written (disk full), 128 + signal number when stopped by
// SIGINT (130) or SIGTERM (143).
#include "compiled_model.h"
#include "mesh_tools.h"

#include <dolfinx/common/log.h>
#include <petscsys.h>
#include <piezocontact/driver.h>
#include <piezocontact/output.h>

int main(int argc, char* argv[])
{
  // The arguments are ours alone (PETSc options belong in the config's
  // solver.petsc_options): neither PETSc nor the logger sees them
  int argc0 = 1;
  dolfinx::init_logging(argc0, argv);
  PetscInitialize(&argc0, &argv, nullptr, nullptr);
  piezocontact::silence_hdf5_errors(); // failures are reported in one line
  const std::vector<std::string> args(argv + 1, argv + argc);
  const int code = piezocontact::command_line(
      "piezo-contact", args, MPI_COMM_WORLD, {{"cpp", "cpp", piezocontact::app::compiled_model}},
      piezocontact::app::convert_mesh);
  PetscFinalize();
  return code;
}
