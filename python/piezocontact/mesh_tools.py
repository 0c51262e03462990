"""The mesh tools of the Python front end: a gmsh script of meshes/ or the
.msh converter (python3 -m piezocontact.msh), run as a child process on one
rank, as the executable runs them (cpp/app/mesh_tools.cpp). The core calls
`convert` with a MeshConversion (mesh.h) and reads the log on failure."""

import os
import subprocess

# What the child inherits: not the MPI job's variables, which would make its
# mpi4py join (and break) this job
CHILD_ENV_KEYS = ("PATH", "HOME", "TMPDIR", "XDG_CACHE_HOME", "LANG", "PYTHONPATH")


PYTHON = "/usr/bin/python3"  # the executable's too: the interpreter with Debian's gmsh


def convert(job):
    """Run the tool of `job`; its exit status (0: done; 128 + N: killed by
    signal N). Never raises: the core reads the log."""
    if job.type == "gmsh":
        args = [PYTHON, job.input, "--size", repr(job.size)]
    else:
        args = [PYTHON, "-m", "piezocontact.msh", job.input]
    env = {k: os.environ[k] for k in CHILD_ENV_KEYS if k in os.environ}
    try:
        with open(job.log, "w") as log:
            code = subprocess.run(args + ["--output", job.target], stdout=log,
                                  stderr=subprocess.STDOUT, env=env).returncode
        return code if code >= 0 else 128 - code
    except BaseException as e:  # noqa: B902 (an escape would leave the other ranks waiting)
        try:
            with open(job.log, "a") as log:
                log.write(f"{type(e).__name__}: {e}\n")
        except OSError:
            pass
        return 127
