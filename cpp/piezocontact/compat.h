// compat.h: the one place where piezocontact meets the parts of dolfinx's
// C++ API that changed between 0.5.2 (Debian 12), 0.9.0 (Debian 13) and
// 0.11.0 (Debian unstable). Everything else in cpp/ spells dolfinx the same
// way on all three (docs/dolfinx-versions.md lists every shim).
#pragma once

#include <dolfinx/common/version.h>

#include <chrono>
#include <optional>

#include <algorithm>
#include <array>
#include <basix/finite-element.h>
#include <cstdint>
#include <dolfinx/common/Timer.h>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/CoordinateElement.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/sparsitybuild.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/geometry/BoundingBoxTree.h>
#include <dolfinx/io/XDMFFile.h>
#include <dolfinx/la/Vector.h>
#include <dolfinx/la/SparsityPattern.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/MeshTags.h>
#include <dolfinx/mesh/generation.h>
#include <dolfinx/mesh/utils.h>
#include <dolfinx/refinement/refine.h>
#include <functional>
#include <iterator>
#include <map>
#include <memory>
#include <numeric>
#include <span>
#include <string>
#include <utility>
#include <vector>

// The targets: 0.5.2, 0.9 and 0.11 (0.6-0.8 and 0.10 untested).
// PIEZO_DOLFINX_09: 0.9 or later; PIEZO_DOLFINX_011: 0.11 (or 0.10)
#if DOLFINX_VERSION_MAJOR > 0 || DOLFINX_VERSION_MINOR >= 10
#define PIEZO_DOLFINX_011 1
#else
#define PIEZO_DOLFINX_011 0
#endif
#if DOLFINX_VERSION_MAJOR > 0 || DOLFINX_VERSION_MINOR >= 9
#define PIEZO_DOLFINX_09 1
#include <spdlog/spdlog.h>
#else
#define PIEZO_DOLFINX_09 0
#include <dolfinx/common/loguru.hpp>
#include <xtensor/xarray.hpp>
#include <xtensor/xtensor.hpp>
#endif

