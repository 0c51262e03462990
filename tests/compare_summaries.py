#!/usr/bin/python3
"""Compare the probes of two runs of the same discrete problem, step by
step: u relative to the largest |u| at the probes over the run, phi to the
largest |phi| (each field in its own unit). Exit 1 above the tolerance.

    compare_summaries.py A/summary.json B/summary.json --tolerance 1e-10
    compare_summaries.py A/summary.json B/summary.json --identical

--identical: every step record (all but its timing) equal, bit for bit.
"""

import argparse
import json
import sys


def probe_values(summary):
    """Per step, per probe: (u components, phi)."""
    return [[(p["u"], p["phi"]) for p in step["probes"]] for step in summary["steps"]]


def identical(a, b):
    """Every step record equal but its timing: 0, else 1 naming the first
    step and keys that differ."""
    def record(step):
        return {k: v for k, v in step.items() if k != "timing"}
    if len(a["steps"]) != len(b["steps"]):
        print(f"different step counts: {len(a['steps'])} and {len(b['steps'])}")
        return 1
    for i, (sa, sb) in enumerate(zip(a["steps"], b["steps"]), start=1):
        if record(sa) != record(sb):
            keys = sorted(k for k in record(sa).keys() | record(sb).keys() if sa.get(k) != sb.get(k))
            print(f"step {i} differs: {', '.join(keys)}")
            return 1
    print(f"{len(a['steps'])} steps: identical")
    return 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--tolerance", type=float, default=1e-10)
    ap.add_argument("--identical", action="store_true")
    args = ap.parse_args()
    a, b = (json.load(open(f)) for f in (args.a, args.b))
    if args.identical:
        return identical(a, b)
    pa, pb = probe_values(a), probe_values(b)
    if len(pa) != len(pb):
        print(f"different step counts: {len(pa)} and {len(pb)}")
        return 1
    scale_u = max(abs(c) for step in pa for u, _ in step for c in u)
    scale_phi = max(abs(phi) for step in pa for _, phi in step)
    du = max(abs(x - y) for sa, sb in zip(pa, pb) for (ua, _), (ub, _) in zip(sa, sb)
             for x, y in zip(ua, ub))
    dphi = max(abs(x - y) for sa, sb in zip(pa, pb) for (_, x), (_, y) in zip(sa, sb))
    worst = max(du / scale_u, dphi / scale_phi)
    print(f"{len(pa)} steps x {len(pa[0])} probes: largest difference u {du:.3e} m "
          f"({du / scale_u:.1e} of {scale_u:.3e}), phi {dphi:.3e} V "
          f"({dphi / scale_phi:.1e} of {scale_phi:.3e}); tolerance {args.tolerance:.0e}: "
          + ("agree" if worst <= args.tolerance else "DIFFER"))
    return 0 if worst <= args.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
