"""Hostile input, generated: random mutations of the shipped configs and of
the command line, run through every engine.

A case is a config file (bytes: it may not even be JSON) and the arguments
after `--config FILE --output DIR`. Mutations, on a base made cheap (a coarse
mesh, two steps, no field output):
  value level: a key dropped or added, a value replaced by an extreme or
    non-finite number, a big integer, a string, null, a list or an object,
    wrapped in a list, or nested deeply;
  text level: a byte-order mark, invalid UTF-8, NUL, random bytes flipped,
    the file cut short, a number beyond double (1e400), NaN/Infinity tokens,
    more than 1 MiB, nesting 100000 deep;
  command line: malformed or hostile --set, unknown or repeated flags.

Every engine must answer every case with exit 0, 2 (bad input) or 3 (no
convergence), never a traceback, signal, PETSc or HDF5 dump; a failure is one
line of reasonable length. The executable and the C++ loop from Python run
the same code and must agree exactly; bad input is refused by all three with
the same message. The reference engine (its own Newton, fixed steps, no
solver.newton settings) may end a run the C++ loop ends differently (0 vs 3)
only where a mutation touched solver.newton, the settings it does not use,
or put a number 1e9 or more off its scale: there the two independent
acceptance tests (scaled residual and increments) need not reach the same
verdict (e.g. a piezoelectric coupling of 2e9 C/m^2 makes the C++ loop's
phi residual stall at round-off; it stops rather than accept).

    /usr/bin/python3 tests/fuzz.py --cases 300 --seed 1    # prints a report
"""

import argparse
import collections
import json
import os
import random
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BUILD = Path(os.environ.get("PIEZO_BUILD", ROOT / "build"))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           PYTHONPATH=str(BUILD / "python"))
WORKER = Path(__file__).with_name("fuzz_worker.py")
CASE_TIMEOUT = 120  # s; a hang is a finding

CHEAP = {"square.json": {"mesh": {"n": 3}}, "manufactured.json": {"mesh": {"n": 3}},
         "contactor.json": {"mesh": {"size": 0.5}}, "slab.json": {"mesh": {"n": [2, 2, 1]}},
         "manufactured_3d.json": {"mesh": {"n": [1, 1, 1]}}, "bilayer.json": {"mesh": {}},
         # a floating electrode and a load history
         "sensor.json": {"mesh": {"size": 0.5}}}
EXTREMES = [0, -1, 1, 0.5, 1e308, -1e308, 5e-324, 1e-300, 2 ** 31 - 1, 2 ** 31, -2 ** 31 - 1,
            2 ** 63, 2 ** 64, 10 ** 30, "", "x", "\u0000", "\u00e9", True, False, None, [], {},
            [[]], [1e308, 1e308], [0.0, 0.0, 0.0], {"bogus": 1}]
FORBIDDEN = ("Traceback", "PETSC ERROR", "HDF5-DIAG", "Segmentation", "MPI_ABORT",
             "terminate called", "error (rank", "Aborted", "core dumped")
MAX_LINE = 400


def base_configs():
    """The shipped configs, cheap, with absolute paths (the case files live
    elsewhere)."""
    out = {}
    for name, cheap in CHEAP.items():
        cfg = json.loads((ROOT / "demos" / name).read_text())
        for key in ("geometry", "path"):
            if key in cfg["mesh"]:
                cfg["mesh"][key] = str((ROOT / "demos" / cfg["mesh"][key]).resolve())
        cfg["mesh"].update(cheap["mesh"])
        cfg["time"]["steps"] = 2
        cfg["output"] = {"xdmf": False, "nodal": "none"}
        out[name] = cfg
    return out


def paths(node, prefix=()):
    """Every key path of a JSON value (objects and lists)."""
    yield prefix
    items = node.items() if isinstance(node, dict) else \
        enumerate(node) if isinstance(node, list) else []
    for k, v in items:
        yield from paths(v, prefix + (k,))


def get(node, path):
    for k in path:
        node = node[k]
    return node


def put(node, path, value):
    get(node, path[:-1])[path[-1]] = value


def nested(depth, inner="1"):
    return "[" * depth + inner + "]" * depth


def off_scale(value):
    """A number (or list holding one) 1e9 or more from any physical datum of
    the shipped configs."""
    if isinstance(value, list):
        return any(off_scale(v) for v in value)
    return isinstance(value, (int, float)) and not isinstance(value, bool) and value != 0 \
        and (abs(value) >= 1e20 or abs(value) <= 1e-20 or abs(value) >= 2 ** 31 - 1)


