"""Convert a gmsh .msh file into what the C++ core reads: NAME.xdmf (the
mesh "mesh", facet tags "facets", cell tags "cells") and
NAME.boundaries.json ({"boundaries": {name: facet tag}, "regions": {name:
cell tag}}). The physical groups of the file name them: groups of the
cells' dimension are regions, groups one dimension lower are boundaries (a
group without a name is called by its number). dolfinx 0.5 has no .msh
reader in C++, so the executable runs this on one process:

    python3 -m piezocontact.msh device.msh --output out/mesh/device.xdmf
"""

import argparse
import json
import sys
from pathlib import Path

import gmsh
from dolfinx import io
from mpi4py import MPI

from ._compat import gmsh_model_to_mesh, write_meshtags


def physical_names(dim):
    """{name: tag} of the physical groups of dimension dim."""
    return {gmsh.model.getPhysicalName(dim, tag) or str(tag): tag
            for d, tag in gmsh.model.getPhysicalGroups(dim) if d == dim}


def convert(source, output):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        gmsh.merge(str(source))
        tdim = gmsh.model.getDimension()
        if tdim not in (2, 3):
            raise ValueError(f"a mesh of dimension {tdim}: expected 2 (triangles) or 3 (tetrahedra)")
        regions, boundaries = physical_names(tdim), physical_names(tdim - 1)
        if not regions:
            raise ValueError(f"no physical group of dimension {tdim}: name the cells "
                             "(gmsh drops every cell outside a physical group)")
        # a 2D mesh lies in the plane z = 0: its geometry is (x, y)
        x = gmsh.model.mesh.getNodes()[1].reshape(-1, 3)
        gdim = 3 if tdim == 3 or abs(x[:, 2]).max(initial=0) > 0 else 2
        mesh, cell_tags, facet_tags = gmsh_model_to_mesh(gmsh.model, MPI.COMM_SELF, 0, gdim)
    finally:
        gmsh.finalize()
    if mesh.geometry.dim != mesh.topology.dim:
        raise ValueError("a surface in 3D space: expected a plane mesh in z = 0 or a volume")
    mesh.name, cell_tags.name, facet_tags.name = "mesh", "cells", "facets"
    output.parent.mkdir(parents=True, exist_ok=True)
    mesh.topology.create_connectivity(tdim - 1, tdim)
    with io.XDMFFile(MPI.COMM_SELF, str(output), "w") as xdmf:
        xdmf.write_mesh(mesh)
        write_meshtags(xdmf, facet_tags, mesh)
        write_meshtags(xdmf, cell_tags, mesh)
    output.with_suffix(".boundaries.json").write_text(json.dumps(
        {"boundaries": boundaries, "regions": regions, "source": str(source)}, indent=1))
    return mesh


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("msh", type=Path, help="gmsh .msh file")
    ap.add_argument("--output", type=Path, required=True, help="NAME.xdmf to write")
    args = ap.parse_args()
    try:
        mesh = convert(args.msh, args.output)
    except Exception as e:  # one line for the caller's message
        sys.exit(f"error: {args.msh}: {e}".replace("\n", " ")[:300])
    cells = mesh.topology.index_map(mesh.topology.dim).size_global
    print(f"{args.output}: {cells} cells")


if __name__ == "__main__":
    main()
