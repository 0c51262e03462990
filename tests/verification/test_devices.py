"""Real devices (issue 13): 3D, presets with a poling direction, regions,
own meshes, roller supports. Checked against exact discrete solutions, a
rotated copy of the same problem, the plane-strain limit, manufactured
solutions in 3D, and between the three engines."""

import json
import math
import sys

import numpy as np
import pytest
from conftest import ROOT, resume, run_solver, xdmf_times

sys.path.insert(0, str(ROOT / "forms"))
from manufactured import PHI0, U0  # noqa: E402

SLAB = ROOT / "demos" / "slab.json"
BILAYER = ROOT / "demos" / "bilayer.json"
SQUARE = ROOT / "demos" / "square.json"
MMS3 = ROOT / "demos" / "manufactured_3d.json"
QUIET = ["output.xdmf=false", "output.nodal=none"]


def write(path, cfg):
    path.write_text(json.dumps(cfg))
    return path


def relative(a, b):
    """Largest |a - b| relative to the largest |b|, over all entries."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def step_values(summary):
    """Per step: probe u and phi, contact force, reactions (flattened)."""
    out = []
    for s in summary["steps"]:
        out.append((np.array([p["u"] for p in s["probes"]]), np.array([p["phi"] for p in s["probes"]]),
                    np.array(s["contact_force"]),
                    np.array([r for name in sorted(s["reactions"]) for r in s["reactions"][name]])))
    return out


@pytest.mark.parametrize("config,overrides", [
    (SLAB, ["time.steps=4", "mesh.n=[4,4,2]"]),
    (BILAYER, ["time.steps=4"])], ids=["3d-slab", "2d-regions"])
@pytest.mark.parametrize("other", ["cpp-jit", "reference"])
def test_engines_agree_in_3d_and_with_regions(tmp_path, config, overrides, other):
    """The executable, the C++ loop from Python and the reference engine:
    probes, contact force and reactions at every step to 1e-8 (measured
    1e-15 between the two C++ front doors, 1e-14 against the reference)."""
    a = run_solver("cpp", tmp_path / "cpp", overrides + QUIET, config=config)[0]
    b = run_solver(other, tmp_path / other, overrides + QUIET, config=config)[0]
    assert len(a["steps"]) == len(b["steps"]) == 4
    for x, y in zip(step_values(a), step_values(b)):
        for qa, qb in zip(x, y):
            assert relative(qa, qb) < 1e-8
    assert abs(a["steps"][-1]["contact_force"][1]) > 1.0  # the foundation carries the load


def test_zno_preset_poled_along_y_is_the_papers_material(tmp_path):
    """ZnO-paper poled along y, reduced to plane strain, is Tables 1-2 of the
    paper to the last digit (the numbers of square.json), and the run is the
    same bit for bit."""
    cfg = json.loads(SQUARE.read_text())
    explicit = cfg["material"]
    cfg["material"] = {"preset": "ZnO-paper", "poling": [0, 1]}
    preset = write(tmp_path / "preset.json", cfg)
    overrides = ["mesh.n=8", "time.steps=4"] + QUIET
    a = run_solver("cpp", tmp_path / "a", overrides, config=preset)[0]
    b = run_solver("cpp", tmp_path / "b", overrides)[0]
    resolved = a["config"]["material"]
    for key in ("elastic", "viscosity", "piezoelectric", "permittivity"):
        assert resolved[key] == explicit[key], key
    assert resolved["resolved_from"] == {"preset": "ZnO-paper", "poling": [0.0, 1.0],
                                         "relaxation_time": 0.1}
    assert [s["probes"] for s in a["steps"]] == [s["probes"] for s in b["steps"]]


# --- Uniform fields: P1 holds them exactly ---------------------------------

SIGMA0 = 1e6  # Pa: uniaxial compression along y


def uniform_block(tmp_path, axis, preset="PZT-5H"):
    """The unit cube on rollers (x = 0, y = 0, z = 0 faces), compressed along
    y by a traction on its top, grounded on the face normal to the poling
    axis, every other face charge-free: a uniform strain and field."""
    poling = [0.0, 0.0, 0.0]
    poling[axis] = 1.0
    rollers = {"left": 0, "bottom": 1, "back": 2}
    boundaries = {}
    for name, a in rollers.items():
        d = [None, None, None]
        d[a] = 0.0
        boundaries[name] = {"displacement": d}
    grounded = ["left", "bottom", "back"][axis]
    boundaries[grounded]["potential"] = 0.0
    boundaries["top"] = {"traction": [0.0, -SIGMA0, 0.0]}
    cfg = {"mesh": {"type": "box", "n": [2, 2, 2], "size": [1.0, 1.0, 1.0]},
           "material": {"preset": preset, "poling": poling},
           "contact": {"c_p": 0.0, "gap": 0.0},
           "boundaries": boundaries,
           "time": {"T": 0.5, "steps": 5},
           "probes": [[1.0, 1.0, 1.0], [0.5, 0.25, 0.75]]}
    return write(tmp_path / f"block_{axis}.json", cfg)


def creep_recurrence(material, k, steps, axis, factor=lambda t: 1.0):
    """Backward Euler on the uniform state: strains eps = (e_xx, e_yy, e_zz)
    (no shear: rollers), D = e eps - beta grad(phi) = 0 (charge-free faces),
    so grad(phi) = beta^-1 e eps and the normal stresses
    (B + e^T beta^-1 e) eps + A (eps - eps_prev)/k = (0, -SIGMA0 factor(t), 0)."""
    B, A = np.array(material["elastic"]), np.array(material["viscosity"])
    e, beta = np.array(material["piezoelectric"]), np.array(material["permittivity"])
    normal = [0, 1, 2]
    stiff = (B + e.T @ np.linalg.solve(beta, e))[np.ix_(normal, normal)]
    visc = A[np.ix_(normal, normal)] / k
    eps, out = np.zeros(3), []
    for n in range(1, steps + 1):
        load = np.array([0.0, -SIGMA0 * factor(n * k), 0.0])
        eps = np.linalg.solve(stiff + visc, load + visc @ eps)
        strain = np.zeros(6)
        strain[:3] = eps
        out.append((eps, np.linalg.solve(beta, e @ strain)))
    return out


@pytest.mark.parametrize("axis", [0, 1, 2], ids=["poled-x", "poled-y", "poled-z"])
def test_uniform_fields_are_reproduced_exactly_in_3d(tmp_path, axis):
    """u = (e_xx x, e_yy y, e_zz z), phi = grad(phi).x: the discrete solution
    at two probes equals the recurrence of the three strains at every step
    to 1e-10 (round-off of the solve; any discretisation error would be
    O(1)). Only poling along a mesh axis keeps the shears at zero."""
    s = run_solver("cpp", tmp_path / "out", QUIET, config=uniform_block(tmp_path, axis))[0]
    exact = creep_recurrence(s["config"]["material"], 0.1, 5, axis)
    for step, (eps, grad_phi) in zip(s["steps"], exact):
        for probe in step["probes"]:
            x = np.array(probe["point"])
            assert relative(probe["u"], eps * x) < 1e-10
            assert probe["phi"] == pytest.approx(grad_phi @ x, rel=1e-10)
        # the support carries the whole load (unit area)
        assert abs(step["reactions"]["bottom"][1]) == pytest.approx(SIGMA0, rel=1e-10)
    # the field is along the poling axis, and the strain creeps
    assert abs(exact[-1][1][axis]) > 1e3 * np.delete(abs(exact[-1][1]), axis).max(initial=1e-300)
    assert abs(exact[-1][0][1]) > abs(exact[0][0][1])


# --- Rotating the whole problem rotates the solution ---------------------------

def bunge(R):
    """Bunge angles (degrees) of a rotation, R = Rz(phi1) Rx(Phi) Rz(phi2)."""
    Phi = math.acos(max(-1.0, min(1.0, R[2, 2])))
    return [math.degrees(math.atan2(R[0, 2], -R[1, 2])), math.degrees(Phi),
            math.degrees(math.atan2(R[2, 0], R[2, 1]))]


def euler_matrix(angles):
    a, b, c = (math.radians(x) for x in angles)

    def rz(t):
        return np.array([[math.cos(t), -math.sin(t), 0], [math.sin(t), math.cos(t), 0], [0, 0, 1]])

    def rx(t):
        return np.array([[1, 0, 0], [0, math.cos(t), -math.sin(t)], [0, math.sin(t), math.cos(t)]])
    return rz(a) @ rx(b) @ rz(c)


def box_mesh_file(path, Q):
    """A box mesh [0,1] x [0,1] x [0,0.5] with its sides named, its vertices
    rotated by Q, as XDMF + sidecar (mesh.type xdmf)."""
    from dolfinx import io, mesh
    from mpi4py import MPI
    from piezocontact._compat import write_meshtags
    msh = mesh.create_box(MPI.COMM_SELF, [[0, 0, 0], [1, 1, 0.5]], [3, 3, 2],
                          mesh.CellType.tetrahedron)
    sides = {"left": (0, 0.0), "right": (0, 1.0), "bottom": (1, 0.0), "top": (1, 1.0)}
    facets, values = [], []
    for tag, (name, (a, c)) in enumerate(sorted(sides.items()), start=1):
        found = mesh.locate_entities_boundary(msh, 2, lambda x, a=a, c=c: np.isclose(x[a], c))
        facets.append(found)
        values.append(np.full(len(found), tag, dtype=np.int32))
    order = np.argsort(np.concatenate(facets))
    tags = mesh.meshtags(msh, 2, np.concatenate(facets)[order], np.concatenate(values)[order])
    msh.geometry.x[:] = msh.geometry.x @ Q.T
    msh.name, tags.name = "mesh", "facets"
    with io.XDMFFile(MPI.COMM_SELF, str(path), "w") as f:
        f.write_mesh(msh)
        write_meshtags(f, tags, msh)
    path.with_suffix(".boundaries.json").write_text(json.dumps(
        {"boundaries": {n: t for t, n in enumerate(sorted(sides), start=1)}}))


def test_rotating_the_problem_rotates_the_solution(tmp_path):
    """The same device twice: once as it is, once with its mesh, crystal
    orientation, loads and probes rotated by Q. P1 on a rotated mesh is the
    rotated discretisation, so u' = Q u and phi' = phi at the rotated probes,
    to round-off (1e-9): this checks the rotation of the preset tensors (a
    crystal not aligned with any axis) and every vector of the model."""
    Q = euler_matrix([30.0, 50.0, -20.0])
    R = euler_matrix([10.0, 70.0, 40.0])  # the crystal in the first copy
    probes = np.array([[1.0, 1.0, 0.25], [1.0, 0.0, 0.5], [0.5, 0.0, 0.25]])
    traction = np.array([0.0, -10.0, 2.0])
    runs = []
    for name, rotation in (("as_is", np.eye(3)), ("rotated", Q)):
        box_mesh_file(tmp_path / f"{name}.xdmf", rotation)
        cfg = {"mesh": {"type": "xdmf", "path": f"{name}.xdmf"},
               "material": {"preset": "PZT-4", "euler": bunge(rotation @ R)},
               "contact": {"c_p": 1e12, "gap": 0.0},
               "boundaries": {"left": {"displacement": [0.0, 0.0, 0.0], "potential": 0.0},
                              "top": {"traction": list(rotation @ traction)},
                              "bottom": {"contact": True}},
               "time": {"T": 1.0, "steps": 3},
               "probes": (probes @ rotation.T).tolist()}
        config = write(tmp_path / f"{name}.json", cfg)
        runs.append(run_solver("cpp", tmp_path / name, QUIET, config=config)[0])
    for a, b in zip(runs[0]["steps"], runs[1]["steps"]):
        u = np.array([p["u"] for p in a["probes"]])
        u_rot = np.array([p["u"] for p in b["probes"]])
        assert relative(u_rot, u @ Q.T) < 1e-9
        assert relative([p["phi"] for p in b["probes"]], [p["phi"] for p in a["probes"]]) < 1e-9
        assert relative(b["contact_force"], Q @ np.array(a["contact_force"])) < 1e-9
    assert np.linalg.norm(runs[0]["steps"][-1]["contact_force"]) > 1.0  # in contact


# --- The plane-strain limit ------------------------------------------------------

def test_slab_on_rollers_approaches_the_plane_strain_solution(tmp_path):
    """Example 1 extruded (thickness 0.25, rollers on both z-faces) against
    the 2D run on the same n: the difference of the probes shrinks with h
    (measured 1.9e-3, 6.2e-4, 2.1e-4 in u for n = 4, 8, 16; table in
    docs/verification.md), at least 1.5x per halving."""
    diffs = []
    for n in (4, 8, 16):
        common = ["time.steps=4"] + QUIET
        a = run_solver("cpp", tmp_path / f"3d{n}", common + [f"mesh.n=[{n},{n},1]"], config=SLAB)[0]
        b = run_solver("cpp", tmp_path / f"2d{n}", common + [f"mesh.n={n}"])[0]
        ua = np.array([p["u"][:2] for p in a["steps"][-1]["probes"]])
        ub = np.array([p["u"] for p in b["steps"][-1]["probes"]])
        diffs.append(relative(ua, ub))
        # per unit thickness, the same contact force (N / 0.25 m vs N/m)
        assert a["steps"][-1]["contact_force"][1] / 0.25 == pytest.approx(
            b["steps"][-1]["contact_force"][1], rel=0.02)
    assert diffs[0] > 1.5 * diffs[1] > 1.5 ** 2 * diffs[2], diffs


# --- Manufactured solutions in 3D ------------------------------------------------

def mms3(tmp_path, name, space, time_, n, steps):
    overrides = [f"manufactured.space={space}", f"manufactured.time={time_}",
                 f"mesh.n=[{n},{n},{n}]", f"time.steps={steps}"] + QUIET
    return run_solver("cpp", tmp_path / name, overrides, config=MMS3)[0]


def errors(summary, name):
    return max(s["errors"][name] for s in summary["steps"])


def test_manufactured_linear_solution_is_exact_in_3d(tmp_path):
    """Linear in space and time, contact active: round-off (measured 2e-15
    relative to U0, PHI0)."""
    s = mms3(tmp_path, "lin", "linear", "linear", 4, 4)
    for name in ("u_L2", "u_H1", "phi_L2", "phi_H1"):
        assert errors(s, name) / (U0 if name.startswith("u") else PHI0) < 1e-12
    assert abs(s["steps"][-1]["contact_force"][1]) > 0.1


def test_manufactured_rates_in_3d(tmp_path):
    """h: smooth in space, linear in time, one step (no time error) on n = 4,
    8, 16: H1 rate 1 (measured 1.03, 1.00 at 8 -> 16), L2 rising to 2
    (1.39 -> 1.70 for u, 1.68 -> 1.85 for phi; at 16 -> 32, 1.89 and 1.95,
    measured once: 4 GB and 4 min of LU, not a CI test). k: linear in space,
    sin(pi t/2) in time, k = 1/4 .. 1/16: rate 1 (0.98)."""
    h = [mms3(tmp_path, f"h{n}", "smooth", "linear", n, 1) for n in (4, 8, 16)]
    for field in ("u", "phi"):
        l2 = [errors(s, f"{field}_L2") for s in h]
        h1 = [errors(s, f"{field}_H1") for s in h]
        r2 = [math.log2(a / b) for a, b in zip(l2, l2[1:])]
        r1 = [math.log2(a / b) for a, b in zip(h1, h1[1:])]
        assert 0.9 < r1[-1] < 1.2, (field, r1)
        assert r2[-1] > 1.6 and r2[-1] > r2[0], (field, r2)
    k = [mms3(tmp_path, f"k{m}", "linear", "smooth", 2, m) for m in (4, 8, 16)]
    for name in ("u_L2", "u_H1", "phi_L2", "phi_H1"):
        e = [errors(s, name) for s in k]
        assert 0.9 < math.log2(e[-2] / e[-1]) < 1.2, (name, e)


# --- MPI, resume and output in 3D ---------------------------------------------------

def test_3d_regions_under_mpi_resume_and_xdmf(tmp_path):
    """The 3D two-region unimorph (its .msh converted once, on rank 0):
    mpirun -n 2 gives the serial answers (1e-8); a run to T/2 extended to T
    on resume equals the straight run (1e-8: the checkpoint holds u_x, u_y,
    u_z, phi per node; the demo's degree is 2); the XDMF steps hold u, phi, D, the contact
    pressure and the six stress components."""
    base = ["time.steps=4", "time.T=0.2"]
    serial = run_solver("cpp", tmp_path / "serial", base, config=ROOT / "demos" / "unimorph.json")[0]
    mpi = run_solver("cpp", tmp_path / "mpi", base + QUIET, config=ROOT / "demos" / "unimorph.json",
                     np_=2)[0]
    for x, y in zip(step_values(serial), step_values(mpi)):
        for qa, qb in zip(x, y):
            assert relative(qb, qa) < 1e-8
    assert serial["steps"][-1]["contact_force"][2] > 0.1  # the tip presses on the foundation
    short = tmp_path / "short"
    run_solver("cpp", short, ["time.steps=2", "time.T=0.1"] + QUIET,
               config=ROOT / "demos" / "unimorph.json")
    extended, _ = resume("cpp", short, overrides=["time.T=0.2", "time.steps=4"])
    for x, y in zip(step_values(serial), step_values(extended)):
        for qa, qb in zip(x, y):
            assert relative(qb, qa) < 1e-8
    fields = {"u", "phi", "D", "contact_pressure"} | {f"stress_{c}" for c in
                                                      ("xx", "yy", "zz", "yz", "xz", "xy")}
    assert {name: len(t) for name, t in xdmf_times(tmp_path / "serial" / "solution.xdmf").items()} \
        == {name: 4 for name in fields}
