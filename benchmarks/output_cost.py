#!/usr/bin/python3
"""What writing the outputs costs per step: example 1 (k = h = 1/n, T = 1),
XDMF on and off (nodal files off), wall time measured from outside, and the
run's own split of its output time (summary.json timing.output: step files,
checkpoint, summary). With --baseline BUILD, the same runs of another build
(e.g. the release before the outputs were made kill-safe) for comparison.

    /usr/bin/python3 benchmarks/output_cost.py                       # prints markdown
    /usr/bin/python3 benchmarks/output_cost.py --sizes 128 256 --baseline /tmp/old/build
    /usr/bin/python3 benchmarks/output_cost.py --solver cpp-jit --sizes 64 128
    ... --write docs/benchmarks.md   # (re)places its section there

Each configuration is run --repeat times and the fastest run is kept (the
disk cache makes the first write of a file slower than the others).
"""

import argparse
import json
import os
import platform
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SQUARE = ROOT / "demos" / "square.json"
HEADING = "## Output cost per step"


def command(solver, build):
    """The executable, or the C++ loop from Python (that build's package)."""
    if solver == "cpp":
        return [str(Path(build) / "piezo-contact")]
    return ["env", f"PYTHONPATH={Path(build) / 'python'}", "/usr/bin/python3", "-m", "piezocontact"]


def run(cmd, n, xdmf):
    """Wall time (s) and summary of one run."""
    with tempfile.TemporaryDirectory(dir=os.environ.get("PIEZO_BENCH_DIR")) as out:
        args = cmd + ["--config", str(SQUARE), "--output", out, "--quiet"]
        for o in (f"mesh.n={n}", f"time.steps={n}", "output.nodal=none",
                  f"output.xdmf={'true' if xdmf else 'false'}"):
            args += ["--set", o]
        t0 = time.perf_counter()
        subprocess.run(args, check=True, capture_output=True)
        wall = time.perf_counter() - t0
        return wall, json.loads((Path(out) / "summary.json").read_text())


def fastest(cmd, n, xdmf, repeat):
    return min((run(cmd, n, xdmf) for _ in range(repeat)), key=lambda r: r[0])


def ms_per_step(seconds, steps):
    return f"{1e3 * seconds / steps:.1f}"


def write_section(path, heading, lines):
    """(Re)place the section that starts with `heading` (to the next ##
    heading) in a markdown file, or append it."""
    path = Path(path)
    text = path.read_text() if path.exists() else ""
    section = "\n".join(lines) + "\n"
    start = text.find(heading)
    if start < 0:
        text = text.rstrip("\n") + "\n\n" + section
    else:
        end = text.find("\n## ", start + 1)
        text = text[:start] + section + (text[end + 1:] if end >= 0 else "")
    path.write_text(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[128, 256])
    ap.add_argument("--solver", choices=["cpp", "cpp-jit"], default="cpp")
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--baseline", help="another build directory to compare with (C++)")
    ap.add_argument("--baseline-name", default="another build",
                    help="what the baseline is, for the report")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--write", help="(re)place the report's section in this markdown file")
    args = ap.parse_args()

    builds = [("this", args.build)] + ([("baseline", args.baseline)] if args.baseline else [])
    t0 = time.perf_counter()
    lines = [f"{HEADING} ({args.solver})\n",
             f"Regenerate: `/usr/bin/python3 benchmarks/output_cost.py "
             f"--sizes {' '.join(map(str, args.sizes))}"
             + (" --baseline BUILD" if args.baseline else "")
             + f" --write docs/benchmarks.md` (this run: {platform.node()}, "
             f"{os.cpu_count()} cores, {time.strftime('%Y-%m-%d')}).\n",
             "Example 1, steps = n, T = 1, nodal files off; fastest of "
             f"{args.repeat} runs; times per step in ms. *XDMF on - off*: wall time with "
             "the XDMF output minus without, per step; *in run*: the run's own "
             "`timing.output` (step files: XDMF and nodal; checkpoint; summary.json)."
             + (" *baseline*: " + args.baseline_name if args.baseline else "") + "\n",
             "| n | build | wall, XDMF off (s) | wall, XDMF on (s) | XDMF on - off | "
             "in run: step files | checkpoint | summary |",
             "|---|---|---|---|---|---|---|---|"]
    print("\n".join(lines), flush=True)
    for n in args.sizes:
        for name, build in builds:
            cmd = command(args.solver, build)
            off, _ = fastest(cmd, n, False, args.repeat)
            on, summary = fastest(cmd, n, True, args.repeat)
            split = summary["timing"].get("output")
            inside = ([ms_per_step(split[k]["seconds"], n)
                       for k in ("step_files", "checkpoint", "summary")]
                      if split else ["-", "-", "-"])
            lines.append(f"| {n} | {name} | {off:.2f} | {on:.2f} | "
                         f"{ms_per_step(on - off, n)} | " + " | ".join(inside) + " |")
            print(lines[-1], flush=True)
    lines.append(f"\n(benchmark wall time {time.perf_counter() - t0:.0f} s)")
    if args.write:
        write_section(args.write, f"{HEADING} ({args.solver})", lines)

if __name__ == "__main__":
    main()
