"""Contact with rigid obstacles, by normal compliance and by Nitsche's
method (the Signorini limit), against what no one here wrote: Hertz's
solutions, and the paper's foundation as the special case of a plane.

Hertz (K. L. Johnson, Contact Mechanics, CUP 1985, sections 4.2 and 5.2):
a rigid indenter of radius R pressed with a force P on an elastic
half-space of modulus E* = E / (1 - nu^2) (plane strain), frictionless,
  cylinder (2D, P per unit length): a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a)
  sphere (axisymmetric, 3D):         a = (3 P R / (4 E*))^(1/3), p0 = 3 P / (2 pi a^2)
a the contact half-width (radius), p0 the peak pressure. The force P is
the run's; the half-space is a 40 mm block (meshes/hertz_block.py) whose
contact zone (a ~ 0.5 mm) is resolved by cells of 20 um, at degree 2."""

import json
import math

import numpy as np
import pytest
from conftest import ENGINES, ROOT, SQUARE, run_solver

E, NU = 100e9, 0.3
E_STAR = E / (1 - NU ** 2)
R = 20e-3                    # m: the indenter's radius


def isotropic():
    """An elastic isotropic material with the piezoelectric coupling off (a
    permittivity keeps the electric equation regular)."""
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    B = np.zeros((6, 6))
    B[:3, :3] = lam
    B[:3, :3] += 2 * mu * np.eye(3)
    B[3:, 3:] = mu * np.eye(3)
    return {"elastic": B.tolist(), "relaxation_time": 1e-9,  # s: A = 1e-9 B, viscosity negligible
            "piezoelectric": np.zeros((3, 6)).tolist(),
            "permittivity": (1e-9 * np.eye(3)).tolist()}


def hertz_config(formulation, depth, contact, size=0.02e-3, steps=1):
    """The rigid cylinder (plane strain) or sphere (axisymmetric) of radius
    R touching the block's top at the origin, moved down by `depth`."""
    block = {"obstacle": {"sphere": {"center": [0.0, R], "radius": R},
                          "displacement": [0.0, -depth]}, **contact}
    return {
        "mesh": {"type": "gmsh", "geometry": str(ROOT / "meshes" / "hertz_block.py"),
                 "size": size},
        "formulation": formulation,
        "elements": {"degree": 2},
        "material": isotropic(),
        "boundaries": {
            "axis": {"displacement": [0.0, None]},
            "bottom": {"displacement": [0.0, 0.0], "potential": 0.0},
            "side": {},
            "top": {"contact": block},
        },
        "time": {"T": 1.0, "steps": steps},
        "probes": [[0.0, 0.0]],
        "output": {"xdmf": False},
    }


def hertz(formulation, P):
    """(a, p0) of Hertz for the force P (per unit length in 2D)."""
    if formulation == "axisymmetric":
        a = (3 * P * R / (4 * E_STAR)) ** (1 / 3)
        return a, 3 * P / (2 * math.pi * a ** 2)
    a = math.sqrt(4 * P * R / (math.pi * E_STAR))
    return a, 2 * P / (math.pi * a)


def measured(formulation, summary):
    """(P, a, p0) of the last step: the force on the whole indenter (minus
    the indenter's force on the body, along y), the contact half-width
    (radius) and the peak pressure."""
    c = summary["steps"][-1]["contacts"]["top"]
    if formulation == "axisymmetric":  # per revolution; contact_length is the disc's area
        return -c["force"][1], math.sqrt(c["contact_length"] / math.pi), c["max_pressure"]
    # the half model of plane strain: twice its force, its contact length is a
    return -2 * c["force"][1], c["contact_length"], c["max_pressure"]


NITSCHE = {"method": "nitsche"}


@pytest.mark.parametrize("formulation, depth", [("plane_strain", 28e-6),
                                                ("axisymmetric", 12.5e-6)])
