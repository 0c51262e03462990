#include "output_mesh.h"

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
  // each refined cell lies in a local cell of its parent's process
  const auto tree = compat::cell_tree(*_mesh);
  const auto candidates = geometry::compute_collisions(tree, std::span<const double>(t.points));
  const auto colliding
      = geometry::compute_colliding_cells(*_mesh, candidates, std::span<const double>(t.points));
  for (std::size_t i = 0; i < t.points.size() / 3; ++i)
  {
    if (colliding.links(i).empty())
      throw std::logic_error("output mesh: a refined node outside its process's cells");
    t.cells.push_back(colliding.links(i)[0]);
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
  auto values = t.target->x()->mutable_array();
  f.eval(t.points, {m, 3}, t.cells, values.subspan(0, m * bs), {m, bs});
  return *t.target;
}
} // namespace piezocontact
