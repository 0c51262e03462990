"""The Figure-3 study's machinery: the transfer between nested meshes is
exact for P1, and the study's errors behave (a small study, finest 1/16)."""

import math
import subprocess
import sys

import pytest
import ufl
from conftest import ENV, ROOT
from dolfinx import fem
from piezocontact import compare

sys.path.insert(0, str(ROOT / "demos"))

STUDY = ROOT / "demos" / "convergence_study.py"


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("conv")
    subprocess.run(["/usr/bin/python3", str(STUDY), "--finest", "16", "--output", str(out)],
                   check=True, env=ENV, capture_output=True)
    return out


def h1_norm(v):
    return math.sqrt(fem.assemble_scalar(fem.form(
        (ufl.inner(v, v) + ufl.inner(ufl.grad(v), ufl.grad(v))) * ufl.dx)))


def test_transfer_between_nested_meshes_is_exact(study):
    """A P1 function on 1/4 is P1 on 1/16: its H1 norm is kept, and going
    through 1/8 gives the same function as going directly."""
    from convergence_study import Level, Transfer, h1_error
    level = {n: Level(study / f"n{n}", compare.load_summary(study / f"n{n}"))
             for n in (4, 8, 16)}
    direct = Transfer(level[4], level[16])
    first, second = Transfer(level[4], level[8]), Transfer(level[8], level[16])
    for name in ("u", "phi"):
        f = level[4].field(4, name)
        g = direct(f, name)
        assert h1_norm(g) == pytest.approx(h1_norm(f), rel=1e-12)
        assert h1_error(g, second(first(f, name), name)) <= 1e-12 * h1_norm(g)


def test_errors_decrease_with_h_and_k(study):
    first_table = (study / "table.md").read_text().split("Where the error lives")[0]
    rows = [line.split("|") for line in first_table.splitlines() if line.startswith("| 1/")]
    errors = [float(r[3]) for r in rows]
    successive = [float(r[9]) for r in rows]
    assert all(b < a for a, b in zip(errors, errors[1:])), errors
    assert all(b < a for a, b in zip(successive, successive[1:])), successive
    # the last level's error against the reference is its difference to it
    assert errors[-1] == pytest.approx(successive[-1], rel=1e-12)
    assert (study / "figure3.png").stat().st_size > 10_000


def test_regions_partition_the_error(study):
    """The corner discs and the rest split the domain: their squared H1
    errors add up to the whole one (so the localisation misses nothing)."""
    from convergence_study import Level, Transfer, h1_error, regional_errors
    level = {n: Level(study / f"n{n}", compare.load_summary(study / f"n{n}")) for n in (4, 8)}
    transfer = Transfer(level[4], level[8])
    parts = regional_errors(level[4], level[8], transfer)
    assert len(parts) == 5
    for name in ("u", "phi"):
        whole = h1_error(transfer(level[4].field(4, name), name), level[8].field(8, name))
        assert math.fsum(p[name] ** 2 for p in parts.values()) == pytest.approx(whole ** 2,
                                                                               rel=1e-12)
        assert min(p[name] for p in parts.values()) > 0