def test_hertz_nitsche(tmp_path, formulation, depth):
    """Hertz at 40 um under the indenter (a / h ~ 7 to 11): a and p0 within
    1 % (measured +0.45/-0.33 % and -0.82/-0.08 %; the tables of
    benchmarks/hertz.py refine to 10 um)."""
    cfg = tmp_path / "hertz.json"
    cfg.write_text(json.dumps(hertz_config(formulation, depth, NITSCHE, size=0.04e-3)))
    summary, _ = run_solver("cpp", tmp_path / "out", config=cfg)
    P, a, p0 = measured(formulation, summary)
    a_h, p0_h = hertz(formulation, P)
    print(f"{formulation}: P = {P:.6g}, a = {a:.6g} (Hertz {a_h:.6g}, {a / a_h - 1:+.2%}), "
          f"p0 = {p0:.6g} (Hertz {p0_h:.6g}, {p0 / p0_h - 1:+.2%})")
    assert a / R < 0.05  # Hertz's small contact
    assert abs(a / a_h - 1) < 0.01 and abs(p0 / p0_h - 1) < 0.01


def plane_foundation(cfg):
    """Example 1 with its foundation (gap 0 below y = 0) as an obstacle plane."""
    cfg = dict(cfg)
    cfg["contact"] = {"c_p": cfg["contact"]["c_p"],
                      "obstacle": {"plane": {"point": [0.0, -cfg["contact"]["gap"]],
                                             "normal": [0.0, 1.0]}}}
    return cfg


def test_plane_parallel_to_the_boundary_is_the_foundation(tmp_path):
    """The obstacle plane y = -g reproduces the paper's foundation offset by
    g: the same steps, probes and contact forces."""
    base = json.loads(SQUARE.read_text())
    base["mesh"]["n"], base["time"]["steps"] = 16, 8
    base["output"] = {"xdmf": False}
    runs = {}
    for name, cfg in (("foundation", base), ("plane", plane_foundation(base))):
        path = tmp_path / f"{name}.json"
        path.write_text(json.dumps(cfg))
        runs[name], _ = run_solver("cpp", tmp_path / name, config=path)
    for a, b in zip(runs["foundation"]["steps"], runs["plane"]["steps"]):
        assert a["newton_iterations"] == b["newton_iterations"]
        assert a["probes"] == b["probes"]
        assert a["contact_force"] == b["contact_force"]
        assert a["max_penetration"] == pytest.approx(b["max_penetration"], abs=1e-20)


def relative_difference(a, b):
    """Largest difference of the step quantities of two summaries, each
    relative to that quantity's size over the run."""
    worst = 0.0
    for key in ("probes", "contacts"):
        def values(summary):
            return np.array([v for s in summary["steps"] for v in _numbers(s[key])])
        va, vb = values(a), values(b)
        scale = np.abs(va).max()
        worst = max(worst, np.abs(va - vb).max() / scale if scale else 0.0)
    return worst


def _numbers(node):
    if isinstance(node, dict):
        return [v for k in sorted(node) for v in _numbers(node[k])]
    if isinstance(node, list):
        return [v for item in node for v in _numbers(item)]
    return [float(node)] if isinstance(node, (int, float)) and not isinstance(node, bool) else []


@pytest.mark.parametrize("contact", [NITSCHE, {"c_p": 1e16}], ids=["nitsche", "penalty"])
@pytest.mark.parametrize("formulation, depth", [("plane_strain", 28e-6),
                                                ("axisymmetric", 12.5e-6)])
def test_engines_agree_with_obstacles(tmp_path, formulation, depth, contact):
    """The three engines on a coarse Hertz run in two steps, to 1e-9 of
    each quantity's size (Newton stops on the same error bound)."""
    cfg = tmp_path / "hertz.json"
    cfg.write_text(json.dumps(hertz_config(formulation, depth, contact, size=0.1e-3, steps=2)))
    runs = {e: run_solver(e, tmp_path / e, config=cfg)[0] for e in ENGINES}
    for e in ENGINES[1:]:
        assert relative_difference(runs["cpp"], runs[e]) < 1e-9, e


