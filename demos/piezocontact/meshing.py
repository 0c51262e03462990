"""Meshes and named boundaries, as cpp/mesh.cpp builds them.

mesh.type:
  unit_square  built in: n x n squares cut in two; boundaries left, right,
               bottom, top
  gmsh         `geometry` is a gmsh script of meshes/ (e.g. contactor.py); it
               is run with `--size` into DIR/mesh/ and the result read
  xdmf         `path` is an XDMF mesh with facet tags "facets" and a sidecar
               NAME.boundaries.json naming them (what the gmsh scripts write)
Relative paths are relative to the config file's folder.

Whatever the source, the facet tag of a named boundary becomes 1 + its index
in sorted name order: the slot of the per-boundary constants of the forms.
"""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
from dolfinx import io
from dolfinx import mesh as dmesh

from .config import ConfigError, _fmt

UNIT_SQUARE_SIDES = {"left": (0, 0.0), "right": (0, 1.0), "bottom": (1, 0.0), "top": (1, 1.0)}
# What a mesh-generator child process inherits: not the MPI job's variables,
# which would make the child's mpi4py join (and break) the parent's job
CHILD_ENV_KEYS = ("PATH", "HOME", "TMPDIR", "XDG_CACHE_HOME", "LANG")


def resolve(value, source):
    path = Path(value)
    return path if path.is_absolute() else Path(source).resolve().parent / path


def prepare(cfg, source, out_dir, comm):
    """The XDMF file to read (None for the built-in square); for gmsh, run the
    geometry script on rank 0. Errors are raised on every rank."""
    m = cfg["mesh"]
    if m["type"] == "unit_square":
        return None
    key = "geometry" if m["type"] == "gmsh" else "path"
    path = resolve(m[key], source)
    error, target = None, path
    if comm.rank == 0:
        if not path.is_file():
            error = f"{source}: mesh.{key} = {_fmt(m[key])}: no such file ({path})"
        elif m["type"] == "gmsh":
            target = Path(out_dir).resolve() / "mesh" / (path.stem + ".xdmf")
            env = {k: os.environ[k] for k in CHILD_ENV_KEYS if k in os.environ}
            proc = subprocess.run(["/usr/bin/python3", str(path), "--size", repr(m["size"]),
                                   "--output", str(target)],
                                  capture_output=True, text=True, env=env)
            if proc.returncode != 0:
                tail = (proc.stderr.strip().splitlines() or ["(no output)"])[-1]
                error = (f"{source}: mesh.geometry = {_fmt(m['geometry'])}: mesh generation "
                         f"failed (exit {proc.returncode}): {tail}")
    error, target = comm.bcast((error, str(target)), root=0)
    if error:
        raise ConfigError(error)
    return target


def build(cfg, comm, mesh_file, source="config"):
    """Mesh, facet tags (values = slots) and {boundary name: tag}."""
    if mesh_file is None:
        return _unit_square(cfg, comm)
    return _read_xdmf(mesh_file, comm, source)


def _unit_square(cfg, comm):
    m = cfg["mesh"]
    msh = dmesh.create_unit_square(comm, m["n"], m["n"], dmesh.CellType.triangle,
                                   ghost_mode=dmesh.GhostMode.shared_facet,
                                   diagonal=getattr(dmesh.DiagonalType, m["diagonal"]))
    facets, values = [], []
    for slot, name in enumerate(sorted(UNIT_SQUARE_SIDES)):
        axis, c = UNIT_SQUARE_SIDES[name]
        f = dmesh.locate_entities_boundary(msh, 1, lambda x: np.isclose(x[axis], c))
        facets.append(f)
        values.append(np.full(len(f), slot + 1, dtype=np.int32))
    facets, values = np.concatenate(facets), np.concatenate(values)
    order = np.argsort(facets)
    tags = dmesh.meshtags(msh, 1, facets[order], values[order])
    return msh, tags, {name: s + 1 for s, name in enumerate(sorted(UNIT_SQUARE_SIDES))}


def _read_xdmf(mesh_file, comm, source):
    sidecar = Path(mesh_file).with_suffix(".boundaries.json")
    try:
        names = json.loads(sidecar.read_text())["boundaries"]
    except (OSError, ValueError, KeyError) as err:
        raise ConfigError(f"{source}: mesh: cannot read the boundary names of {mesh_file} "
                          f"from {sidecar}: {err}") from None
    try:  # every rank reads the same file
        with io.XDMFFile(comm, str(mesh_file), "r") as f:
            msh = f.read_mesh(name="mesh")
            msh.topology.create_connectivity(1, 2)
            file_tags = f.read_meshtags(msh, name="facets")
    except RuntimeError as err:
        raise ConfigError(f"{source}: mesh: cannot read a triangle mesh \"mesh\" with facet "
                          f"tags \"facets\" from {mesh_file}: {err}") from None
    tag_of = {name: s + 1 for s, name in enumerate(sorted(names))}
    slot_of_file_tag = {names[name]: tag_of[name] for name in names}
    values = np.array([slot_of_file_tag.get(v, 0) for v in file_tags.values], dtype=np.int32)
    keep = values > 0
    tags = dmesh.meshtags(msh, 1, file_tags.indices[keep], values[keep])
    return msh, tags, tag_of


def boundary_lengths(msh, tags, tag_of, comm):
    """Length of each named boundary: the sum of its owned facets' lengths."""
    from mpi4py import MPI
    from dolfinx import cpp as _cpp
    n_owned = msh.topology.index_map(1).size_local
    x = msh.geometry.x[:, :2]
    out = {}
    for name, tag in sorted(tag_of.items()):
        facets = tags.indices[(tags.values == tag) & (tags.indices < n_owned)]
        local = 0.0
        if len(facets):
            v = x[_cpp.mesh.entities_to_geometry(msh._mesh, 1, facets, False)]
            local = float(np.sum(np.linalg.norm(v[:, 1] - v[:, 0], axis=1)))
        out[name] = comm.allreduce(local, op=MPI.SUM)
    return out
