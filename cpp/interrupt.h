// SIGINT and SIGTERM end a run cleanly instead of killing it mid-write: the
// handler only records the signal; the time loop asks, at every Newton
// iteration and between steps, whether any rank was signalled (a collective
// call, so that all ranks stop at the same point), abandons the step under
// way and writes the summary with status "interrupted".
#pragma once

#include <mpi.h>
#include <string>

namespace piezo
{
/// Exit code of a run ended by signal `signum`: 128 + signum (130, 143)
inline int exit_code_of_signal(int signum) { return 128 + signum; }

/// Install the handlers (after PetscInitialize, which installs its own).
void install_interrupt_handlers();

/// The signal received on this rank, 0 if none
int local_interrupt();

/// The signal received on any rank, 0 if none. Collective.
int agreed_interrupt(MPI_Comm comm);

/// "SIGINT", "SIGTERM"
std::string signal_name(int signum);
} // namespace piezo
