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