def squeezed_config(contact, depth):
    """The unit square between two obstacle planes, y = 0 below and y = 1
    above, the upper one moved down by `depth`, each its own contact block;
    x = 0 on rollers, x = 1 free: uniaxial stress sigma_yy in plane strain."""
    def block(point, normal, moved=None):
        obstacle = {"plane": {"point": point, "normal": normal}}
        if moved is not None:
            obstacle["displacement"] = {"value": [0.0, -moved], "history": {"ramp": 1.0}}
        return {"obstacle": obstacle, **contact}
    return {
        "mesh": {"type": "unit_square", "n": 4},
        "material": {**isotropic(), "relaxation_time": 1e-12},
        "boundaries": {
            "left": {"displacement": [0.0, None]},
            "bottom": {"contact": block([0.0, 0.0], [0.0, 1.0]), "potential": 0.0},
            "top": {"contact": block([0.0, 1.0], [0.0, -1.0], depth)},
            "right": {},
        },
        "time": {"T": 1.0, "steps": 2},
        "probes": [[1.0, 1.0], [0.0, 0.0]],
        "output": {"xdmf": False},
    }


@pytest.mark.parametrize("contact, below", [(NITSCHE, "plane"), ({"c_p": 1e12}, "plane"),
                                            (NITSCHE, "foundation"), ({"c_p": 1e12}, "foundation")])
def test_a_block_squeezed_between_two_obstacles(tmp_path, contact, below):
    """Each boundary its own obstacle; exact: the uniform stress
    sigma_yy = -E* (delta - 2 r) of a unit height, r = 0 for Nitsche (the
    Signorini limit: no penetration at all) and r = E* delta / (c_p + 2 E*)
    for the penalty; P1 holds the linear fields exactly. Below, the plane
    y = 0 or the paper's foundation in a block of its own (gap 0: the same
    surface, its penetration measured along the facets' normals)."""
    depth = 1e-3
    cfg = tmp_path / "squeezed.json"
    squeezed = squeezed_config(contact, depth)
    if below == "foundation":
        squeezed["boundaries"]["bottom"]["contact"] = {"gap": 0.0, **contact}
    cfg.write_text(json.dumps(squeezed))
    summary, _ = run_solver("cpp", tmp_path / "out", config=cfg)
    for step in summary["steps"]:
        delta = depth * step["t"]
        r = 0.0 if contact is NITSCHE else E_STAR * delta / (contact["c_p"] + 2 * E_STAR)
        stress = E_STAR * (delta - 2 * r)
        c = step["contacts"]
        assert c["bottom"]["force"] == pytest.approx([0.0, stress], abs=1e-9 * stress)
        assert c["top"]["force"] == pytest.approx([0.0, -stress], abs=1e-9 * stress)
        for name in ("bottom", "top"):
            assert c[name]["max_penetration"] == pytest.approx(r, abs=1e-9 * delta)
            assert c[name]["max_pressure"] == pytest.approx(stress, rel=1e-9)
            assert c[name]["contact_length"] == pytest.approx(1.0, rel=1e-12)
        top_corner = step["probes"][0]["u"]
        assert top_corner[1] == pytest.approx(-(delta - r), abs=1e-9 * delta)


def hertz_3d_config(msh, depth, contact, steps=1):
    """The rigid sphere of radius R on a quarter of a 20 mm block
    (meshes/hertz_quarter_msh.py), the symmetry planes on rollers."""
    block = {"obstacle": {"sphere": {"center": [0.0, R, 0.0], "radius": R},
                          "displacement": {"value": [0.0, -depth, 0.0],
                                           "history": {"ramp": 1.0}}}, **contact}
    return {
        "mesh": {"type": "msh", "path": str(msh)},
        "elements": {"degree": 2},
        "material": isotropic(),
        "boundaries": {
            "sym_x": {"displacement": [0.0, None, None]},
            "sym_z": {"displacement": [None, None, 0.0]},
            "bottom": {"displacement": [0.0, 0.0, 0.0], "potential": 0.0},
            "sides": {},
            "top": {"contact": block},
        },
        "time": {"T": 1.0, "steps": steps},
        "probes": [[0.0, 0.0, 0.0]],
        "output": {"xdmf": False, "nodal": "none"},
    }

