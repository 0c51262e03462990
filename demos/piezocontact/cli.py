"""Command line shared by the Python twin and the demos; the same flags and
exit codes as the C++ executable `piezo-contact`."""

import argparse
import json
import sys
from pathlib import Path

from mpi4py import MPI

from . import config

EXIT_RUN_ERROR = 3


def _abort_on_uncaught(exc_type, exc, tb):
    """An unexpected exception on one rank must not leave the others waiting
    in a collective call: print it and abort the whole MPI job."""
    sys.__excepthook__(exc_type, exc, tb)
    if MPI.COMM_WORLD.size > 1:
        MPI.COMM_WORLD.Abort(1)


sys.excepthook = _abort_on_uncaught


def parser(description):
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--config", help="JSON run configuration")
    ap.add_argument("--output", required=True, help="output directory")
    ap.add_argument("--resume", action="store_true",
                    help="continue the interrupted or failed run in --output "
                         "(its config is in summary.json)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE",
                    help="override a config value (JSON value), e.g. --set mesh.n=64")
    ap.add_argument("--quiet", action="store_true", help="no per-step progress lines")
    return ap


def fail(message, code):
    """Print on rank 0, exit with the same code on every rank (no deadlock)."""
    if MPI.COMM_WORLD.rank == 0:
        print(f"error: {message}", file=sys.stderr, flush=True)
    sys.exit(code)


def prepare_output(path, source, comm):
    """Create DIR and check it can be written, on rank 0; every rank gets the
    same error, so that none waits for the others forever."""
    error = None
    if comm.rank == 0:
        try:
            Path(path).mkdir(parents=True, exist_ok=True)
            probe = Path(path) / ".write-test"
            probe.write_text("")
            probe.unlink()
        except OSError as err:
            error = f"{source}: --output {path}: cannot write there: {err.strerror}"
    error = comm.bcast(error, root=0)
    if error:
        raise config.ConfigError(error)


def resumable_summary(out_dir, solver, overrides=()):
    """The summary.json of an interrupted or failed run in DIR, to continue
    it, with its config. `--set time.T=... --set time.steps=...` extend a
    run (completed or not) at the same step size."""
    path = Path(out_dir) / "summary.json"
    where = f"{path}: cannot resume: "
    try:
        summary = json.loads(path.read_text())
    except OSError:
        raise config.ConfigError(where + "no such file") from None
    except ValueError:
        raise config.ConfigError(where + "not valid JSON") from None
    if not isinstance(summary, dict) or summary.get("solver") != solver:
        found = summary.get("solver") if isinstance(summary, dict) else None
        raise config.ConfigError(where + f'solver = {json.dumps(found)}, '
                                 f'this is the "{solver}" solver')
    if "checkpoint" not in summary or "config" not in summary:
        raise config.ConfigError(where + "no checkpoint (an older version wrote it)")
    for o in overrides:
        key = o.split("=", 1)[0]
        if key not in ("time.T", "time.steps"):
            raise config.ConfigError(f"{path}: --set {key}: only time.T and time.steps can "
                                     "change on --resume (to extend the run)")
    old = summary["config"]
    cfg = config.configure(json.loads(json.dumps(old)), overrides, str(path))
    k_old = old["time"]["T"] / old["time"]["steps"]
    k_new = cfg["time"]["T"] / cfg["time"]["steps"]
    if k_new != k_old:
        raise config.ConfigError(f"{path}: time.T / time.steps = {k_new!r}: an extended run "
                                 f"keeps its step T/steps = {k_old!r}")
    done = summary["checkpoint"].get("nominal_steps", 0)
    if cfg["time"]["steps"] < done:
        raise config.ConfigError(f"{path}: time.steps = {cfg['time']['steps']}: the run has "
                                 f"done {done} steps already")
    if summary.get("status") == "completed" and cfg["time"]["steps"] == old["time"]["steps"]:
        raise config.ConfigError(where + 'status = "completed" (to extend it, --set time.T '
                                 "and time.steps)")
    return summary, cfg
