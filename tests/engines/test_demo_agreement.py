"""Every shipped config (demos/*.json) on the three engines, each at a small
size: the executable and the C++ loop from Python agree to round-off, the
reference engine (its own Newton and test) within 1e-9 of each quantity's
run-wide size and 1e-8 value by value (floored at 1e-3 of that size), on
every probe value, force, reaction, penetration and electrode quantity of
every step. Both loops stop Newton on a bound of the error of the answer
(docs/verification.md), so this holds by construction, not by luck."""


import pytest
from conftest import ROOT, run_solver
from piezocontact import compare

OF_SIZE, BY_VALUE = 1e-9, 1e-8
SMALL = {  # the smallest honest size of each: every feature it has still at work
    "square.json": ["mesh.n=8", "time.steps=8"],
    "contactor.json": ["mesh.size=0.2", "time.steps=10"],
    "contactor_in_contact.json": ["mesh.size=0.2", "time.steps=10"],
    "sensor.json": ["mesh.size=0.2", "time.T=2", "time.steps=20"],
    "unimorph.json": ["time.steps=4"],
    "bilayer.json": ["time.steps=4"],
    "slab.json": ["mesh.n=[4,4,1]", "time.steps=4"],
    "manufactured.json": ["mesh.n=4", "time.steps=4"],
    "manufactured_3d.json": ["mesh.n=[2,2,2]", "time.steps=2"],
    "disc.json": ["mesh.size=1e-3", "time.steps=4"],
    "plate.json": ["mesh.n=4", "time.steps=3"],
    "indentation.json": ["mesh.size=40e-6", "time.steps=3"],
    "transducer.json": ["mesh.size=1e-3"],  # modes (the analysis's own comparison)
}


# At degree 2 (the unimorph's own): examples 1 and 2, two regions with contact, 3D, a
# floating electrode (the list)
P2 = ["square.json", "contactor.json", "bilayer.json", "manufactured_3d.json", "sensor.json",
      "unimorph.json"]


def test_every_demo_config_is_covered():
    shipped = {p.name for p in (ROOT / "demos").glob("*.json")}
    assert shipped == set(SMALL)


@pytest.mark.parametrize("name,degree", [(n, 1) for n in sorted(SMALL)] + [(n, 2) for n in P2])
def test_engines_agree_on_demo_config(tmp_path, name, degree):
    overrides = SMALL[name] + ["output.xdmf=false", "output.nodal=none",
                               f"elements.degree={degree}"]
    runs = {engine: run_solver(engine, tmp_path / engine, overrides,
                               config=ROOT / "demos" / name)[0]
            for engine in ("cpp", "cpp-jit", "reference")}
    for engine, summary in runs.items():
        assert summary["status"] == "completed", engine
    same_loop = compare.agreement(runs["cpp"], runs["cpp-jit"])
    for quantity, (of_size, _) in same_loop.items():
        assert of_size <= 1e-12, (quantity, of_size)
    for quantity, (of_size, by_value) in compare.agreement(runs["cpp"],
                                                           runs["reference"]).items():
        assert of_size <= OF_SIZE and by_value <= BY_VALUE, (quantity, of_size, by_value)


def test_agreement_can_fail():
    """A 1e-8 change in one probe value of one step is seen."""
    summary = {"steps": [{"probes": [{"u": [1.0, 2.0], "phi": 3.0}], "contact_force": [0.0, 0.0],
                          "max_penetration": None, "support_force": 0.0}
                         for _ in range(3)]}
    import copy
    other = copy.deepcopy(summary)
    other["steps"][1]["probes"][0]["phi"] *= 1 + 1e-8
    of_size, by_value = compare.agreement(other, summary)["probes.phi"]
    assert of_size == pytest.approx(1e-8, rel=1e-6) and by_value == pytest.approx(1e-8, rel=1e-6)
