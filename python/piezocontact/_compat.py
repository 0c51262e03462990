"""The one module where piezocontact meets the parts of dolfinx's Python API
that differ between dolfinx 0.5.2 (Debian 12), 0.9.0 (Debian 13, with
dolfinx_mpc 0.9.1, UFL 2024.2, numpy 2) and 0.11.0 (Debian unstable, with
dolfinx_mpc 0.11, UFL 2026.1, Python 3.14): the package, the demos, the mesh
scripts and the tests call these instead of testing versions.

    cpp(obj)                       0.9 wraps every C++ object in ._cpp_object
                                   (0.5: Forms are theirs, a Mesh holds ._mesh)
    cell_name(topology)            the C++ Topology has no cell_name() in 0.9
    meshtags(tags)                 ufl.Measure(subdomain_data=) wants a Python
                                   MeshTags in 0.9, not the bindings' C++ one
    dirichletbcs(bcs)              fem.petsc and dolfinx_mpc want Python
                                   DirichletBCs in 0.9, not the bindings' C++ ones
    one_subdomain_data(form)       0.9's fem.form refuses integrals of one type
                                   with and without subdomain data (ufl.dx + dx(1))
    functionspace(msh, element)    fem.FunctionSpace(msh, e) and
                                   VectorFunctionSpace -> fem.functionspace
    petsc_vec(f)                   Function.vector -> Function.x.petsc_vec
    dofmap_array(V)                V.dofmap.list: AdjacencyList -> 2-D array
    geometry_dofmap(msh)           geometry.dofmap: AdjacencyList -> 2-D array
    colliding_cells(msh, points)   BoundingBoxTree, compute_collisions ->
                                   bb_tree, compute_collisions_points
    exterior_facet_geometry(msh)   cpp.mesh.entities_to_geometry(msh._mesh) ->
                                   mesh.entities_to_geometry(msh)
    write_meshtags(xdmf, tags, msh)  XDMFFile.write_meshtags wants the geometry
    mpc_backsubstitution(mpc, f)   dolfinx_mpc's homogenize, backsubstitution
                                   take the Function in 0.9, its Vec in 0.5
    create_vector(form)            0.11's fem.petsc.create_vector takes the
                                   form's space, not the form
    gmsh_model_to_mesh(model, comm, rank, gdim)  dolfinx.io.gmshio became
                                   dolfinx.io.gmsh (0.10), returning MeshData
    create_petsc_vector(imap, bs)  la.create_petsc_vector ->
                                   la.petsc.create_vector([(imap, bs)]) (0.10)

Bridged by calls that work on both, with no shim:
    elements of UFL (ufl.VectorElement, ufl.Cell(gdim) are gone): the
      elements come from forms/entry_points.elements (basix.ufl in 0.9)
    fem.petsc.apply_lifting(..., scale=) became alpha=: pass it positionally
    dolfinx.fem.petsc is no longer imported by dolfinx.fem: import it
    dolfinx.cpp.la.petsc.create_vector is gone: create_petsc_vector below
    fem.petsc.assemble_matrix(diagonal=) became diag= (0.10): positional
    dolfinx_mpc.cpp.mpc.create_matrix takes the C++ Form: cpp(form)

This module imports nothing of piezocontact (meshes/polygon_mesh.py loads it
from the source tree without the bindings)."""

import dolfinx
import dolfinx.fem.petsc  # noqa: F401  (0.9: not imported with dolfinx.fem)
import numpy as np
import ufl
from dolfinx import cpp as _cpp
from dolfinx import fem, geometry
from dolfinx import mesh as dmesh

# 0.5.2, 0.9.0 or 0.11.0: the releases in Debian 12, 13 and unstable (0.6-0.8
# and 0.10 are none of them)
_VERSION = tuple(int(p) for p in dolfinx.__version__.split(".")[:2])
DOLFINX_09 = _VERSION >= (0, 9)
DOLFINX_011 = _VERSION >= (0, 10)


def cpp(obj):
    """The C++ object of a dolfinx Python object, as our bindings take it
    (itself if it is one already)."""
    for wrapped in ("_cpp_object", "_mesh"):  # 0.5's Mesh holds its C++ mesh as ._mesh
        if hasattr(obj, wrapped):
            return getattr(obj, wrapped)
    return obj


def cell_name(topology):
    """"triangle" or "tetrahedron": the cell of a (C++ or Python) Topology."""
    return _cpp.mesh.to_string(topology.cell_type)


def meshtags(tags):
    """The bindings' C++ MeshTags as ufl.Measure(subdomain_data=) takes them."""
    if DOLFINX_09 and not isinstance(tags, dmesh.MeshTags):
        return dmesh.MeshTags(tags)
    return tags


