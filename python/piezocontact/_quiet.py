"""The JIT compilation of forms, quiet.

dolfinx compiles forms through ffcx and cffi, whose compiler driver
(distutils) configures the root logger at INFO on its first use and then
logs every compiler command line through it: hundreds of lines per run.
A filter on the root logger drops those records (INFO and below, logged
from distutils' own log module) and says once per process that forms are
being compiled; everything else logged reaches its handlers as before."""

import logging
import sys


def _from_distutils(record):
    path = record.pathname.replace("\\", "/")
    return record.levelno <= logging.INFO and "distutils/" in path


class _QuietCompiler(logging.Filter):
    announced = False

    def filter(self, record):
        if not _from_distutils(record):
            return True
        if not self.announced:
            type(self).announced = True
            print("piezocontact: compiling forms (first run only)", file=sys.stderr,
                  flush=True)
        return False


def install():
    """Once per process: the filter on the root logger (distutils logs
    through the root logger itself, so its records pass the root's filters)."""
    root = logging.getLogger()
    if not any(isinstance(f, _QuietCompiler) for f in root.filters):
        root.addFilter(_QuietCompiler())
