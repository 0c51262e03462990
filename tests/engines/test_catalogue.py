"""The catalogue of terms (forms/terms.py), in process: the terms the Python
model instantiates piece by piece sum to the reference engine's whole
residual and Jacobian (two independent assemblies of the same catalogue),
the Jacobian terms are classified as the core needs them (only the contact
term depends on the state), and a `where` term lands only on the boundaries
that set its key."""

import json

import numpy as np
import pytest
from conftest import ROOT
from dolfinx.fem import petsc as fem_petsc
from mpi4py import MPI
from petsc4py import PETSc

from piezocontact import cpp, model

SQUARE = json.loads((ROOT / "demos" / "square.json").read_text())


def jit_model(cfg):
    text = json.dumps(json.loads(cpp.configure(json.dumps(cfg), [], "config")))
    named = cpp.build_mesh(text, MPI.COMM_WORLD, None, "config")
    m = model.JitModel(named, cpp.model_spec(text))
    cpp.set_constants(text, m.cpp_model())
    return m


def random_state(m, seed):
    rng = np.random.default_rng(seed)
    for f, scale in ((m.x, 1e-9), (m.x_prev, 1e-9)):
        f.x.array[:] = scale * rng.standard_normal(f.x.array.size)
        f.x.scatter_forward()


def assembled(forms):
    out = None
    for f in forms:
        v = fem_petsc.assemble_vector(f)
        v.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        out = v if out is None else out + v
    return out.array


def matrix(forms):
    total = None
    for f in forms:
        A = fem_petsc.assemble_matrix(f)
        A.assemble()
        total = A if total is None else total + A
    return total


CASES = {
    "example 1": SQUARE,
    "a spring bed and a clamp": {
        **SQUARE, "boundaries": {
            "left": {"displacement": [0.0, 0.0], "potential": 0.0},
            "right": {"spring": {"normal": 3e11, "tangential": 1e11}},
            "top": {"traction": [1.0, -10.0], "surface_charge": 1e-4},
            "bottom": {"contact": True}}},
}


@pytest.mark.parametrize("case", CASES)
def test_pieces_sum_to_the_whole_residual_and_jacobian(case):
    m = jit_model({**CASES[case], "mesh": {"type": "unit_square", "n": 6}})
    # a state pressing part of Gamma_C into the foundation, part not
    random_state(m, 1)
    m.x.x.array[:] += 1e-11 * np.sign(np.sin(np.arange(m.x.x.array.size)))
    r_pieces, r_whole = assembled(m.F), assembled([m.F_whole])
    assert np.abs(r_pieces).max() > 0
    assert np.abs(r_pieces - r_whole).max() <= 1e-12 * np.abs(r_whole).max()
    J_pieces, J_whole = matrix(m.J), matrix([m.J_whole])
    J_whole.axpy(-1.0, J_pieces)
    assert J_whole.norm() <= 1e-12 * J_pieces.norm()


def test_jacobian_terms_are_classified_and_where_terms_placed():
    cfg = CASES["a spring bed and a clamp"]
    m = jit_model({**cfg, "mesh": {"type": "unit_square", "n": 2}})
    # J: the region's, the spring's (on "right" only) and the contact's;
    # only the contact's changes with the state
    assert len(m.J) == 3 and len(m.J_state) == 1
    assert m.J_state[0] is m.J[-1]
    # F: region, the loads of 4 boundaries, the spring of 1, the contact
    assert len(m.F) == 1 + 4 + 1 + 1
    without = model.JitModel(m.named, cpp.model_spec(json.dumps(
        json.loads(cpp.configure(json.dumps({**SQUARE, "mesh": {"type": "unit_square", "n": 2}}),
                                 [], "config")))))
    assert len(without.J) == 2 and len(without.F) == 1 + 4 + 1
