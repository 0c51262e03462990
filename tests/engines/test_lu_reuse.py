"""Keeping the LU factorisation while the Jacobian is unchanged must not
change the answer: it is detected exactly (the contact part of J compared
value by value), not guessed. Run where the contact set changes during the
run (the contactor variant: the contact zone grows as the body relaxes)."""

import pytest
from conftest import ROOT, run_solver
from piezocontact import compare

VARIANT = ROOT / "demos" / "contactor_in_contact.json"
SMALL = ["mesh.size=0.2", "time.steps=10", "output.nodal=all"]


@pytest.fixture(scope="module")
def both_paths(tmp_path_factory):
    base = tmp_path_factory.mktemp("reuse")
    return {reuse: (run_solver("cpp", base / str(reuse), SMALL + [
        f"solver.reuse_factorisation={str(reuse).lower()}"], config=VARIANT)[0],
        base / str(reuse)) for reuse in (True, False)}


def test_reuse_gives_the_same_solution(both_paths):
    (a, a_dir), (b, b_dir) = both_paths[True], both_paths[False]
    assert [s["newton_iterations"] for s in a["steps"]] == \
        [s["newton_iterations"] for s in b["steps"]]
    for d in compare.probe_differences(a, b):
        assert d["u"] < 1e-10 and d["phi"] < 1e-10, d
    for step, d in compare.field_differences(a_dir, b_dir, b).items():
        assert d["u"] < 1e-10 and d["phi"] < 1e-10, (step, d)


def test_refactorises_exactly_when_the_contact_set_changes(both_paths):
    a, b = both_paths[True][0], both_paths[False][0]
    fresh = b["timing"]["operations"]["factorisation"]["count"]
    kept = a["timing"]["operations"]["factorisation"]["count"]
    iterations = sum(s["newton_iterations"] for s in a["steps"])
    # without reuse: one factorisation per Newton iteration (+ the first one)
    assert fresh == iterations + 1
    # with reuse: the contact set changed during the run, so more than the
    # first factorisation, but far fewer than one per iteration
    assert 1 < kept < iterations
    assert a["timing"]["operations"]["reused_factorisation"] == iterations + 1 - kept
    changed = [s for s in a["steps"] if s["factorisations"] > 0]
    assert changed, "no step refactorised"