namespace piezocontact::compat
{
namespace dfx = dolfinx;

// ---- Types: templated on the geometry type since 0.7 ----------------------
#if PIEZO_DOLFINX_09
using Mesh = dfx::mesh::Mesh<double>;
using FunctionSpace = dfx::fem::FunctionSpace<double>;
using CoordinateElement = dfx::fem::CoordinateElement<double>;
#else
using Mesh = dfx::mesh::Mesh;
using FunctionSpace = dfx::fem::FunctionSpace;
using CoordinateElement = dfx::fem::CoordinateElement;
#endif
using Function = dfx::fem::Function<double>;
using Constant = dfx::fem::Constant<double>;
using Form = dfx::fem::Form<double>;
using Expression = dfx::fem::Expression<double>;
using DirichletBC = dfx::fem::DirichletBC<double>;
using MeshTags = dfx::mesh::MeshTags<std::int32_t>;
using BCList = std::vector<std::shared_ptr<const DirichletBC>>;

// ---- Topology: a shared_ptr since 0.6 --------------------------------------
inline const dfx::mesh::Topology& topology(const Mesh& m)
{
#if PIEZO_DOLFINX_09
  return *m.topology();
#else
  return m.topology();
#endif
}
inline dfx::mesh::Topology& topology_mutable(const Mesh& m)
{
#if PIEZO_DOLFINX_09
  return *m.topology_mutable();
#else
  return m.topology_mutable();
#endif
}

/// Geometry nodes of cell c (an AdjacencyList in 0.5, an mdspan in 0.9;
/// 0.11 has one per cell type)
inline std::span<const std::int32_t> cell_nodes(const Mesh& m, std::int32_t c)
{
#if PIEZO_DOLFINX_011 // one dofmap per cell type
  auto dofmap = m.geometry().dofmaps().front();
  return {dofmap.data_handle() + c * dofmap.extent(1), dofmap.extent(1)};
#elif PIEZO_DOLFINX_09
  auto dofmap = m.geometry().dofmap();
  return {dofmap.data_handle() + c * dofmap.extent(1), dofmap.extent(1)};
#else
  return m.geometry().dofmap().links(c);
#endif
}

/// Bounding-box tree of the cells, owned and ghost (0.9.0's (mesh, tdim)
/// constructor does not compile: it passes topology_mutable()'s shared_ptr
/// as a reference; 0.11 takes a padding before the cells)
#if PIEZO_DOLFINX_09
using BoundingBoxTree = dfx::geometry::BoundingBoxTree<double>;
#else
using BoundingBoxTree = dfx::geometry::BoundingBoxTree;
#endif
inline BoundingBoxTree cell_tree(const Mesh& m)
{
  const int tdim = topology(m).dim();
#if PIEZO_DOLFINX_09
  const auto cells = m.topology()->index_map(tdim);
  std::vector<std::int32_t> all(cells->size_local() + cells->num_ghosts());
  std::iota(all.begin(), all.end(), 0);
#if PIEZO_DOLFINX_011
  return BoundingBoxTree(m, tdim, 0.0, std::span<const std::int32_t>(all));
#else
  return BoundingBoxTree(m, tdim, all);
#endif
#else
  return BoundingBoxTree(m, tdim);
#endif
}

/// The local values (owned, then ghosts) of a vector, as a view. 0.11's
/// array()/mutable_array() return the std::vector itself, which `auto v =
/// x.mutable_array()` would silently copy: cpp/ reads vectors through these.
inline std::span<const double> values(const dfx::la::Vector<double>& v) { return v.array(); }
inline std::span<double> mutable_values(dfx::la::Vector<double>& v)
{
#if PIEZO_DOLFINX_011
  return v.array(); // mutable_array() is deprecated
#else
  return v.mutable_array();
#endif
}

/// The index map of a vector (Vector::map() became index_map())
template <typename V>
auto index_map(const V& v)
{
#if PIEZO_DOLFINX_09
  return v.index_map();
#else
  return v.map();
#endif
}

/// Geometry nodes of each of some entities of dimension dim, flattened
/// (0.11 returns their shape too)
template <typename E>
std::vector<std::int32_t> entities_to_geometry(const Mesh& m, int dim, const E& entities)
{
#if PIEZO_DOLFINX_011
  return dfx::mesh::entities_to_geometry(m, dim, entities, false).first;
#else
  const auto nodes = dfx::mesh::entities_to_geometry(m, dim, entities, false);
  return {nodes.begin(), nodes.end()};
#endif
}

// ---- Meshes -----------------------------------------------------------------
// 0.9: sizes are int64, the ghost mode moved into the partitioner (the
// default partitioner does NOT ghost: pass shared_facet explicitly); 0.11's
// partitioner also takes the most cells a facet joins (2: no branching)
namespace detail
{
inline dfx::mesh::CellPartitionFunction facet_ghosting_partitioner()
{
#if PIEZO_DOLFINX_011
  return dfx::mesh::create_cell_partitioner(dfx::mesh::GhostMode::shared_facet, 2);
#elif PIEZO_DOLFINX_09
  return dfx::mesh::create_cell_partitioner(dfx::mesh::GhostMode::shared_facet);
#else
  return nullptr;
#endif
}
} // namespace detail

inline Mesh create_rectangle(MPI_Comm comm, std::array<std::array<double, 2>, 2> p,
                             std::array<std::size_t, 2> n, dfx::mesh::DiagonalType diagonal)
{
#if PIEZO_DOLFINX_09
  return dfx::mesh::create_rectangle<double>(
      comm, p, {std::int64_t(n[0]), std::int64_t(n[1])}, dfx::mesh::CellType::triangle,
      detail::facet_ghosting_partitioner(), diagonal);
#else
  return dfx::mesh::create_rectangle(comm, p, n, dfx::mesh::CellType::triangle,
                                     dfx::mesh::GhostMode::shared_facet, diagonal);
#endif
}

inline Mesh create_box(MPI_Comm comm, std::array<std::array<double, 3>, 2> p,
                       std::array<std::size_t, 3> n)
{
#if PIEZO_DOLFINX_09
  return dfx::mesh::create_box<double>(
      comm, p, {std::int64_t(n[0]), std::int64_t(n[1]), std::int64_t(n[2])},
      dfx::mesh::CellType::tetrahedron,
      detail::facet_ghosting_partitioner());
#else
  return dfx::mesh::create_box(comm, p, n, dfx::mesh::CellType::tetrahedron,
                               dfx::mesh::GhostMode::shared_facet);
#endif
}

/// An affine mesh "name" of an XDMF file, ghosted by facet
inline Mesh read_mesh(dfx::io::XDMFFile& f, dfx::mesh::CellType cell, const std::string& name)
{
  return f.read_mesh(CoordinateElement(cell, 1), dfx::mesh::GhostMode::shared_facet, name);
}

/// (indices, values) of the MeshTags "name" of an XDMF file
inline std::pair<std::vector<std::int32_t>, std::vector<std::int32_t>>
read_meshtags(dfx::io::XDMFFile& f, std::shared_ptr<const Mesh> mesh, const std::string& name)
{
#if PIEZO_DOLFINX_011
  const auto tags = f.read_meshtags(*mesh, name, std::nullopt);
#elif PIEZO_DOLFINX_09
  const auto tags = f.read_meshtags(*mesh, name);
#else
  const auto tags = f.read_meshtags(mesh, name);
#endif
  return {{tags.indices().begin(), tags.indices().end()},
          {tags.values().begin(), tags.values().end()}};
}

/// The degree of the coordinate element (0.11: one per cell type)
inline int coordinate_degree(const Mesh& mesh)
{
#if PIEZO_DOLFINX_011
  return mesh.geometry().cmaps().front().degree();
#else
  return mesh.geometry().cmap().degree();
#endif
}

/// MeshTags hold the topology since 0.6 (the mesh before)
inline std::shared_ptr<MeshTags> make_meshtags(std::shared_ptr<const Mesh> mesh, int dim,
                                               std::vector<std::int32_t> indices,
                                               std::vector<std::int32_t> values)
{
#if PIEZO_DOLFINX_09
  return std::make_shared<MeshTags>(mesh->topology(), dim, std::move(indices),
                                    std::move(values));
#else
  return std::make_shared<MeshTags>(mesh, dim, std::move(indices), std::move(values));
#endif
}

/// Boundary facets whose vertices all satisfy on(x, y, z) (the marker
/// takes an xtensor in 0.5, an mdspan in 0.9)
template <typename P>
std::vector<std::int32_t> locate_boundary_facets(const Mesh& mesh, P on)
{
  const int fdim = topology(mesh).dim() - 1;
#if PIEZO_DOLFINX_09
  return dfx::mesh::locate_entities_boundary(
      mesh, fdim,
      [on](auto X)
      {
        std::vector<std::int8_t> marked(X.extent(1));
        for (std::size_t i = 0; i < X.extent(1); ++i)
          marked[i] = on(X(0, i), X(1, i), X(2, i));
        return marked;
      });
#else
  return dfx::mesh::locate_entities_boundary(
      mesh, fdim,
      [on](const xt::xtensor<double, 2>& X)
      {
        xt::xtensor<bool, 1> marked(std::array<std::size_t, 1>{X.shape(1)});
        for (std::size_t i = 0; i < X.shape(1); ++i)
          marked(i) = on(X(0, i), X(1, i), X(2, i));
        return marked;
      });
#endif
}

// ---- Function spaces ----------------------------------------------------------
/// A sub-space collapsed, and the map from its dofs to the parent's (0.11
/// gives one map per cell type: ours have one)
inline std::pair<FunctionSpace, std::vector<std::int32_t>> collapse(const FunctionSpace& V)
{
  auto [collapsed, maps] = V.collapse();
#if PIEZO_DOLFINX_011
  return {std::move(collapsed), std::move(maps.front())};
#else
  return {std::move(collapsed), std::move(maps)};
#endif
}

/// Values of f at points x (m x 3) in their cells, into u (m x value size).
/// 0.11 takes the Newton tolerance and iterations of a non-affine
/// pull-back (our geometry is affine: unused; dolfinx Python's defaults)
inline void eval(const Function& f, std::span<const double> x, std::span<const std::int32_t> cells,
                 std::span<double> u, std::size_t value_size)
{
  const std::size_t m = cells.size();
#if PIEZO_DOLFINX_011
  f.eval(x, {m, 3}, cells, u, {m, value_size}, 1e-6, 15);
#else
  f.eval(x, {m, 3}, cells, u, {m, value_size});
#endif
}

/// Sub-space i (FunctionSpace::sub returns a value since 0.7, a shared_ptr in 0.5)
inline std::shared_ptr<const FunctionSpace> sub(const FunctionSpace& V, int i)
{
#if PIEZO_DOLFINX_09
  return std::make_shared<const FunctionSpace>(V.sub({i}));
#else
  return V.sub({i});
#endif
}

// The spaces of the forms. ffcx 0.9 generates no
// ufcx_function_space (no functionspace_form_* helpers): the space is built
// from basix the way dolfinx.fem.functionspace(basix.ufl.mixed_element(...))
// does. Its forms' finite_element_hashes are 0 for a mixed space, so
// create_form does not compare elements.
#if PIEZO_DOLFINX_09
using UfcxSpaceFactory = std::nullptr_t;
#define PIEZO_UFCX_SPACE(factory) nullptr
#else
using UfcxSpaceFactory = ufcx_function_space* (*)(const char*);
#define PIEZO_UFCX_SPACE(factory) factory
#endif
namespace detail
{
#if PIEZO_DOLFINX_09
using Element = std::shared_ptr<const dfx::fem::FiniteElement<double>>;

/// A dolfinx element of a basix one with `size` components (1: scalar;
/// 0.9 takes the block size, 0.11 the value shape)
inline Element blocked(const basix::FiniteElement<double>& e, int size)
{
#if PIEZO_DOLFINX_011
  return std::make_shared<const dfx::fem::FiniteElement<double>>(
      e, size == 1 ? std::nullopt : std::optional(std::vector<std::size_t>{std::size_t(size)}));
#else
  return std::make_shared<const dfx::fem::FiniteElement<double>>(e, size);
#endif
}

/// The Lagrange element of a degree, as basix.ufl.element makes it (the
/// GLL-warped variant: the equispaced points up to degree 2; create_form
/// compares the hash of a non-mixed element with the forms')
inline Element lagrange(const Mesh& mesh, int degree, int size)
{
  namespace be = basix::element;
  const auto cell = dfx::mesh::cell_type_to_basix_type(mesh.topology()->cell_type());
  return blocked(basix::create_element<double>(be::family::P, cell, degree,
                                               be::lagrange_variant::gll_warped,
                                               be::dpc_variant::unset, false),
                 size);
}

/// The space of an element (0.9 takes its value shape too; 0.11 reads it
/// from the element)
inline std::shared_ptr<FunctionSpace> space_of(std::shared_ptr<Mesh> mesh, Element e,
                                               [[maybe_unused]] std::vector<std::size_t> value_shape)
{
  auto dofmap = std::make_shared<const dfx::fem::DofMap>(
      dfx::fem::create_dofmap(mesh->comm(), dfx::fem::create_element_dof_layout(*e),
                              *mesh->topology_mutable(), nullptr, nullptr));
#if PIEZO_DOLFINX_011
  return std::make_shared<FunctionSpace>(mesh, e, dofmap);
#else
  return std::make_shared<FunctionSpace>(mesh, e, dofmap, std::move(value_shape));
#endif
}
#endif
} // namespace detail

/// The mixed space P{ku}^d x P{kphi} of x = (u, phi), the degrees those of
/// the factory's forms (dolfinx 0.5 makes it from ffcx's function space)
inline std::shared_ptr<FunctionSpace> mixed_space(std::shared_ptr<Mesh> mesh,
                                                  [[maybe_unused]] UfcxSpaceFactory factory,
                                                  [[maybe_unused]] std::array<int, 2> degrees)
{
#if PIEZO_DOLFINX_09
  const int gdim = mesh->geometry().dim();
  using Element = dfx::fem::FiniteElement<double>;
  auto e = std::make_shared<const Element>(std::vector<std::shared_ptr<const Element>>{
      detail::lagrange(*mesh, degrees[0], gdim), detail::lagrange(*mesh, degrees[1], 1)});
  return detail::space_of(mesh, e, {std::size_t(gdim + 1)});
#else
  return std::make_shared<FunctionSpace>(dfx::fem::create_functionspace(factory, "x", mesh));
#endif
}

/// The scalar P1 space of the contact pressure's forms (their test space)
inline std::shared_ptr<FunctionSpace> pressure_space(std::shared_ptr<Mesh> mesh,
                                                     [[maybe_unused]] UfcxSpaceFactory factory)
{
#if PIEZO_DOLFINX_09
  return detail::space_of(mesh, detail::lagrange(*mesh, 1, 1), {});
#else
  return std::make_shared<FunctionSpace>(dfx::fem::create_functionspace(factory, "v_0", mesh));
#endif
}

/// A Lagrange space of a degree (continuous, or DG) with `size` components
/// (1: scalar), for output: no form is made on it
inline std::shared_ptr<FunctionSpace> lagrange_space(std::shared_ptr<Mesh> mesh, int degree,
                                                     bool discontinuous, int size)
{
  namespace be = basix::element;
  const auto cell = dfx::mesh::cell_type_to_basix_type(topology(*mesh).cell_type());
#if PIEZO_DOLFINX_011
  const auto e = basix::create_element<double>(be::family::P, cell, degree,
                                               be::lagrange_variant::unset,
                                               be::dpc_variant::unset, discontinuous);
  return std::make_shared<FunctionSpace>(
      dfx::fem::create_functionspace(mesh, detail::blocked(e, size)));
#elif PIEZO_DOLFINX_09
  const auto e = basix::create_element<double>(be::family::P, cell, degree,
                                               be::lagrange_variant::unset,
                                               be::dpc_variant::unset, discontinuous);
  return std::make_shared<FunctionSpace>(dfx::fem::create_functionspace(
      mesh, e, size == 1 ? std::vector<std::size_t>{} : std::vector<std::size_t>{std::size_t(size)}));
#else
  const auto e = basix::create_element(be::family::P, cell, degree, be::lagrange_variant::unset,
                                       be::dpc_variant::unset, discontinuous);
  return std::make_shared<FunctionSpace>(dfx::fem::create_functionspace(mesh, e, size));
#endif
}

/// The Lagrange space of a datum given by expressions (the forms' field of
/// it): degree, and shape () or (d,). 0.9's create_form compares element
/// hashes: its element is made as basix.ufl makes the forms'.
inline std::shared_ptr<FunctionSpace> field_space(std::shared_ptr<Mesh> mesh, int degree,
                                                  const std::vector<std::size_t>& shape)
{
  const int size = shape.empty() ? 1 : int(shape[0]);
#if PIEZO_DOLFINX_09
  return detail::space_of(mesh, detail::lagrange(*mesh, degree, size), shape);
#else
  return lagrange_space(mesh, degree, false, size);
#endif
}

/// Cell-wise constant (DG0) space with `size` components (size > 1)
inline std::shared_ptr<FunctionSpace> dg0_space(std::shared_ptr<Mesh> mesh, int size)
{
  return lagrange_space(mesh, 0, true, size);
}

/// The mesh refined once uniformly (each edge halved), its cells on the
/// process of their parent
inline std::shared_ptr<Mesh> refined_once(const Mesh& mesh)
{
#if PIEZO_DOLFINX_011 // the default partitioner keeps cells where their parent is
  return std::make_shared<Mesh>(std::get<0>(dfx::refinement::refine(mesh, std::nullopt)));
#elif PIEZO_DOLFINX_09
  return std::make_shared<Mesh>(
      std::get<0>(dfx::refinement::refine(mesh, std::nullopt, nullptr)));
#else
  return std::make_shared<Mesh>(dfx::refinement::refine(mesh, false));
#endif
}

// ---- Dirichlet conditions -------------------------------------------------------
/// Dofs of V0 (a sub-space) and V1 (its collapsed space) on `entities`
/// (0.9 takes the topology and the two dofmaps)
inline std::array<std::vector<std::int32_t>, 2>
locate_dofs_topological(const FunctionSpace& V0, const FunctionSpace& V1, int dim,
                        std::span<const std::int32_t> entities)
{
#if PIEZO_DOLFINX_09
  return dfx::fem::locate_dofs_topological(*V0.mesh()->topology_mutable(),
                                           {*V0.dofmap(), *V1.dofmap()}, dim, entities);
#else
  return dfx::fem::locate_dofs_topological({V0, V1}, dim, entities);
#endif
}

/// The nodes (dof blocks) of a space on some entities of dimension dim
inline std::vector<std::int32_t> locate_nodes(const FunctionSpace& V, int dim,
                                              std::span<const std::int32_t> entities)
{
#if PIEZO_DOLFINX_09
  return dfx::fem::locate_dofs_topological(*V.mesh()->topology_mutable(), *V.dofmap(), dim,
                                           entities);
#else
  return dfx::fem::locate_dofs_topological(V, dim, entities);
#endif
}

/// x[dof] = g at the condition's dofs
inline void set_bc_values(const DirichletBC& bc, std::span<double> x)
{
#if PIEZO_DOLFINX_09
  bc.set(x, std::nullopt);
#else
  bc.set(x);
#endif
}

// ---- Forms and expressions ---------------------------------------------------------
using Coefficients = std::map<std::string, std::shared_ptr<const Function>>;
using Constants = std::map<std::string, std::shared_ptr<const Constant>>;

/// A form whose integrals marked 1 (dx(1), ds(1)) run over `entities` (cells
/// or facets, local indices) and whose unmarked integrals run everywhere.
/// `entities` null: no marked integral is integrated. 0.5 took MeshTags; 0.9
/// takes (id, integration entities), (cell, local facet) pairs for facets.
inline std::shared_ptr<const Form>
create_form(const ufcx_form& f, const std::vector<std::shared_ptr<const FunctionSpace>>& spaces,
            const Coefficients& coefficients, const Constants& constants,
            dfx::fem::IntegralType type, const std::vector<std::int32_t>* entities,
            std::shared_ptr<const Mesh> mesh)
{
  const int tdim = topology(*mesh).dim();
  const int dim = type == dfx::fem::IntegralType::cell ? tdim : tdim - 1;
  std::vector<std::int32_t> piece;
  if (entities) // sorted, unique (MeshTags requires it; assembly order is then fixed)
  {
    piece = *entities;
    std::sort(piece.begin(), piece.end());
    piece.erase(std::unique(piece.begin(), piece.end()), piece.end());
  }
#if PIEZO_DOLFINX_09
  std::map<dfx::fem::IntegralType,
           std::vector<std::pair<std::int32_t, std::span<const std::int32_t>>>>
      subdomains;
  std::vector<std::int32_t> domain;
  if (entities)
  {
    if (dim != tdim)
    {
      mesh->topology_mutable()->create_connectivity(dim, tdim);
      mesh->topology_mutable()->create_connectivity(tdim, dim);
    }
#if PIEZO_DOLFINX_011
    // 0.11 integrates an exterior-facet integral over any facet given (one
    // side of an interior one); dolfinx.fem.form, and 0.5 and 0.9 here, keep
    // the exterior ones: an internal electrode's ds charge stays 0 as there
    if (type == dfx::fem::IntegralType::exterior_facet)
    {
      const auto exterior = dfx::mesh::exterior_facet_indices(*mesh->topology());
      std::vector<std::int32_t> kept;
      std::ranges::set_intersection(piece, exterior, std::back_inserter(kept));
      piece = std::move(kept);
    }
    domain = dfx::fem::compute_integration_domains(type, *mesh->topology(), piece);
#else
    domain = dfx::fem::compute_integration_domains(type, *mesh->topology(), piece, dim);
#endif
    subdomains[type] = {{1, std::span<const std::int32_t>(domain)}};
  }
  // 0.9: coefficients' entity maps (mixed-dimensional forms), 0.11: the
  // entity maps of the form: none here either way
  return std::make_shared<const Form>(dfx::fem::create_form<double>(
      f, spaces, coefficients, constants, subdomains, {}, mesh));
#else
  std::shared_ptr<MeshTags> tags;
  if (entities)
    tags = make_meshtags(mesh, dim, piece, std::vector<std::int32_t>(piece.size(), 1));
  return std::make_shared<const Form>(dfx::fem::create_form<double>(
      f, spaces, coefficients, constants, {{type, tags.get()}}, mesh));
#endif
}

/// 0.9 drops the mesh argument (an Expression has no mesh; interpolation
/// uses the target's); 0.11 takes entity maps (none: one mesh)
inline std::shared_ptr<const Expression>
create_expression(const ufcx_expression& e, const Coefficients& coefficients,
                  const Constants& constants, [[maybe_unused]] std::shared_ptr<const Mesh> mesh)
{
#if PIEZO_DOLFINX_011
  return std::make_shared<const Expression>(
      dfx::fem::create_expression<double>(e, coefficients, constants, {}));
#elif PIEZO_DOLFINX_09
  return std::make_shared<const Expression>(
      dfx::fem::create_expression<double>(e, coefficients, constants));
#else
  return std::make_shared<const Expression>(
      dfx::fem::create_expression<double>(e, coefficients, constants, mesh));
#endif
}

// ---- Sparsity -------------------------------------------------------------------
/// Add the cell and exterior-facet integrals of a bilinear form on V x V
/// (0.9: one cells() call for both, facets given as (cell, local facet);
/// 0.11 does it for a form, its integrals indexed per kernel)
inline void add_sparsity(dfx::la::SparsityPattern& pattern, const Form& a,
                         [[maybe_unused]] const dfx::fem::DofMap& dofmap)
{
  using dfx::fem::IntegralType;
#if PIEZO_DOLFINX_011
  if (a.num_integrals(IntegralType::interior_facet, 0) > 0)
    throw std::runtime_error("interior-facet terms are not supported by the Jacobian's sparsity");
  dfx::fem::build_sparsity_pattern(pattern, a);
#elif PIEZO_DOLFINX_09
  if (!a.integral_ids(IntegralType::interior_facet).empty())
    throw std::runtime_error("interior-facet terms are not supported by the Jacobian's sparsity");
  for (int id : a.integral_ids(IntegralType::cell))
  {
    const auto cells = a.domain(IntegralType::cell, id);
    dfx::fem::sparsitybuild::cells(pattern, {cells, cells}, {{dofmap, dofmap}});
  }
  for (int id : a.integral_ids(IntegralType::exterior_facet))
  {
    const auto pairs = a.domain(IntegralType::exterior_facet, id);
    std::vector<std::int32_t> cells;
    for (std::size_t i = 0; i < pairs.size(); i += 2)
      cells.push_back(pairs[i]);
    dfx::fem::sparsitybuild::cells(pattern, {cells, cells}, {{dofmap, dofmap}});
  }
#else
  if (!a.integral_ids(IntegralType::interior_facet).empty())
    throw std::runtime_error("interior-facet terms are not supported by the Jacobian's sparsity");
  for (int id : a.integral_ids(IntegralType::cell))
    dfx::fem::sparsitybuild::cells(pattern, a.cell_domains(id), {{dofmap, dofmap}});
  for (int id : a.integral_ids(IntegralType::exterior_facet))
    dfx::fem::sparsitybuild::exterior_facets(pattern, a.exterior_facet_domains(id),
                                             {{dofmap, dofmap}});
#endif
}

inline void finalize(dfx::la::SparsityPattern& pattern)
{
#if PIEZO_DOLFINX_09
  pattern.finalize();
#else
  pattern.assemble();
#endif
}

// ---- Matrix assembly ---------------------------------------------------------------
namespace detail
{
/// 0.11 takes conditions by reference
inline std::vector<std::reference_wrapper<const DirichletBC>> refs(const BCList& bcs)
{
  std::vector<std::reference_wrapper<const DirichletBC>> out;
  for (const auto& bc : bcs)
    out.push_back(*bc);
  return out;
}
} // namespace detail

/// Add a bilinear form's entries, the conditions' rows and columns zeroed
template <typename SetFn>
void assemble_matrix(SetFn add, const Form& a, const BCList& bcs)
{
#if PIEZO_DOLFINX_011
  dfx::fem::assemble_matrix(add, a, detail::refs(bcs));
#else
  dfx::fem::assemble_matrix(add, a, bcs);
#endif
}

/// 1 on the diagonal of the conditions' rows of V
template <typename SetFn>
void set_diagonal(SetFn set, const FunctionSpace& V, const BCList& bcs)
{
#if PIEZO_DOLFINX_011
  dfx::fem::set_diagonal<double>(set, V, detail::refs(bcs));
#else
  dfx::fem::set_diagonal<double>(set, V, bcs);
#endif
}

// ---- PETSc assembly --------------------------------------------------------------
/// b -= alpha A (g - x0) for one bilinear form (0.9 cannot deduce the
/// geometry type: it is explicit; 0.11 takes forms and conditions by
/// reference)
inline void apply_lifting(Vec b, const std::shared_ptr<const Form>& a, const BCList& bcs, Vec x0,
                          double alpha)
{
#if PIEZO_DOLFINX_011
  const std::vector<std::optional<std::reference_wrapper<const Form>>> forms{std::cref(*a)};
  const std::vector<std::vector<std::reference_wrapper<const DirichletBC>>> bcs1{
      detail::refs(bcs)};
  dfx::fem::petsc::apply_lifting<double>(b, forms, bcs1, {x0}, alpha);
#elif PIEZO_DOLFINX_09
  dfx::fem::petsc::apply_lifting<double>(b, {a}, {bcs}, {x0}, alpha);
#else
  dfx::fem::petsc::apply_lifting(b, {a}, {bcs}, {x0}, alpha);
#endif
}

inline void set_bc(Vec b, const BCList& bcs, Vec x0, double alpha)
{
#if PIEZO_DOLFINX_011
  dfx::fem::petsc::set_bc<double>(b, detail::refs(bcs), x0, alpha);
#elif PIEZO_DOLFINX_09
  dfx::fem::petsc::set_bc<double>(b, bcs, x0, alpha);
#else
  dfx::fem::petsc::set_bc(b, bcs, x0, alpha);
#endif
}

// ---- PETSc 3.18 (0.5.2) to 3.25 (0.11) --------------------------------------------
namespace detail
{
/// The specific message's pointer type read off PetscErrorMessage's
/// declaration (char* in 3.18, const char* in 3.25)
template <typename Code, typename Specific>
std::pair<std::string, std::string>
error_message(PetscErrorCode (*message)(Code, const char*[], Specific**), PetscErrorCode code)
{
  const char* text = nullptr;
  Specific* specific = nullptr;
  message(static_cast<Code>(code), &text, &specific);
  return {text ? text : "", specific ? specific : ""};
}
} // namespace detail

/// PETSc's text of an error code, and the specific message of the last error
inline std::pair<std::string, std::string> petsc_error_message(PetscErrorCode code)
{
  return detail::error_message(&PetscErrorMessage, code);
}

// ---- Timing -------------------------------------------------------------------------
/// A wall-clock timer registered in dolfinx's TimeLogger under `task`, in
/// seconds (0.11's Timer is a template on its clock and returns durations;
/// 0.9's elapsed() returns wall, user and system times)
class Timer
{
public:
  explicit Timer(const std::string& task) : _timer(task) {}
  double stop() { return seconds(_timer.stop()); }
  double elapsed() const
  {
#if PIEZO_DOLFINX_011
    return seconds(_timer.elapsed());
#else
    return _timer.elapsed()[0];
#endif
  }

private:
#if PIEZO_DOLFINX_011
  static double seconds(std::chrono::duration<double> d) { return d.count(); }
  dfx::common::Timer<> _timer;
#else
  static double seconds(double s) { return s; }
  dfx::common::Timer _timer;
#endif
};

// ---- Logging: loguru (0.5) became spdlog (0.6+) ------------------------------------
inline void log_errors_only()
{
#if PIEZO_DOLFINX_09
  spdlog::set_level(spdlog::level::err);
#else
  loguru::g_stderr_verbosity = loguru::Verbosity_ERROR;
#endif
}
} // namespace piezocontact::compat
