#include "output_mesh.h"
#include "cell_geometry.h"

#include <algorithm>

#include <dolfinx/geometry/utils.h>
#include <stdexcept>

namespace piezocontact
{
using namespace dolfinx;

OutputMesh::OutputMesh(std::shared_ptr<compat::Mesh> mesh, bool refine)
    : _mesh(mesh), _refined(refine ? compat::refined_once(*mesh) : nullptr)
{
}

namespace
{
/// The midpoint of each local cell of a mesh, (num_cells, 3)
std::vector<double> cell_midpoints(const compat::Mesh& mesh)
{
  const int tdim = compat::topology(mesh).dim();
  const auto cells = compat::topology(mesh).index_map(tdim);
  const std::int32_t n = cells->size_local() + cells->num_ghosts();
  const auto x = mesh.geometry().x();
  std::vector<double> out(3 * n, 0.0);
  for (std::int32_t c = 0; c < n; ++c)
  {
    const auto nodes = compat::cell_nodes(mesh, c);
    for (const auto node : nodes)
      for (int j = 0; j < 3; ++j)
        out[3 * c + j] += x[3 * node + j] / nodes.size();
  }
  return out;
}
} // namespace

OutputMesh::Transfer OutputMesh::transfer_for(const fem::Function<double>& f) const
{
  const auto& V = *f.function_space();
  const int bs = V.dofmap()->bs();
  // a cell-wise field has one node per cell
  const bool cellwise = V.dofmap()->cell_dofs(0).size() == 1;
  Transfer t;
  t.target = std::make_shared<fem::Function<double>>(
      compat::lagrange_space(_refined, cellwise ? 0 : 1, cellwise, bs));
  t.target->name = f.name;
  t.points = cellwise ? cell_midpoints(*_refined)
                      : t.target->function_space()->tabulate_dof_coordinates(false);
  // Each refined cell lies in a local cell of its parent's process: of the
  // cells whose bounding box holds a point, the one it is deepest in (its
  // smallest barycentric coordinate largest; no distance tolerance, which
  // would depend on the mesh's size)
  const auto tree = compat::cell_tree(*_mesh);
  const auto candidates = geometry::compute_collisions(tree, std::span<const double>(t.points));
  for (std::size_t i = 0; i < t.points.size() / 3; ++i)
  {
    std::int32_t best = -1;
    double deepest = -1e-8;
    for (const std::int32_t c : candidates.links(i))
    {
      const auto l = barycentric(std::span(t.points.data() + 3 * i, 3), cell_vertices(*_mesh, c));
      if (const double depth = *std::min_element(l.begin(), l.end()); depth > deepest)
        best = c, deepest = depth;
    }
    if (best < 0)
      throw std::logic_error("output mesh: a refined node outside its process's cells");
    t.cells.push_back(best);
  }
  return t;
}

const fem::Function<double>& OutputMesh::operator()(const fem::Function<double>& f)
{
  if (!_refined)
    return f;
  auto it = _transfers.find(&f);
  if (it == _transfers.end())
    it = _transfers.emplace(&f, transfer_for(f)).first;
  auto& t = it->second;
  const std::size_t m = t.cells.size();
  const std::size_t bs = f.function_space()->dofmap()->bs();
  auto values = compat::mutable_values(*t.target->x());
  compat::eval(f, t.points, t.cells, values.subspan(0, m * bs), bs);
  return *t.target;
}
} // namespace piezocontact
