"""Name a gmsh model's entities: the physical groups the solver reads as
regions (cells) and boundaries (facets); and the command line of a script
that writes a .msh file."""

import argparse
from pathlib import Path

import gmsh


def name_groups(dim, groups):
    """Physical groups of dimension `dim` from {name: [entity tags]}, tagged
    1, 2, ... in the order given."""
    for tag, (name, members) in enumerate(groups.items(), start=1):
        gmsh.model.addPhysicalGroup(dim, list(members), tag)
        gmsh.model.setPhysicalName(dim, tag, name)


def grade(points, size, radius, coarse):
    """Cells of `size` within `radius` of some model points (tags), growing
    linearly to `coarse` at ten times that distance: the background mesh
    size, the only one gmsh uses then."""
    field = gmsh.model.mesh.field
    distance = field.add("Distance")
    try:
        field.setNumbers(distance, "PointsList", points)
    except Exception:  # gmsh < 4.10 calls it NodesList
        field.setNumbers(distance, "NodesList", points)
    threshold = field.add("Threshold")
    field.setNumber(threshold, "InField", distance)
    for name, value in (("SizeMin", size), ("SizeMax", coarse), ("DistMin", radius),
                        ("DistMax", 10 * radius)):
        field.setNumber(threshold, name, value)
    field.setAsBackgroundMesh(threshold)
    for option in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
        gmsh.option.setNumber(f"Mesh.{option}", 0)


def msh_script(name, build, description, size, output=None, binary=False):
    """The main of a script that writes one .msh file: --size (default
    `size`) and --output (default `output`, else required); build(size)
    adds and meshes the model."""
    ap = argparse.ArgumentParser(description=description.splitlines()[0])
    ap.add_argument("--size", type=float, default=size)
    ap.add_argument("--output", type=Path, default=output, required=output is None)
    args = ap.parse_args()
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    if binary:
        gmsh.option.setNumber("Mesh.Binary", 1)
    try:
        gmsh.model.add(name)
        build(args.size)
        gmsh.write(str(args.output))
    finally:
        gmsh.finalize()
    print(f"wrote {args.output}")