def mutate_value(rng, cfg):
    """A config mutated at one key path; its description."""
    path = rng.choice([p for p in paths(cfg) if p])
    op = rng.choice(["replace", "replace", "replace", "drop", "add", "wrap", "nest"])
    where = ".".join(map(str, path))
    if op == "drop":
        parent = get(cfg, path[:-1])
        if isinstance(parent, dict):
            del parent[path[-1]]
        else:
            parent.pop(path[-1])
    elif op == "add":
        target = get(cfg, path) if isinstance(get(cfg, path), dict) else get(cfg, path[:-1])
        if isinstance(target, dict):
            target[rng.choice(["bogus", "probes", "\u00ff", "x" * 300])] = rng.choice(EXTREMES)
    elif op == "wrap":
        put(cfg, path, [get(cfg, path)])
    elif op == "nest":
        put(cfg, path, json.loads(nested(rng.choice([5, 31, 40]))))
    else:
        put(cfg, path, rng.choice(EXTREMES))
    return json.dumps(cfg).encode(), f"{op} {where}" + (" (off scale)" if op == "replace"
                                                         and off_scale(get(cfg, path)) else "")


def mutate_text(rng, text):
    """Bytes that may not be JSON; the description."""
    op = rng.choice(["bom", "utf8", "nul", "flip", "cut", "overflow", "nan", "huge", "deep",
                     "directory"])
    if op == "bom":
        return b"\xef\xbb\xbf" + text, op
    if op == "utf8":
        i = text.index(b'"') + 1
        return text[:i] + rng.choice([b"\xff", b"\xc3", b"\xed\xa0\x80"]) + text[i:], op
    if op == "nul":
        i = rng.randrange(len(text))
        return text[:i] + b"\x00" + text[i:], op
    if op == "flip":
        b = bytearray(text)
        for _ in range(rng.randint(1, 5)):
            b[rng.randrange(len(b))] = rng.randrange(256)
        return bytes(b), op
    if op == "cut":
        return text[:rng.randrange(len(text))], op
    if op == "overflow":
        return text.replace(b"2", b"1e400", 1), op
    if op == "nan":
        return text.replace(b"2", rng.choice([b"NaN", b"Infinity", b"-Infinity"]), 1), op
    if op == "huge":
        return text[:-1] + b', "pad": "' + b"x" * (1 << 20) + b'"}', op
    if op == "deep":
        return text[:-1] + b', "probes": ' + nested(100000, "").encode() + b"}", op
    return None, op  # the config path is a directory


def mutate_args(rng, cfg):
    """Extra command-line arguments; the description."""
    keys = [".".join(map(str, p)) for p in paths(cfg) if p]
    op = rng.choice(["set", "set", "set", "malformed", "unknown", "repeat", "trailing"])
    if op == "set":
        value = rng.choice(["1e400", "nan", "-inf", "2147483648", "99999999999999999999",
                            "[]", "{}", "null", "true", "\xff", nested(40), "mumps", "-1", ""])
        return ["--set", f"{rng.choice(keys)}={value}"], op
    if op == "malformed":
        return ["--set", rng.choice(["=3", "=", "a..b=1", ".a=1", "a.=1", "time.steps",
                                     "probes.99999999999999999999=1", "\xff=1",
                                     "solver.petsc_options.-ksp_type=cg",
                                     "solver.petsc_options.pc_type=bogus",
                                     "solver.petsc_options.ksp_rtol=abc"])], op
    if op == "unknown":
        return [rng.choice(["--quite", "-ksp_view", "--verbose", "x", "--set=1"])], op
    if op == "repeat":
        return ["--output", "/tmp/elsewhere"], op
    return ["--set"], op


def make_case(rng, bases):
    name = rng.choice(sorted(bases))
    cfg = json.loads(json.dumps(bases[name]))
    level = rng.choice(["value", "value", "text", "args"])
    args = []
    if level == "value":
        text, what = mutate_value(rng, cfg)
    elif level == "text":
        text, what = mutate_text(rng, json.dumps(cfg).encode())
    else:
        args, what = mutate_args(rng, cfg)
        text = json.dumps(cfg).encode()
    return {"base": name, "mutation": f"{level}: {what}", "text": text, "args": args}


def materialise(case, directory, index):
    """(config path, output directory) of a case."""
    d = Path(directory) / f"case{index:05d}"
    d.mkdir()
    config = d / "config.json"
    if case["text"] is None:
        config.mkdir()
    else:
        config.write_bytes(case["text"])
    return str(config), str(d / "out")


def run_executable(argv):
    """(exit code, stderr, whether the loop cut a step)"""
    proc = subprocess.run([str(BUILD / "piezo-contact")] + argv, capture_output=True,
                          env=ENV, timeout=CASE_TIMEOUT)
    return (proc.returncode, proc.stderr.decode(errors="replace"),
            STEP_CUT in proc.stdout.decode(errors="replace"))