@pytest.mark.slow  # 100 s: a campaign (Debian 12)
def test_hertz_sphere_in_3d(tmp_path):
    """The sphere on a quarter model in 3D, Nitsche at P2, driven in 4 steps:
    a and p0 against Hertz for each step's force, and the force against
    the depth: P ~ delta^(3/2), the exponent from the last two steps (the
    block is 20 mm deep on a rigid base, not a half-space: measured 1.514)."""
    import subprocess
    msh = tmp_path / "quarter.msh"
    subprocess.run(["/usr/bin/python3", str(ROOT / "meshes" / "hertz_quarter_msh.py"), "--size",
                    "50e-6", "--output", str(msh)], check=True, capture_output=True)
    depth = 12.5e-6
    cfg = tmp_path / "hertz3d.json"
    cfg.write_text(json.dumps(hertz_3d_config(msh, depth, NITSCHE, steps=4)))
    summary, _ = run_solver("cpp", tmp_path / "out", config=cfg)
    forces = []
    for step in summary["steps"]:
        c = step["contacts"]["top"]
        P, a, p0 = -4 * c["force"][1], math.sqrt(4 * c["contact_area"] / math.pi), c["max_pressure"]
        a_h, p0_h = hertz("axisymmetric", P)
        print(f"t = {step['t']}: P = {P:.6g}, a = {a:.6g} ({a / a_h - 1:+.2%}), "
              f"p0 = {p0:.6g} ({p0 / p0_h - 1:+.2%})")
        forces.append(P)
    assert abs(a / a_h - 1) < 0.01 and abs(p0 / p0_h - 1) < 0.01  # the last step's
    exponent = math.log(forces[-1] / forces[-2]) / math.log(4 / 3)
    print(f"P ~ delta^{exponent:.4f}")
    assert abs(exponent - 1.5) < 0.03


# PZT-5H as config/materials.json gives it (c66 = (c11 - c12) / 2: transversely isotropic)
EPS0 = 8.854e-12
PZT5H = dict(c11=126e9, c12=79.5e9, c13=84.1e9, c33=117e9, c44=23.0e9, c66=(126e9 - 79.5e9) / 2,
             e31=-6.5, e33=23.3, e15=17.0, k11=1700 * EPS0, k33=1470 * EPS0)


@pytest.mark.parametrize("surface", ["grounded", "charge-free"])
def test_piezoelectric_indentation(tmp_path, surface):
    """A rigid sphere (R = 20 mm) on poled PZT-5H (the 40 mm block, poled
    into the body), Nitsche, P2, against the transversely isotropic
    piezoelectric half-space (tests/verification/piezo_half_space.py: the
    surface Green's function of the half-space and the Hertz-type contact
    solution, derived here by the route of Giannakopoulos & Suresh 1999,
    Chen & Ding 1999 and Karapetian, Kachanov & Kalinin; its elastic limit
    checked against Delafargue & Ulm 2004). Grounded surface (a conducting
    indenter, or an electrode on the surface at 0 V): P = 4 C1* a^3 / (3 R);
    charge-free surface (an insulating indenter): P = 4 E_ins a^3 / (3 R)
    and the potential phi(0) = (C3*/C4*) a^2 / R induced under it."""
    from piezo_half_space import _ti, sphere
    cfg = hertz_config("axisymmetric", 12.5e-6, NITSCHE)
    cfg["material"] = {"preset": "PZT-5H", "poling": [0, -1], "relaxation_time": 1e-9}
    if surface == "grounded":
        cfg["boundaries"]["top"]["potential"] = 0.0
    path = tmp_path / "indent.json"
    path.write_text(json.dumps(cfg))
    summary, _ = run_solver("cpp", tmp_path / "out", config=path)
    P, a, p0 = measured("axisymmetric", summary)
    exact = sphere(*_ti(*PZT5H.values()), R, a)["conducting" if surface == "grounded"
                                                else "insulating"]
    print(f"{surface}: P = {P:.6g} ({P / exact['P'] - 1:+.2%}), a = {a:.6g}, "
          f"p0 = {p0:.6g} ({p0 / exact['p0'] - 1:+.2%})")
    assert abs(P / exact["P"] - 1) < 0.01 and abs(p0 / exact["p0"] - 1) < 0.01
    if surface == "charge-free":
        phi = summary["steps"][-1]["probes"][0]["phi"]
        print(f"phi(0) = {phi:.6g} ({phi / exact['phi_center'] - 1:+.2%})")
        assert abs(phi / exact["phi_center"] - 1) < 0.02


