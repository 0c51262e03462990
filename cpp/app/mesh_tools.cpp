#include "mesh_tools.h"

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

namespace piezocontact::app
{
namespace
{
// What the child process inherits: not the MPI job's variables, which
// would make its mpi4py join (and break) this job
const char* child_env_keys[] = {"PATH", "HOME", "TMPDIR", "XDG_CACHE_HOME", "LANG", "PYTHONPATH"};

std::string quote(const std::string& s)
{
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
} // namespace

int convert_mesh(const MeshConversion& job)
{
  std::string cmd = "env -i";
  for (const char* k : child_env_keys)
    if (const char* v = std::getenv(k))
      cmd += std::string(" ") + k + "=" + quote(v);
  if (job.type == "gmsh")
    cmd += " /usr/bin/python3 " + quote(job.input.string()) + " --size "
           + nlohmann::json(job.size).dump();
  else
    cmd += " /usr/bin/python3 -m piezocontact.msh " + quote(job.input.string());
  cmd += " --output " + quote(job.target.string()) + " > " + quote(job.log.string()) + " 2>&1";
  const int status = std::system(cmd.c_str());
  if (status == -1)
    return 127;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
} // namespace piezocontact::app
