// One run at a time in an output folder: two runs writing the same
// summary, checkpoint and XDMF index leave them unreadable. Rank 0 holds an
// advisory lock (flock) on DIR/.lock for the run; the kernel releases it
// however the process ends (return, exception, signal, kill -9), so a
// stopped run can always be resumed, and a second run is refused at once.
#pragma once

#include <filesystem>
#include <mpi.h>
#include <string>

namespace piezocontact
{
class OutputLock
{
public:
  /// Take the lock (rank 0; the directory must exist); ConfigError naming
  /// `source` and the folder on every rank if another process holds it
  OutputLock(const std::filesystem::path& dir, const std::string& source, MPI_Comm comm);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

private:
  int _fd = -1;
};
} // namespace piezocontact
