"""Bad input: both solvers refuse it with exit code 2 and the same message,
which names the file, the key and the value, before writing anything."""

import json

import pytest
from conftest import SQUARE, run_solver


def both(tmp_path, overrides=(), config=SQUARE):
    out = {}
    for solver in ("cpp", "python"):
        _, proc = run_solver(solver, tmp_path / solver, overrides, config=config, check=False)
        assert proc.returncode == 2, (solver, proc.stderr)
        lines = [line for line in proc.stderr.splitlines() if line.startswith("error: ")]
        assert len(lines) == 1, (solver, proc.stderr)
        out[solver] = lines[0]
        assert not (tmp_path / solver / "summary.json").exists()
    return out


CASES = {
    "unknown key": (["time.stpes=3"], "time.stpes: unknown key (did you mean 'time.steps'?)"),
    "zero steps": (["time.steps=0"], "time.steps = 0: must be >= 1"),
    "negative T": (["time.T=-1"], "time.T = -1: must be > 0"),
    "non-integer n": (["mesh.n=4.5"], "mesh.n = 4.5: expected an integer"),
    "paper's permittivity sign": (
        ["material.permittivity=[[-7.37455e-11,0],[0,-7.8188e-11]]"],
        "material.permittivity = [[-7.37455e-11,0.0],[0.0,-7.8188e-11]]: not positive "
        "definite: permittivity must be positive definite (2.14c)"),
    "negative penalty": (["contact.c_p=-1"], "contact.c_p = -1: must be >= 0"),
    "unknown boundary": (["boundaries.lft={}"],
                         "boundaries.lft: the mesh has no boundary 'lft' "
                         "(it has: bottom, left, right, top)"),
    "probe outside": (["probes=[[2,2]]"], "probes[0] = [2.0,2.0]: outside the mesh"),
    "wrong type": (["boundaries.top.traction=5"],
                   "boundaries.top.traction = 5: expected a list of 2 numbers"),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_value(case, tmp_path):
    overrides, expected = CASES[case]
    messages = both(tmp_path, overrides)
    assert messages["cpp"] == messages["python"]
    assert messages["cpp"].startswith(f"error: {SQUARE}: ")
    assert expected in messages["cpp"]


def test_missing_required_key(tmp_path):
    cfg = json.loads(SQUARE.read_text())
    del cfg["contact"]["c_p"]
    path = tmp_path / "no_cp.json"
    path.write_text(json.dumps(cfg))
    messages = both(tmp_path, config=path)
    assert messages["cpp"] == messages["python"] == \
        f"error: {path}: contact.c_p: missing required key"


def test_malformed_json_names_line_and_column(tmp_path):
    path = tmp_path / "broken.json"
    path.write_text('{\n  "mesh": {"type": "unit_square", "n": 4,}\n}\n')
    messages = both(tmp_path, config=path)
    # the parsers' own descriptions differ; where they stopped does not
    for m in messages.values():
        assert m.startswith(f"error: {path}: invalid JSON at line 2 column 42: ")


def test_missing_file(tmp_path):
    messages = both(tmp_path, config=tmp_path / "nope.json")
    assert messages["cpp"] == messages["python"] == \
        f"error: {tmp_path / 'nope.json'}: cannot read config file: No such file or directory"
