#!/usr/bin/python3
"""Every kind of bad input the engines must refuse, with (part of) the
message all three give. Used by tests/robustness/test_config.py; run it to regenerate
the table of messages in docs/errors.md from real runs of the executable:

    /usr/bin/python3 tests/bad_inputs.py --write docs/errors.md
"""

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SQUARE = ROOT / "demos" / "square.json"
CONTACTOR = ROOT / "demos" / "contactor.json"
MMS = ROOT / "demos" / "manufactured.json"
SLAB = ROOT / "demos" / "slab.json"
BILAYER = ROOT / "demos" / "bilayer.json"
DISC = ROOT / "demos" / "disc.json"
PLANE = '"plane":{"point":[0,0],"normal":[0,1]}'
UNUSED = "not used with a manufactured solution (its loads come from the exact solution)"

# name: (config, --set overrides, expected part of the message)
CASES = {
    "unknown key": (SQUARE, ["time.stpes=3"],
                    "time.stpes: unknown key (did you mean 'time.steps'?)"),
    "wrong type": (SQUARE, ["boundaries.top.traction=5"],
                   "boundaries.top.traction = 5: expected a list of 2 numbers"),
    "non-integer n": (SQUARE, ["mesh.n=4.5"], "mesh.n = 4.5: expected an integer"),
    "T <= 0": (SQUARE, ["time.T=-1"], "time.T = -1: must be > 0"),
    "steps < 1": (SQUARE, ["time.steps=0"], "time.steps = 0: must be >= 1"),
    "permittivity with the paper's sign": (
        SQUARE, ["material.permittivity=[[-7.37455e-11,0],[0,-7.8188e-11]]"],
        "material.permittivity = [[-7.37455e-11,0.0],[0.0,-7.8188e-11]]: not positive "
        "definite: permittivity must be positive definite (2.14c); the paper's Table 2 "
        "prints -beta, use +8.3 eps0 and +8.8 eps0"),
    "non-symmetric permittivity": (
        SQUARE, ["material.permittivity=[[7e-11,1e-12],[0,8e-11]]"],
        "material.permittivity = [[7e-11,1e-12],[0.0,8e-11]]: must be symmetric "
        "(entry [0][1] = 1e-12 but [1][0] = 0)"),
    "viscosity not positive definite": (
        SQUARE, ["material.viscosity=[[21e9,30e9,0],[30e9,21.1e9,0],[0,0,4.25e9]]"],
        "not positive definite: viscosity must be positive definite (2.11c)"),
    "c_p < 0": (SQUARE, ["contact.c_p=-1"], "contact.c_p = -1: must be >= 0"),
    "g < 0": (SQUARE, ["contact.gap=-1e-4"], "contact.gap = -0.0001: must be >= 0"),
    "key of another mesh type": (SQUARE, ["mesh.size=0.1"],
                                 "mesh.size: not used with mesh.type \"unit_square\""),
    "a mesh only the Python API takes": (
        SQUARE, ['mesh={"type":"dolfinx"}'],
        "mesh.type = \"dolfinx\": a mesh given as dolfinx objects, which only the Python API "
        "takes (piezocontact.Problem)"),
    "mesh script missing": (CONTACTOR, ["mesh.geometry=nope.py"],
                            "mesh.geometry = \"nope.py\": no such file"),
    "mesh file unreadable": (SQUARE, ["mesh={\"type\":\"xdmf\",\"path\":\"BROKEN\"}"],
                             "mesh: cannot read a mesh \"mesh\" with facet tags"),
    "unknown boundary name": (SQUARE, ["boundaries.lft={}"],
                              "boundaries.lft: the mesh has no boundary 'lft' "
                              "(it has: bottom, left, right, top)"),
    "probe outside the domain": (SQUARE, ["probes=[[2,2]]"],
                                 "probes[0] = [2.0,2.0]: outside the mesh"),
    "output directory not writable": (SQUARE, [], "--output /proc/piezo: cannot write there"),
    "malformed JSON": ("BROKEN_JSON", [], "invalid JSON at line 2 column 42: "),
    "config file missing": ("MISSING", [], "cannot read: No such file or directory"),
    "config is a directory": ("DIRECTORY", [], "cannot read: not a regular file"),
    "number beyond double": ("OVERFLOW", [], "mesh.n = 1e400: beyond the range of a double "
                             "(invalid JSON at line 1 column 39)"),
    "number beyond double in --set": (SQUARE, ["contact.c_p=1e400"],
                                      "--set contact.c_p: 1e400: beyond the range of a double"),
    "top level not an object": ("ARRAY", ["mesh.n=4"], "the top level is an array: a config "
                                "is one JSON object"),
    "contact boundary without the contact block": (
        "NO_CONTACT", [], "contact: missing: boundaries.bottom has \"contact\": true, which "
        "needs the top-level contact block (c_p and gap, or an obstacle)"),
    "invalid UTF-8": ("BAD_UTF8", [], "invalid JSON at line 1 column 11: syntax error while "
                      "parsing value - invalid string: ill-formed UTF-8 byte; last read: "
                      "'\"\\xff'"),
    "nesting 100000 deep": ("DEEP", [], "invalid JSON: nested more than 32 levels deep"),
    "more than 1 MiB": ("HUGE", [], "bytes: more than the 1048576 accepted"),
    "integer beyond 32 bits": (SQUARE, ["time.steps=4294967297"],
                               "time.steps = 4294967297: must be <= 1000000"),
    "Newton iterations beyond 32 bits": (SQUARE, ["solver.newton.max_iterations=2147483648"],
                                         "solver.newton.max_iterations = 2147483648: "
                                         "must be <= 1000"),
    "--set without a key": (SQUARE, ["=3"], "--set '=3': expected key.path=value"),
    "--set index beyond any list": (SQUARE, ["probes.99999999999999999999=1"],
                                    "--set probes.99999999999999999999: cannot set "
                                    "'99999999999999999999' here"),
    "unknown linear solver": (SQUARE, ["solver.linear=bogus"],
                              'solver.linear = "bogus": expected one of direct, iterative'),
    "unknown PETSc type": (SQUARE, ["solver.petsc_options.pc_type=bogus"],
                           "solver.petsc_options.pc_type = bogus: refused by PETSc: Unable "
                           "to find requested PC type bogus"),
    "unknown PETSc type of a sub-solver": (
        SQUARE, ["solver.petsc_options.pc_type=fieldsplit",
                 "solver.petsc_options.fieldsplit_phi_pc_type=bogus"],
        "solver.petsc_options.fieldsplit_phi_pc_type = bogus: refused by PETSc: Unable to "
        "find requested PC type bogus"),
    "malformed PETSc number": (SQUARE, ["solver.petsc_options.ksp_type=gmres",
                                        "solver.petsc_options.ksp_rtol=abc"],
                               "solver.petsc_options.ksp_rtol = abc: refused by PETSc: Input "
                               "string abc has no numeric value"),
    "PETSc option with a dash": (SQUARE, ["solver.petsc_options.-ksp_type=cg"],
                                 "solver.petsc_options.-ksp_type = cg: not a PETSc option "
                                 "name (letters, digits and _; no leading dash)"),
    "no displacement condition": (SQUARE, ["boundaries.left={}"],
                                  "boundaries: none has a displacement condition (or a spring "
                                  "bed with both stiffnesses): with frictionless contact nothing "
                                  "holds the body against sliding"),
    "output is a file": (SQUARE, [], "cannot write there: it exists and is not a directory"),
    "missing required key": ("NO_CP", [], "contact.c_p: missing required key"),
    "Dirichlet value neither numbers nor \"exact\"": (
        SQUARE, ["boundaries.left.displacement=5"],
        "boundaries.left.displacement = 5: expected a list of 2 numbers or expressions of x, y, z, t (strings), null for a free component (the mesh is 2D) or \"exact\""),
    "\"exact\" without a manufactured solution": (
        SQUARE, ["boundaries.left.potential=exact"],
        "boundaries.left.potential = \"exact\": needs the key manufactured "
        "(the exact solution to take it from)"),
    "unknown manufactured profile": (MMS, ["manufactured.space=cubic"],
                                     "manufactured.space = \"cubic\": expected one of "
                                     "linear, quadratic, smooth"),
    "a load with a manufactured solution": (MMS, ["loads.body_force=[1,0]"],
                                            f"loads.body_force = [1.0,0.0]: {UNUSED}"),
    "a traction with a manufactured solution": (MMS, ["boundaries.top.traction=[0,-10]"],
                                                f"boundaries.top.traction: {UNUSED}"),
    "a preset with tensors of its own": (
        SQUARE, ['material={"preset":"PZT-4","poling":[0,1],"elastic":[[1,0,0],[0,1,0],[0,0,1]]}'],
        "material.elastic: not used with a preset"),
    "a preset without orientation": (
        SQUARE, ['material={"preset":"PZT-4"}'],
        "material.preset = \"PZT-4\": give its orientation, either poling"),
    "an unknown preset": (
        SQUARE, ['material={"preset":"PZT-8","poling":[0,1]}'],
        "material.preset = \"PZT-8\": expected one of ZnO-paper, PZT-4, PZT-5H"),
    "a zero poling direction": (
        SQUARE, ['material={"preset":"PZT-4","poling":[0,0]}'],
        "material.poling = [0.0,0.0]: must be a nonzero direction"),
    "a 2D vector on a 3D mesh": (
        SLAB, ["boundaries.top.traction=[0,-10]"],
        "boundaries.top.traction = [0,-10]: expected a list of 3 numbers or expressions of x, y, z, t "
        "(strings) (the mesh is 3D)"),
    "a region the mesh lacks": (
        BILAYER, ['regions.core={"preset":"PZT-4","poling":[0,1]}'],
        "regions.core: the mesh has no region 'core' (it has: film, substrate)"),
    "both material and regions": (
        BILAYER, ['material={"preset":"PZT-4","poling":[0,1]}'],
        "regions: give either material (one for the whole body) or regions, not both"),
    "numeric Dirichlet data with a manufactured solution": (
        MMS, ["boundaries.top.potential=3"],
        "boundaries.top.potential = 3.0: with a manufactured solution the Dirichlet data "
        "are the exact solution's: use \"exact\""),
    "no potential anywhere": (
        SQUARE, ['boundaries.left={"displacement":[0,0]}'],
        "boundaries: none has a potential, so phi is known only up to a constant"),
    "a floating electrode with a potential": (
        SQUARE, ['boundaries.right={"floating":{},"potential":1}'],
        "boundaries.right: floating and potential are exclusive"),
    "a floating electrode with nothing grounded": (
        SQUARE, ['boundaries.left={"displacement":[0,0]}', 'boundaries.right={"floating":{}}'],
        "boundaries.right.floating: no boundary has a prescribed potential"),
    "a floating electrode touching another electrode": (
        SQUARE, ['boundaries.top={"floating":{"charge":1e-9}}'],
        "boundaries.top.floating: the electrode shares a vertex with the electrode left"),
    "a floating charge that is not a number": (
        SQUARE, ['boundaries.right={"floating":{"charge":"1e-9"}}'],
        "boundaries.right.floating.charge = \"1e-9\": expected a number"),
    # data that vary in space: the parser's reason, and values that are not finite
    "an expression with an unknown name": (
        SQUARE, ['boundaries.top.traction=["-2e10*yy", 0]'],
        "boundaries.top.traction[0]: \"-2e10*yy\": not an expression of x, y, z, t: "
        "Unexpected token \"yy\" found at position 6."),
    "an unfinished expression": (
        SQUARE, ['loads.charge_density="1e-3*(x+"'],
        "loads.charge_density: \"1e-3*(x+\": not an expression of x, y, z, t: "),
    "two values in one expression": (
        SQUARE, ['contact.gap="1e-6, 2e-6"'],
        "contact.gap: \"1e-6, 2e-6\": not an expression of x, y, z, t: 2 values separated "
        "by commas: a datum takes one"),
    "an assignment in an expression": (
        SQUARE, ['boundaries.left.potential="y=1"'],
        "boundaries.left.potential: \"y=1\": not an expression of x, y, z, t: \"=\" assigns "
        "in muparser: write == for a comparison"),
    "an expression that is not finite on its boundary": (
        SQUARE, ['boundaries.top.traction=["1/x", 0]'],
        "boundaries.top.traction[0]: \"1/x\" is inf at (0.0, 1.0"),
    "an expression in a manufactured run": (
        MMS, ['contact.gap="1e-11*x"'],
        "contact.gap = \"1e-11*x\": a manufactured solution's gap is a number"),
    # the 2D formulations
    "a formulation on a 3D mesh": (
        SLAB, ["formulation=plane_stress"],
        "formulation: \"plane_stress\": a formulation of 2D meshes (the mesh is 3D)"),
    "an unknown formulation": (
        SQUARE, ["formulation=plane"],
        "formulation = \"plane\": expected one of plane_strain, plane_stress, axisymmetric"),
    "plane tensors in axisymmetry": (
        SQUARE, ["formulation=axisymmetric"],
        "material.elastic: a 3x3 matrix does not fit the axisymmetric formulation: it takes "
        "4x4 (reduced) or 6x6 (the 3D tensor, reduced by the formulation)"),
    "tensors of two shapes in one material": (
        SQUARE, ['material={"elastic":[[1e11,5e10,5e10,0,0,0],[5e10,1e11,5e10,0,0,0],'
                 '[5e10,5e10,1e11,0,0,0],[0,0,0,2e10,0,0],[0,0,0,0,2e10,0],[0,0,0,0,0,2e10]],'
                 '"relaxation_time":0.1,"piezoelectric":[[0,0,1],[1,1,0]],'
                 '"permittivity":[[1e-8,0],[0,1e-8]]}'],
        "material.permittivity: a 2x2 matrix with a 6x6 elastic tensor: one material's "
        "tensors have one shape (3x3 here)"),
    "a material that drives torsion in axisymmetry": (
        SQUARE, ["formulation=axisymmetric",
                 'material={"preset":"PZT-5H","euler":[0,30,0]}'],
        "material: axisymmetric: it couples the axisymmetric strains or fields to torsion"),
    "an axisymmetric mesh across the axis": (
        "ACROSS_AXIS", ["formulation=axisymmetric"],
        "formulation: axisymmetric: the mesh has points at x = r < 0 (down to -1.0 m): an "
        "axisymmetric mesh lies in the half-plane x >= 0, y the axis"),
    # obstacles and Nitsche's method
    "an obstacle of two kinds": (
        SQUARE, ['contact={"c_p":1e12,"obstacle":{' + PLANE
                 + ',"sphere":{"center":[0,-1],"radius":1}}}'],
        ": give exactly one of plane, sphere, cylinder"),
    "an obstacle and a gap": (
        SQUARE, ['contact.obstacle={' + PLANE + '}'],
        "contact.gap: the obstacle's geometry gives the gap (gap is the paper's "
        "foundation's, without an obstacle)"),
    "an obstacle's direction zero": (
        SQUARE, ['contact={"c_p":1e12,"obstacle":{"plane":{"point":[0,0],"normal":[0,0]}}}'],
        "contact.obstacle.plane.normal = [0.0,0.0]: a direction cannot be zero"),
    "a cylinder in 2D": (
        SQUARE, ['contact={"c_p":1e12,"obstacle":{"cylinder":{"point":[0,0],"axis":[0,1],'
                 '"radius":1}}}'],
        "contact.obstacle.cylinder: a 3D obstacle (in 2D, a sphere is a circle: a cylinder "
        "across the plane)"),
    "the penalty without c_p": (
        SQUARE, ['contact={"gap":0}'],
        "contact.c_p: missing required key (the penalty method's stiffness; or \"method\": "
        "\"nitsche\")"),
    "nitsche with a penalty": (
        SQUARE, ["contact.method=nitsche"],
        "contact.c_p: the penalty method's (the method is nitsche: its parameter is gamma)"),
    "nitsche's theta out of range": (
        SQUARE, ['contact={"gap":0,"method":"nitsche","theta":2}'],
        "contact.theta = 2: must be <= 1"),
    "nitsche's gamma with the penalty": (
        SQUARE, ["contact.gamma=10"],
        "contact.gamma: Nitsche's method's (give \"method\": \"nitsche\")"),
    "a boundary's contact neither true nor a block": (
        SQUARE, ["boundaries.bottom.contact=5"],
        "boundaries.bottom.contact = 5: expected true or false, or a contact block (the keys "
        "of the top-level contact)"),
    "a sphere off the axis in axisymmetry": (
        DISC, ['boundaries.side={"contact":{"c_p":1e12,"obstacle":{"sphere":{"center":[0.02,0],'
               '"radius":0.01}}}}'],
        "boundaries.side.contact.obstacle.sphere.center = [0.02,0.0]: in axisymmetry a sphere "
        "is centred on the axis (r = 0)"),
    "an obstacle in a manufactured run": (
        MMS, ['contact={"c_p":1e12,"obstacle":{' + PLANE + '}}'],
        "contact: a manufactured solution's contact is the paper's foundation (\"contact\": "
        "true, the top-level block with c_p and gap, penalty)"),
    "a dynamic analysis without density": (
        SQUARE, ['analysis={"modal":{"modes":3}}'],
        "material.density: missing: a dynamic analysis needs the mass density of each "
        "material (kg/m^3)"),
    "modes < 1": (SQUARE, ['analysis={"modal":{"modes":0}}', "material.density=5680"],
                  "analysis.modal.modes = 0: must be >= 1"),
    "both analyses": (
        SQUARE, ['analysis={"modal":{"modes":1},"harmonic":{"frequencies":[1]}}',
                 "material.density=5680"],
        "analysis: give modal or harmonic, not both"),
    "a negative frequency": (
        SQUARE, ['analysis={"harmonic":{"frequencies":[1e3,-1e3]}}', "material.density=5680"],
        "analysis.harmonic.frequencies[1] = -1000.0: must be >= 0"),
    "an empty band": (
        SQUARE, ['analysis={"harmonic":{"frequencies":{"start":2e3,"stop":1e3,"points":10}}}',
                 "material.density=5680"],
        "analysis.harmonic.frequencies: the band 2000 to 1000 Hz is empty (stop > start, or "
        "one point)"),
    "a history in harmonic data": (
        SQUARE, ['analysis={"harmonic":{"frequencies":[1e3]}}', "material.density=5680",
                 'boundaries.top.traction={"value":[0,-10],"history":{"ramp":1}}'],
        "boundaries.top.traction.history: a harmonic analysis takes each datum's value as its "
        "complex amplitude (phase 0): no history, no expression of t"),
    "harmonic with nothing driven": (
        SQUARE, ['analysis={"harmonic":{"frequencies":[1e3]}}', "material.density=5680",
                 "boundaries.top.traction=[0,0]"],
        "analysis.harmonic: nothing is driven (give a load, a prescribed displacement or "
        "potential, or a floating electrode's charge: their values are the amplitudes)"),
}


