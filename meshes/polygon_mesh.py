"""Mesh a polygon with gmsh and write what the C++ core reads:
  NAME.xdmf (+ .h5)       the triangle mesh ("mesh") and facet tags ("facets")
  NAME.boundaries.json    {"boundaries": {name: facet tag}, ...}
Each edge of the polygon belongs to a named boundary (a gmsh physical group);
dolfinx 0.5 has no gmsh reader in C++, so this is the exchange format."""

import argparse
import importlib.util
import json
import sys
from pathlib import Path

import gmsh
from dolfinx import io
from physical_groups import grade
from mpi4py import MPI


def _load_compat():
    """The package's _compat (what differs between dolfinx releases),
    from this source tree: importing the package would need its bindings."""
    path = Path(__file__).resolve().parents[1] / "python" / "piezocontact" / "_compat.py"
    spec = importlib.util.spec_from_file_location("piezocontact_compat", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


compat = _load_compat()

MAX_TRIANGLES = 5e6


def build_polygon(points, edge_names, size, graded=None):
    """Add the polygon to the current gmsh model and mesh it. edge_names[i]
    names the edge from points[i] to points[i+1] (closing the loop).
    graded = (i, radius, coarse): cells of `size` within `radius` of
    points[i], growing linearly to `coarse` at ten times that distance."""
    geo = gmsh.model.geo
    tags = [geo.addPoint(x, y, 0.0, size) for x, y in points]
    lines = [geo.addLine(tags[i], tags[(i + 1) % len(tags)]) for i in range(len(tags))]
    surface = geo.addPlaneSurface([geo.addCurveLoop(lines)])
    geo.synchronize()
    if graded:
        i, radius, coarse = graded
        grade([tags[i]], size, radius, coarse)
    names = sorted(set(edge_names))
    for tag, name in enumerate(names, start=1):
        members = [line for line, n in zip(lines, edge_names) if n == name]
        gmsh.model.addPhysicalGroup(1, members, tag)
        gmsh.model.setPhysicalName(1, tag, name)
    gmsh.model.addPhysicalGroup(2, [surface], 1)
    gmsh.model.setPhysicalName(2, 1, "body")
    gmsh.model.mesh.generate(2)
    return {name: tag for tag, name in enumerate(names, start=1)}


def write_mesh(points, edge_names, size, output, comm=MPI.COMM_WORLD, graded=None):
    """Generate on rank 0, distribute, write XDMF + the names sidecar."""
    output = Path(output)
    boundaries = None
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        if comm.rank == 0:
            gmsh.model.add(output.stem)
            boundaries = build_polygon(points, edge_names, size, graded)
        mesh, _, facet_tags = compat.gmsh_model_to_mesh(gmsh.model, comm, 0, 2)
    finally:
        gmsh.finalize()
    boundaries = comm.bcast(boundaries, root=0)
    mesh.name = "mesh"
    facet_tags.name = "facets"
    if comm.rank == 0:
        output.parent.mkdir(parents=True, exist_ok=True)
    comm.barrier()
    mesh.topology.create_connectivity(1, 2)
    with io.XDMFFile(comm, str(output), "w") as xdmf:
        xdmf.write_mesh(mesh)
        compat.write_meshtags(xdmf, facet_tags, mesh)
    if comm.rank == 0:
        sidecar = {"boundaries": boundaries, "size": size, "points": points,
                   "edges": edge_names}
        output.with_suffix(".boundaries.json").write_text(json.dumps(sidecar, indent=1))
    return mesh


def main(points, edge_names, description, graded=None):
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--size", type=float, required=True, help="target cell size (m)")
    ap.add_argument("--output", required=True, help="NAME.xdmf to write")
    args = ap.parse_args()
    if not args.size > 0:
        sys.exit(f"error: --size {args.size}: must be > 0")
    # refuse what would take hours and all the memory, before gmsh tries
    area = 0.5 * abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1)
                         in zip(points, points[1:] + points[:1])))
    if graded:  # fine cells near one point only
        area = min(area, 3.15 * graded[1] ** 2 + 3.15 * (10 * graded[1]) ** 2 / 10)
    estimate = area / (0.433 * args.size ** 2)  # equilateral triangles of side size
    if estimate > MAX_TRIANGLES:
        sys.exit(f"error: --size {args.size:g}: about {estimate:.2g} triangles "
                 f"(at most {MAX_TRIANGLES:.0e})")
    mesh = write_mesh(points, edge_names, args.size, args.output, graded=graded)
    cells = mesh.topology.index_map(2).size_global
    if MPI.COMM_WORLD.rank == 0:
        print(f"{args.output}: {cells} triangles, size {args.size:g}")
