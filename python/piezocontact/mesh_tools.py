"""The mesh tools of the Python front end: a gmsh script of meshes/ or the
.msh converter (python3 -m piezocontact.msh), run as a child process on one
rank, as the executable runs them (cpp/app/mesh_tools.cpp). The core calls
`convert` with a MeshConversion (mesh.h) and reads the log on failure."""

import os
import subprocess
import sys

# What the child inherits: not the MPI job's variables, which would make its
# mpi4py join (and break) this job
CHILD_ENV_KEYS = ("PATH", "HOME", "TMPDIR", "XDG_CACHE_HOME", "LANG", "PYTHONPATH")


def convert(job):
    """Run the tool of `job`; its exit status (0: done)."""
    if job.type == "gmsh":
        args = [sys.executable, job.input, "--size", repr(job.size)]
    else:
        args = [sys.executable, "-m", "piezocontact.msh", job.input]
    env = {k: os.environ[k] for k in CHILD_ENV_KEYS if k in os.environ}
    with open(job.log, "w") as log:
        try:
            return subprocess.run(args + ["--output", job.target], stdout=log,
                                  stderr=subprocess.STDOUT, env=env).returncode
        except OSError as e:
            log.write(f"{e}\n")
            return 127