def run_worker(engine, argvs):
    """Run the cases in one Python process (the package in-process, as a
    script drives it). A crash or hang names the case it happened in."""
    proc = subprocess.run(["/usr/bin/python3", str(WORKER), engine],
                          input=json.dumps(argvs), capture_output=True, text=True, env=ENV,
                          timeout=CASE_TIMEOUT * 4 + 10 * len(argvs))
    results = [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]
    if proc.returncode != 0 or len(results) != len(argvs):
        raise AssertionError(f"{engine} worker died (exit {proc.returncode}) in case "
                             f"{len(results)}: {argvs[len(results)] if len(results) < len(argvs) else ''}"
                             f"\n{proc.stderr[-3000:]}")
    return [(r["code"], r["stderr"]) for r in results]


# What the C++ loop prints when it halves a step (even with --quiet), and
# what either engine says when its convergence test stalls at round-off
STEP_CUT = "retrying with k ="
STALLED = "stalled at round-off"


def problems(code, stderr):
    """What is wrong with one engine's answer to a case."""
    found = [f"exit {code}"] if code not in (0, 2, 3) else []
    found += [f"'{word}' in stderr" for word in FORBIDDEN if word in stderr]
    errors = [line for line in stderr.splitlines() if line.startswith("error")]
    if code in (2, 3) and len(errors) != 1:
        found.append(f"{len(errors)} error lines")
    found += [f"an error line of {len(line)} characters" for line in errors
              if len(line) > MAX_LINE]
    return found


def run_cases(n, seed, directory, skip=0):
    """Generate n cases of a seed's stream, run those after the first
    `skip`; a report: counts and findings."""
    rng = random.Random(seed)
    bases = base_configs()
    cases = [make_case(rng, bases) for _ in range(n)][skip:]
    argvs = []
    for i, case in enumerate(cases):
        config, out = materialise(case, directory, i)
        argvs.append(["--config", config, "--output", out, "--quiet"] + case["args"])
    executable = [run_executable(a) for a in argvs]
    step_cut = [cut for _, _, cut in executable]
    answers = {"cpp": [(code, err) for code, err, _ in executable],
               "cpp-jit": run_worker("cpp", argvs),
               "reference": run_worker("reference", argvs)}
    findings, codes, newton_only, step_cuts, round_off = [], collections.Counter(), 0, 0, 0
    for i, case in enumerate(cases):
        got = {e: answers[e][i] for e in answers}
        codes[tuple(got[e][0] for e in answers)] += 1
        label = f"case {i + skip} ({case['base']}, {case['mutation']}, args {case['args']})"
        for engine, (code, stderr) in got.items():
            for p in problems(code, stderr):
                findings.append(f"{label}: {engine}: {p}: {stderr.strip()[-300:]}")
        c, j, r = (got[e][0] for e in ("cpp", "cpp-jit", "reference"))
        if c != j:
            findings.append(f"{label}: cpp exit {c}, cpp-jit exit {j}")
        if (c == 2) != (r == 2):
            findings.append(f"{label}: cpp exit {c}, reference exit {r}")
        elif c == 2:
            lines = {e: [x for x in got[e][1].splitlines() if x.startswith("error")]
                     for e in got}
            if len({tuple(v) for v in lines.values()}) != 1:
                findings.append(f"{label}: messages differ: {lines}")
        elif c != r:
            if any(tag in case["mutation"] for tag in ("solver.newton", "(off scale)")) \
                    or any("solver.newton" in a for a in case["args"]):
                newton_only += 1
            elif any(STALLED in got[e][1] for e, code in (("cpp", c), ("reference", r))
                     if code == 3):
                # one engine's acceptance test cannot be met in double
                # precision and it says so (data off scale by orders of
                # magnitude: e 1e9 times a real one, a 1 m prescribed
                # displacement); the other's test, of another quantity, is
                round_off += 1
            elif (c, r) == (0, 3) and step_cut[i]:
                # the reference has no step control, by design: where the C++
                # loop converged only with a shorter step (e.g. an indefinite
                # elastic tensor, which the paper allows: A/k + B is coercive
                # for k small enough), full steps may fail
                step_cuts += 1
            else:
                findings.append(f"{label}: cpp exit {c}, reference exit {r}")
    return {"cases": len(cases), "seed": seed, "exit codes (cpp, cpp-jit, reference)": dict(
        (",".join(map(str, k)), v) for k, v in sorted(codes.items())),
        "reference differs (solver.newton or off-scale data)": newton_only,
        "reference fails at full steps where the C++ loop cut its step": step_cuts,
        "one engine stops at round-off, the other accepts": round_off,
        "findings": findings}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        report = run_cases(args.cases, args.seed, d)
    print(json.dumps(report, indent=1))
    return 1 if report["findings"] else 0


if __name__ == "__main__":
    sys.exit(main())