def write_rectangle_msh(path, lo, hi):
    """A gmsh .msh of the rectangle lo-hi, its bottom edge named "bottom"."""
    import gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        gmsh.model.add("rectangle")
        r = gmsh.model.occ.addRectangle(lo[0], lo[1], 0, hi[0] - lo[0], hi[1] - lo[1])
        gmsh.model.occ.synchronize()
        bottom = [c for _, c in gmsh.model.getEntities(1)
                  if gmsh.model.getBoundingBox(1, c)[4] < lo[1] + 1e-6]  # OCC pads boxes
        gmsh.model.addPhysicalGroup(1, bottom, 1)
        gmsh.model.setPhysicalName(1, 1, "bottom")
        gmsh.model.addPhysicalGroup(2, [r], 1)
        gmsh.model.setPhysicalName(2, 1, "body")
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.5)
        gmsh.model.mesh.generate(2)
        gmsh.write(str(path))
    finally:
        gmsh.finalize()


def materialise(case, tmp):
    """(config path, overrides, output dir) for a case, making files it needs."""
    config, overrides, _ = CASES[case]
    tmp = Path(tmp)
    out = "/proc/piezo" if case == "output directory not writable" else str(tmp / "out")
    if case == "output is a file":
        out = str(SQUARE)
    if config == "BROKEN_JSON":
        config = tmp / "broken.json"
        config.write_text('{\n  "mesh": {"type": "unit_square", "n": 4,}\n}\n')
    elif config == "MISSING":
        config = tmp / "nope.json"
    elif config == "DIRECTORY":
        config = tmp
    elif config == "OVERFLOW":
        config = tmp / "overflow.json"
        config.write_text('{"mesh": {"type": "unit_square", "n": 1e400}}')
    elif config == "BAD_UTF8":
        config = tmp / "utf8.json"
        config.write_bytes(b'{"mesh": "\xff\xfe"}')
    elif config == "DEEP":
        config = tmp / "deep.json"
        config.write_text('{"a":' * 100000 + "1" + "}" * 100000)
    elif config == "HUGE":
        config = tmp / "huge.json"
        config.write_text(SQUARE.read_text()[:-2] + ', "pad": "' + "x" * (1 << 20) + '"}')
    elif config == "ARRAY":
        config = tmp / "array.json"
        config.write_text("[1, 2]")
    elif config == "NO_CONTACT":
        cfg = json.loads(SQUARE.read_text())
        del cfg["contact"]
        config = tmp / "no_contact.json"
        config.write_text(json.dumps(cfg))
    elif config == "NO_CP":
        cfg = json.loads(SQUARE.read_text())
        del cfg["contact"]["c_p"]
        config = tmp / "no_cp.json"
        config.write_text(json.dumps(cfg))
    elif config == "ACROSS_AXIS":  # a rectangle -1 <= x <= 1: half of it at r < 0
        config = tmp / "across.json"
        write_rectangle_msh(tmp / "across.msh", (-1.0, 0.0), (1.0, 1.0))
        cfg = {"mesh": {"type": "msh", "path": "across.msh"},
               "material": {"preset": "PZT-5H", "poling": [0, 1]},
               "boundaries": {"bottom": {"displacement": [None, 0.0], "potential": 0.0}},
               "time": {"T": 1.0, "steps": 1}}
        config.write_text(json.dumps(cfg))
    if case == "mesh file unreadable":
        (tmp / "broken.xdmf").write_text("<Xdmf>not a mesh</Xdmf>\n")
        (tmp / "broken.boundaries.json").write_text('{"boundaries": {"a": 1}}')
        overrides = [o.replace("BROKEN", str(tmp / "broken.xdmf")) for o in overrides]
    return Path(config), overrides, out