@pytest.mark.parametrize("engine", ["cpp", "reference"])
def test_an_obstacle_given_in_ufl(tmp_path, engine):
    """From Python, the signed distance of any obstacle as a UFL expression
    of x and t (the data hook "boundaries.NAME.contact.obstacle"): the
    squeezed block's upper plane given so, moving as the config's ramp does,
    gives the config's answer to round-off; a boundary without an obstacle
    in the config is refused."""
    import piezocontact
    import ufl
    depth = 1e-3
    cfg = squeezed_config(NITSCHE, depth)
    by_config = piezocontact.solve(cfg, tmp_path / "config", engine=engine, progress=False)

    def upper_plane(x, t):  # y = 1 - depth t, the obstacle above it
        return (1 - depth * ufl.min_value(t, 1)) - x[1]
    by_ufl = piezocontact.solve(cfg, tmp_path / "ufl", engine=engine, progress=False,
                                data={"boundaries.top.contact.obstacle": upper_plane})
    for a, b in zip(by_config["steps"], by_ufl["steps"]):
        for name in ("bottom", "top"):
            assert b["contacts"][name]["force"] == pytest.approx(
                a["contacts"][name]["force"], abs=1e-12 * abs(a["contacts"][name]["force"][1]))
        assert b["probes"][0]["u"] == pytest.approx(a["probes"][0]["u"], abs=1e-15)
    with pytest.raises(ValueError, match="the boundary has no obstacle in the config"):
        piezocontact.solve(cfg, tmp_path / "bad", engine=engine, progress=False,
                           data={"boundaries.left.contact.obstacle": upper_plane})


@pytest.mark.parametrize("obstacle, nearest", [
    ({"cylinder": {"point": [0.5, 3.0, -7.0], "axis": [0.0, 0.0, 2.0], "radius": 1.0}}, 1.0),
    ({"sphere": {"center": [0.5, 3.5, 0.5], "radius": 1.5}}, 1.0),
    ({"plane": {"point": [0.0, 1.25, 0.0], "normal": [0.0, -3.0, 0.0]}}, 0.25)])
def test_obstacle_geometry_in_3d(tmp_path, obstacle, nearest):
    """Each obstacle kind above the unit cube's top (y = 1), out of reach:
    the largest penetration is minus the distance of the nearest node
    (x = z = 0.5 on the top for the cylinder along z through (0.5, 3), R = 1,
    and the sphere centred at (0.5, 3.5, 0.5), R = 1.5; the plane y = 1.25),
    with the axis and the normal given at any length; no force."""
    cfg = {"mesh": {"type": "box", "n": [2, 2, 2], "size": [1.0, 1.0, 1.0]},
           "material": {"preset": "PZT-5H", "poling": [0, 1, 0]},
           "boundaries": {"bottom": {"displacement": [0.0, 0.0, 0.0], "potential": 0.0},
                          "top": {"contact": {"obstacle": obstacle, "c_p": 1e12}}},
           "time": {"T": 1.0, "steps": 1}, "output": {"xdmf": False}}
    path = tmp_path / "cube.json"
    path.write_text(json.dumps(cfg))
    summary, _ = run_solver("cpp", tmp_path / "out", config=path)
    top = summary["steps"][-1]["contacts"]["top"]
    assert top["max_penetration"] == pytest.approx(-nearest, abs=1e-14)
    assert top["force"] == [0.0, 0.0, 0.0] and top["contact_area"] == 0.0


def test_an_obstacle_moved_by_expressions(tmp_path):
    """The squeezed block's upper plane moved by expressions of t instead of
    a ramp: the same steps to round-off."""
    runs = {}
    for name, moved in (("ramp", None), ("expression", ["0", "-1e-3*t"])):
        cfg = squeezed_config(NITSCHE, 1e-3)
        if moved:
            cfg["boundaries"]["top"]["contact"]["obstacle"]["displacement"] = moved
        path = tmp_path / f"{name}.json"
        path.write_text(json.dumps(cfg))
        runs[name], _ = run_solver("cpp", tmp_path / name, config=path)
    for a, b in zip(runs["ramp"]["steps"], runs["expression"]["steps"]):
        assert b["contacts"]["top"]["force"] == pytest.approx(a["contacts"]["top"]["force"],
                                                              rel=1e-12, abs=1e-3)
