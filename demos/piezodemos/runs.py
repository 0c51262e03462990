"""Run the engines on one config and report how they compare: the C++
executable (ahead-of-time kernels), the C++ loop from Python (JIT kernels)
and the independent reference engine."""

import math
import os
import subprocess
import sys
import time
from pathlib import Path

from piezocontact import compare

def solver_commands(build_dir, np_):
    """The command line of each engine, optionally under mpirun."""
    mpi = ["mpirun", "-n", str(np_)] if np_ > 1 else []
    module = ["/usr/bin/python3", "-m", "piezocontact"]
    return {"cpp": mpi + [str(Path(build_dir) / "piezo-contact")],
            "cpp-jit": mpi + module,
            "reference": mpi + module + ["--engine", "reference"]}


ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def run_quietly(solver, config, out_dir, overrides, build_dir):
    """One serial run without progress lines; (summary, wall seconds)."""
    args = solver_commands(build_dir, 1)[solver] + [
        "--config", str(config), "--output", str(out_dir), "--quiet"]
    for o in overrides:
        args += ["--set", o]
    t0 = time.perf_counter()
    subprocess.run(args, check=True, env=ENV)
    return compare.load_summary(out_dir), time.perf_counter() - t0


def observed_rates(sizes, errors):
    """log(e_i / e_{i+1}) / log(s_i / s_{i+1}) between successive runs;
    None first (and where an error is zero)."""
    return [None] + [math.log(e0 / e1) / math.log(s0 / s1) if e0 > 0 and e1 > 0 else None
                     for s0, s1, e0, e1 in zip(sizes, sizes[1:], errors, errors[1:])]


def run_both(config, out_dir, overrides, build_dir, np_=1, engines=("cpp", "reference")):
    """Run the engines on one config (the executable and the reference by
    default); return their summaries."""
    env = ENV
    summaries = {}
    for name in engines:
        cmd = solver_commands(build_dir, np_)[name]
        args = cmd + ["--config", str(config), "--output", str(Path(out_dir) / name)]
        for o in overrides:
            args += ["--set", o]
        print(f"\n$ {' '.join(args)}", flush=True)
        t0 = time.perf_counter()
        subprocess.run(args, check=True, env=env)
        print(f"  ({name}: {time.perf_counter() - t0:.1f} s wall, including start-up)")
        summaries[name] = compare.load_summary(Path(out_dir) / name)
    return summaries


def report(summaries, out_dir):
    cpp, py = summaries["cpp"], summaries["reference"]
    print()
    print(compare.table(cpp, py))
    fields = compare.field_differences(Path(out_dir) / "cpp", Path(out_dir) / "reference", py)
    final = fields[max(fields)]
    print(f"\nrelative L2 difference at t = {cpp['steps'][-1]['t']:g}: "
          f"u {final['u']:.2e}, phi {final['phi']:.2e}")
    q_size, of_size, q_value, by_value = compare.worst_agreement(cpp, py)
    print(f"largest difference over all steps, probes, forces, reactions and charges: "
          f"{of_size:.1e} of the quantity's size ({q_size}), {by_value:.1e} value by value "
          f"({q_value})")
    for name, s in summaries.items():
        its = [st["newton_iterations"] for st in s["steps"]]
        t = s["timing"]
        print(f"{name:>6}: {s['dofs']} dofs, {len(its)} steps, Newton iterations "
              f"{min(its)}-{max(its)} (total {sum(its)}), time {t['total_s']:.2f} s "
              f"(assembly {t['assembly_s']:.2f} s, solve {t['solve_s']:.2f} s)")
    last = cpp["steps"][-1]
    if last.get("max_penetration") is not None:  # a run with a contact boundary
        print(f"contact force {last['contact_force']}, largest u.nu - g on Gamma_C "
              f"{last['max_penetration']:.3e} m")
    return max(final.values()), of_size, by_value


# What the engines promise (docs/verification.md): both stop Newton on a bound
# of the error, so they agree to the round-off of one discrete solution
OF_SIZE, BY_VALUE = 1e-9, 1e-8


def verdict(of_size, by_value):
    """Print whether two engines agree as promised; True if they do."""
    ok = of_size <= OF_SIZE and by_value <= BY_VALUE
    text = (f"{of_size:.1e} of each quantity's size (promised {OF_SIZE:.0e}), "
            f"{by_value:.1e} value by value (promised {BY_VALUE:.0e})")
    if ok:
        print(f"\nthe engines agree: {text}")
    else:
        print(f"error: the C++ engine and the reference DISAGREE: {text}", file=sys.stderr)
    return ok