def main():
    rows = ["# What bad input gets\n",
            "All three engines (`piezo-contact`, `python3 -m piezocontact`, "
            "`python3 -m piezocontact --engine reference`) refuse each of these before "
            "computing anything, with exit code 2 and the same one-line message naming "
            "the file, the key and the value: one validator, in the C++ core, checks the "
            "input for all three. Checked by `tests/robustness/test_config.py`; this table is "
            "regenerated from real runs by "
            "`/usr/bin/python3 tests/bad_inputs.py --write docs/errors.md`.\n",
            "In the C++ loop (`piezo-contact`, `python3 -m piezocontact`) a Newton failure "
            "is retried with the time step halved (up to "
            "`solver.newton.max_step_halvings`, default 4); if that fails too, the run "
            "stops with exit code 3, the message names the time, the step and both "
            "relative residuals, and summary.json (status \"failed\", with its events) "
            "and the XDMF file keep every step computed before. The reference engine "
            "has fixed steps: it stops at the first failure, with exit code 3. "
            "A linear solve that fails (dolfinx's Krylov solver would go on with its "
            "garbage) is a failed Newton iteration: with `solver.linear = \"iterative\"`, "
            "`the Krylov solver did not converge in N iterations (DIVERGED_ITS, Newton "
            "step)` joins the message; a factorisation out of memory stops the run at "
            "once, exit code 3: `error: the LDL^T factorisation ran out of memory (Newton "
            "step) at t = 0.0625: solver.linear = \"iterative\" needs a fraction of the "
            "memory` (a MUMPS workspace under-estimate names `mat_mumps_icntl_14`); a "
            "failed solve before the first step (the first Jacobian's) ends the run the "
            "same way. Checked by `tests/engines/test_linear_solver.py`.\n",
            "An expression of t that is finite at start-up but not at a later step "
            "(`\"1/(1-t)\"` at t = 1) stops the run at that step with exit code 2 and the "
            "same kind of line (`boundaries.top.traction[0]: \"1/(1-t)\" is inf at (1.0, 1.0, "
            "0.0) at t = 1.0: a datum must be finite everywhere`); summary.json says "
            "\"failed\" with it and keeps the steps before.\n",
            "A write error (a full disk) stops the run with exit code 4 and one line, "
            "`error: cannot write FILE: No space left on device`; summary.json says "
            "\"failed\" with that error when there is room for it, and every earlier step "
            "stays readable. SIGINT and SIGTERM stop it with exit code 130 and 143, status "
            "\"interrupted\". `--resume` refuses, with exit code 2, a directory without "
            "summary.json (`DIR/summary.json: cannot resume: no such file`), a completed run "
            "(`cannot resume: status = \"completed\"`, unless extended to a later `time.T` at "
            "the same step: `--set time.T=... --set time.steps=...`, the only keys `--resume` "
            "takes), another engine's run (`cannot resume: solver = \"cpp-jit\", this is "
            "the \"cpp\" solver`) and `--config` beside it; the reference engine resumes "
            "no run (`cannot resume: the reference engine runs whole`). Checked by "
            "`tests/robustness/test_interrupts.py`.\n",
            "`piezocontact.Problem` (docs/api.md) raises `ConfigError` with these messages, "
            "`piezocontact.Problem:` in place of the file, at construction; its own: a tag "
            "value no entity carries (`boundary_names.top = 99: no entity of the mesh carries "
            "this tag`), tags of the wrong dimension (`facet_tags: tags of entities of "
            "dimension 2, expected 1`) or of another mesh (`an index outside the mesh's N "
            "local entities`), regions without cell tags, cells other than triangles and "
            "tetrahedra, a mesh distributed without ghost cells (`create it with "
            "ghost_mode=dolfinx.mesh.GhostMode.shared_facet`), a UFL value where the config "
            "takes none (`boundaries.left.potential: a UFL value is taken by ...`). Checked by "
            "`tests/engines/test_problem.py`.\n",
            "| bad input | message (`piezo-contact`, config `demos/...` or a scratch file) |",
            "|---|---|"]
    exe = Path(os.environ.get("PIEZO_BUILD", ROOT / "build")) / "piezo-contact"
    for case in CASES:
        with tempfile.TemporaryDirectory() as tmp:
            config, overrides, out = materialise(case, tmp)
            args = [str(exe), "--config", str(config), "--output", out, "--quiet"]
            for o in overrides:
                args += ["--set", o]
            proc = subprocess.run(args, capture_output=True, text=True)
            message = proc.stderr.strip().splitlines()[-1].replace(tmp, "TMP")
            message = message.replace(str(ROOT) + "/", "")
        rows.append(f"| {case} | `{message}` (exit {proc.returncode}) |")
    text = "\n".join(rows) + "\n"
    print(text)
    if "--write" in sys.argv:
        Path(sys.argv[sys.argv.index("--write") + 1]).write_text(text)


if __name__ == "__main__":
    main()
