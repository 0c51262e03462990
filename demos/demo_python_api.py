#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # The Python API: the C++ time loop from a script, and the physics changed without a rebuild
#
# `piezocontact.solve` runs a config through the C++ core of piezocontact on
# forms that dolfinx JIT-compiles from the UFL of `forms/`, or through the
# independent reference engine. This demo
#
# 1. runs example 1 of the paper (the square, `demos/square.json`) with both
#    engines and compares them;
# 2. replaces the normal compliance law `p(r) = c_p max(r, 0)` by a power law
#    and adds a bulk term to the residual — from this script, no rebuild — and
#    checks that both engines still agree.
#
#     /usr/bin/python3 demos/demo_python_api.py [--n 16]

# +
import argparse
from pathlib import Path

import piezocontact
import ufl
from piezocontact import compare

HERE = Path(__file__).resolve().parent
# -

# ## Running a config
#
# `config` is a path or a dict; `overrides` are the `--set` of the command
# line. The result is the summary that is also written to
# `output/summary.json`: per step, the probe values, the contact force, the
# largest `u.nu - g` on the contact boundary, the reactions, Newton's
# residual history.


def run(out, engine, n, overrides=(), **hooks):
    return piezocontact.solve(HERE / "square.json", output=out, engine=engine,
                              overrides=[f"mesh.n={n}", f"time.steps={n}", *overrides],
                              progress=False, **hooks)


def largest_difference(a, b):
    """Largest difference of any probe value over all steps, relative to the
    largest magnitude of that value over the run."""
    return max(max(d["u"], d["phi"]) for d in compare.probe_differences(a, b))


# ## Changing the physics from a script
#
# `contact_law(r, c_p)` replaces `p`; `extra_residual(u, phi, w, psi, data)`
# returns a UFL form added to the residual, its Jacobian taken by UFL. `data`
# holds the runtime Constants of the forms (`Bv`, `e`, `beta`, `c_p`, `k`, ...).
# The C++ loop keeps its exact LU reuse: a term whose Jacobian changes with
# the state joins the part of the Jacobian compared between iterations.


def power_law(r, c_p):
    return c_p * ufl.max_value(r, 0) ** 2  # c_p in N/m^4 now: 1e22 below


def winkler_bulk(u, phi, w, psi, data):
    """A weak elastic bed under the whole body, 1e8 N/m^4."""
    return 1e8 * ufl.inner(u, w) * ufl.dx


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=16)
    ap.add_argument("--output", default=str(HERE.parent / "out" / "api"))
    args = ap.parse_args()
    out = Path(args.output)

    plain = {e: run(out / e, e, args.n) for e in ("cpp", "reference")}
    last = plain["cpp"]["steps"][-1]
    print(f"example 1, n = {args.n}: probe (1, 1) u = {last['probes'][0]['u']}, "
          f"contact force {last['contact_force']} N/m")
    print(f"  cpp vs reference: largest relative probe difference "
          f"{largest_difference(plain['cpp'], plain['reference']):.1e}")

    hooks = dict(contact_law=power_law, extra_residual=winkler_bulk)
    edited = {e: run(out / f"{e}-edited", e, args.n, ["contact.c_p=1e22"], **hooks)
              for e in ("cpp", "reference")}
    last = edited["cpp"]["steps"][-1]
    print(f"power law + elastic bed: largest u.nu - g = {last['max_penetration']:.3e} m, "
          f"contact force {last['contact_force']} N/m")
    print(f"  cpp vs reference: largest relative probe difference "
          f"{largest_difference(edited['cpp'], edited['reference']):.1e}")


if __name__ == "__main__":
    main()
