"""Bad input: every engine refuses it with exit code 2 and the same message
(one validator, in the C++ core), which names the file, the key and the
value, before writing anything. The executable runs a process per case;
each Python engine runs every case in one process (the package as a script
drives it, tests/fuzz_worker.py), as it would a process each."""

import os
import subprocess
import time

import pytest
from bad_inputs import CASES, materialise
from conftest import ENGINES, ENV, SQUARE, command
from fuzz import run_executable, run_worker


def messages(case, tmp_path, np_=1):
    config, overrides, out = materialise(case, tmp_path)
    result = {}
    for solver in ENGINES:
        args = command(solver, np_) + ["--config", str(config), "--output", out, "--quiet"]
        for o in overrides:
            args += ["--set", o]
        t0 = time.perf_counter()
        proc = subprocess.run(args, capture_output=True, text=True, env=ENV, timeout=120)
        assert proc.returncode == 2, (solver, proc.stderr)
        lines = [line for line in proc.stderr.splitlines() if line.startswith("error: ")]
        assert len(lines) == 1, (solver, proc.stderr)
        result[solver] = (lines[0], time.perf_counter() - t0)
        assert not os.path.exists(os.path.join(out, "summary.json"))
    return result


@pytest.fixture(scope="module")
def refusals(tmp_path_factory):
    """{case: (config, out, {engine: (exit code, stderr)})} of every case."""
    made, argvs = {}, []
    for i, case in enumerate(CASES):
        config, overrides, out = materialise(case, tmp_path_factory.mktemp(f"case{i}"))
        made[case] = (config, out)
        argvs.append(["--config", str(config), "--output", out, "--quiet"]
                     + [a for o in overrides for a in ("--set", o)])
    answers = {"cpp": [run_executable(a)[:2] for a in argvs],
               "cpp-jit": run_worker("cpp", argvs), "reference": run_worker("reference", argvs)}
    return {case: (*made[case], {e: answers[e][i] for e in ENGINES})
            for i, case in enumerate(CASES)}


@pytest.mark.parametrize("case", list(CASES))
def test_bad_input_is_refused_alike(case, refusals):
    config, out, found = refusals[case]
    lines = {}
    for engine, (code, stderr) in found.items():
        assert code == 2, (engine, stderr)
        lines[engine] = [line for line in stderr.splitlines() if line.startswith("error: ")]
        assert len(lines[engine]) == 1, (engine, stderr)
    assert not os.path.exists(os.path.join(out, "summary.json"))
    cpp = lines["cpp"][0]
    assert cpp.startswith(f"error: {config}: ")
    assert CASES[case][2] in cpp
    assert {line for (line,) in lines.values()} == {cpp}


@pytest.mark.parametrize("case", ["unknown key", "probe outside the domain"])
def test_bad_input_under_mpi_exits_promptly(case, tmp_path):
    """Raised on every rank: mpirun -n 2 exits with 2, no rank left waiting."""
    for solver, (message, seconds) in messages(case, tmp_path, np_=2).items():
        assert CASES[case][2] in message
        assert seconds < 60, (solver, seconds)


def test_unknown_engine_is_refused(tmp_path):
    """--engine is parsed by the C++ command line, with the other flags."""
    proc = subprocess.run(command("cpp-jit") + ["--engine", "fast", "--config", str(SQUARE),
                                                "--output", str(tmp_path / "out")],
                          capture_output=True, text=True, env=ENV, timeout=120)
    assert proc.returncode == 2
    assert proc.stderr.splitlines()[-1] == "error: --engine fast: not one of the engines above"
    assert "--engine cpp|reference (default cpp)" in proc.stderr
    assert not (tmp_path / "out").exists()
