#include "interrupt.h"

#include <csignal>

namespace piezocontact
{
namespace
{
volatile std::sig_atomic_t received = 0;

extern "C" void record_signal(int signum) { received = signum; }
} // namespace

void install_interrupt_handlers()
{
  struct sigaction action = {};
  action.sa_handler = record_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART; // blocking I/O resumes; we stop at our own checks
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

InterruptScope::InterruptScope() : _previous(new struct sigaction[2])
{
  sigaction(SIGINT, nullptr, &_previous[0]);
  sigaction(SIGTERM, nullptr, &_previous[1]);
  received = 0;
  install_interrupt_handlers();
}

InterruptScope::~InterruptScope()
{
  sigaction(SIGINT, &_previous[0], nullptr);
  sigaction(SIGTERM, &_previous[1], nullptr);
  delete[] _previous;
}

int local_interrupt() { return received; }

int agreed_interrupt(MPI_Comm comm)
{
  int signum = received;
  MPI_Allreduce(MPI_IN_PLACE, &signum, 1, MPI_INT, MPI_MAX, comm);
  return signum;
}

std::string signal_name(int signum)
{
  switch (signum)
  {
  case SIGINT:
    return "SIGINT";
  case SIGTERM:
    return "SIGTERM";
  default:
    return "signal " + std::to_string(signum);
  }
}
} // namespace piezocontact
