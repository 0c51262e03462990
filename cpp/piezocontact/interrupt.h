// SIGINT and SIGTERM end a run cleanly instead of killing it mid-write: the
// handler only records the signal; the time loop asks, at every Newton
// iteration and between steps, whether any rank was signalled (a collective
// call, so that all ranks stop at the same point), abandons the step under
// way and writes the summary with status "interrupted".
#pragma once

#include <csignal>
#include <mpi.h>
#include <string>

namespace piezocontact
{
/// Exit code of a run ended by signal `signum`: 128 + signum (130, 143)
inline int exit_code_of_signal(int signum) { return 128 + signum; }

/// Install the handlers (after PetscInitialize, which installs its own).
void install_interrupt_handlers();

/// While alive: SIGINT and SIGTERM are recorded (not acted on) and none is
/// pending; then the handlers before it come back (a Python interpreter's)
class InterruptScope
{
public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

private:
  struct sigaction* _previous;
};

/// The signal received on this rank, 0 if none
int local_interrupt();

/// The signal received on any rank, 0 if none. Collective.
int agreed_interrupt(MPI_Comm comm);

/// "SIGINT", "SIGTERM"
std::string signal_name(int signum);
} // namespace piezocontact