def dirichletbcs(bcs):
    """The bindings' C++ DirichletBCs as fem.petsc and dolfinx_mpc take them."""
    if DOLFINX_09:
        return [bc if isinstance(bc, fem.DirichletBC) else fem.DirichletBC(bc) for bc in bcs]
    return list(bcs)


def one_subdomain_data(form):
    """The form with its integrals that have no subdomain data given that of
    the others of their type (an "everywhere" integral still runs
    everywhere): e.g. a hook's plain ufl.dx next to the model's tagged dx."""
    if not DOLFINX_09:
        return form
    data = {}
    for integral in form.integrals():
        if integral.subdomain_data() is not None:
            data.setdefault(integral.integral_type(), integral.subdomain_data())
    return ufl.Form([i if i.subdomain_data() is not None
                     else i.reconstruct(subdomain_data=data.get(i.integral_type()))
                     for i in form.integrals()])


def functionspace(msh, element):
    """A space of an element, or of (family, degree) / (family, degree,
    shape) with shape () or (n,)."""
    if DOLFINX_09:
        return fem.functionspace(msh, element)
    if isinstance(element, tuple) and len(element) == 3:
        family, degree, shape = element
        if shape:
            (n,) = shape
            return fem.VectorFunctionSpace(msh, (family, degree), dim=n)
        element = (family, degree)
    return fem.FunctionSpace(msh, element)


def petsc_vec(f):
    """The PETSc Vec of a Function (sharing its values)."""
    return f.x.petsc_vec if DOLFINX_09 else f.vector


def dofmap_array(V):
    """(cells, dofs per cell) array of a space's dofmap (blocks, for a
    vector space)."""
    dofs = V.dofmap.list
    if DOLFINX_09:
        return np.asarray(dofs)
    return dofs.array.reshape(-1, V.dofmap.dof_layout.num_dofs)


def geometry_dofmap(msh):
    """(cells, nodes per cell) array of the geometry's nodes."""
    nodes = msh.geometry.dofmap
    if DOLFINX_09:
        return np.asarray(nodes)
    cells = len(nodes.offsets) - 1
    return nodes.array.reshape(cells, nodes.array.size // max(cells, 1))


def colliding_cells(msh, points):
    """compute_colliding_cells of (n, 3) points: an AdjacencyList of the
    cells holding each."""
    tdim = msh.topology.dim
    if DOLFINX_09:
        candidates = geometry.compute_collisions_points(geometry.bb_tree(msh, tdim), points)
    else:
        candidates = geometry.compute_collisions(geometry.BoundingBoxTree(msh, tdim), points)
    return geometry.compute_colliding_cells(msh, candidates, points)


def exterior_facet_geometry(msh):
    """(exterior facets, nodes per facet) array of their geometry nodes."""
    tdim = msh.topology.dim
    # 0.9: exterior_facet_indices needs facet -> cell, entities_to_geometry
    # both ways
    msh.topology.create_connectivity(tdim - 1, tdim)
    msh.topology.create_connectivity(tdim, tdim - 1)
    facets = dmesh.exterior_facet_indices(msh.topology)
    if DOLFINX_09:
        return dmesh.entities_to_geometry(msh, tdim - 1, facets, False)
    return _cpp.mesh.entities_to_geometry(cpp(msh), tdim - 1, facets, False)


def write_meshtags(xdmf, tags, msh):
    """XDMFFile.write_meshtags of the tags of msh (written before)."""
    if DOLFINX_09:
        xdmf.write_meshtags(tags, msh.geometry)
    else:
        xdmf.write_meshtags(tags)


def mpc_backsubstitution(mpc, f):
    """Set a Function's slave dofs of a dolfinx_mpc MultiPointConstraint
    from their masters: homogenize, then backsubstitution (which adds)."""
    target = f if DOLFINX_09 else f.vector
    mpc.homogenize(target)
    mpc.backsubstitution(target)


def create_vector(form):
    """A ghosted PETSc Vec for a linear form's assembly."""
    if DOLFINX_011:
        return fem.petsc.create_vector(form.function_spaces[0])
    return fem.petsc.create_vector(form)


def gmsh_model_to_mesh(model, comm, rank, gdim):
    """(mesh, cell tags, facet tags) of the gmsh model on `rank`."""
    if DOLFINX_011:
        from dolfinx.io import gmsh as gmsh_io
        data = gmsh_io.model_to_mesh(model, comm, rank, gdim=gdim)
        return data.mesh, data.cell_tags, data.facet_tags
    from dolfinx.io import gmshio
    return gmshio.model_to_mesh(model, comm, rank, gdim=gdim)


def create_petsc_vector(index_map, bs):
    """A ghosted PETSc Vec on an index map with block size bs."""
    if DOLFINX_011:
        from dolfinx.la import petsc as la_petsc  # not `import dolfinx...`: a local name
        return la_petsc.create_vector([(index_map, bs)])
    return dolfinx.la.create_petsc_vector(index_map, bs)
