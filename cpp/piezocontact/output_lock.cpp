#include "output_lock.h"

#include "config.h"
#include "json_input.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace piezocontact
{
OutputLock::OutputLock(const std::filesystem::path& dir, const std::string& source,
                       MPI_Comm comm)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0)
  {
    const auto path = dir / ".lock";
    std::error_code ec;
    std::filesystem::create_directories(dir, ec); // if that fails, open says why
    _fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (_fd < 0)
      error = std::strerror(errno);
    else if (::flock(_fd, LOCK_EX | LOCK_NB) != 0)
    {
      // a file system without locks (some network mounts) runs unguarded,
      // as before locks existed
      if (errno == EWOULDBLOCK)
        error = "another run is writing there (it holds " + path.string()
                + "); wait for it to end or choose another folder";
      else if (errno != ENOLCK and errno != EOPNOTSUPP and errno != ENOSYS)
        error = std::strerror(errno);
      ::close(_fd);
      _fd = -1;
    }
    if (!error.empty())
      error = printable(source, 200) + ": --output " + printable(dir.string(), 200) + ": "
              + error;
  }
  bcast_error(error, comm);
}

OutputLock::~OutputLock()
{
  if (_fd >= 0)
    ::close(_fd); // releases the lock
}
} // namespace piezocontact
