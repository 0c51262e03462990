#include "checkpoint.h"
#include "cell_geometry.h"
#include "output.h"

#include <algorithm>
#include <cmath>

namespace piezocontact
{
using namespace dolfinx;
namespace
{
/// Where a node (a dof of each component) of a Lagrange space sits, in
/// terms no partition changes: the input (file) indices of the vertices of
/// the smallest mesh entity that holds it, ascending, and its barycentric
/// coordinates on them, rounded to 1e-9. A vertex node is its vertex alone.
using NodeKey = std::array<std::int64_t, 8>; // 4 vertices, 4 coordinates (-1: none)

/// The key of a point x in a cell of vertices `v` (coordinates, input indices)
NodeKey node_key(std::span<const double> x, const std::vector<std::array<double, 3>>& v,
                 const std::vector<std::int64_t>& input)
{
  const auto l = barycentric(x, v);
  std::vector<std::pair<std::int64_t, std::int64_t>> on; // (input vertex, rounded l)
  for (std::size_t i = 0; i < l.size(); ++i)
    if (const auto rounded = std::llround(l[i] * 1e9); rounded > 0)
      on.push_back({input[i], rounded});
  std::sort(on.begin(), on.end());
  NodeKey key;
  key.fill(-1);
  for (std::size_t i = 0; i < on.size(); ++i)
    key[i] = on[i].first, key[4 + i] = on.size() > 1 ? on[i].second : -1;
  return key;
}

/// The key of each local node (owned and ghost) of a Lagrange space
std::vector<NodeKey> node_keys(const compat::FunctionSpace& V)
{
  const auto& mesh = *V.mesh();
  const auto& imap = *V.dofmap()->index_map;
  std::vector<NodeKey> keys(imap.size_local() + imap.num_ghosts());
  const auto coordinates = V.tabulate_dof_coordinates(false);
  const auto& input = mesh.geometry().input_global_indices();
  const int tdim = compat::topology(mesh).dim();
  const auto cells = compat::topology(mesh).index_map(tdim);
  const std::int32_t num_cells = cells->size_local() + cells->num_ghosts();
  std::vector<std::int64_t> vertex_input(tdim + 1);
  for (std::int32_t c = 0; c < num_cells; ++c)
  {
    const auto vertices = cell_vertices(mesh, c);
    const auto nodes = compat::cell_nodes(mesh, c); // P1 geometry: the vertices
    for (int i = 0; i <= tdim; ++i)
      vertex_input[i] = input[nodes[i]];
    for (const std::int32_t dof : V.dofmap()->cell_dofs(c))
      keys[dof] = node_key(std::span(coordinates.data() + 3 * dof, 3), vertices, vertex_input);
  }
  return keys;
}

/// The table row of each key: a vertex's input index (the rows of a P1 run),
/// then the other nodes of every rank in ascending key order. Collective.
std::vector<std::int64_t> rows_of(const std::vector<NodeKey>& keys, std::int64_t vertex_rows,
                                  MPI_Comm comm)
{
  std::vector<std::int64_t> rows(keys.size(), -1), others;
  for (std::size_t i = 0; i < keys.size(); ++i)
  {
    if (keys[i][1] < 0)
      rows[i] = keys[i][0];
    else
      others.insert(others.end(), keys[i].begin(), keys[i].end());
  }
  int size, rank;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  const int count = others.size();
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 0; r < size; ++r)
    offsets[r + 1] = offsets[r] + counts[r];
  std::vector<std::int64_t> all(offsets.back());
  MPI_Allgatherv(others.data(), count, MPI_INT64_T, all.data(), counts.data(), offsets.data(),
                 MPI_INT64_T, comm);
  std::vector<NodeKey> sorted(all.size() / 8);
  for (std::size_t i = 0; i < sorted.size(); ++i)
    std::copy_n(all.data() + 8 * i, 8, sorted[i].begin());
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (rows[i] < 0)
      rows[i] = vertex_rows
                + (std::lower_bound(sorted.begin(), sorted.end(), keys[i]) - sorted.begin());
  return rows;
}

/// The largest input vertex index + 1 (input indices need not be 0..N-1: a
/// file may hold nodes no cell uses). Collective.
std::int64_t vertex_rows(const compat::Mesh& mesh, MPI_Comm comm)
{
  const auto& input = mesh.geometry().input_global_indices();
  std::int64_t last = input.empty() ? -1 : *std::max_element(input.begin(), input.end());
  MPI_Allreduce(MPI_IN_PLACE, &last, 1, MPI_INT64_T, MPI_MAX, comm);
  return last + 1;
}
} // namespace

json StepState::to_json() const
{
  return {{"step", step}, {"nominal_steps", nominal}, {"t", t}, {"k", k},
          {"k_last", k_last}, {"k_J", k_J}, {"events", events}, {"file", file}};
}

StepState StepState::from_json(const json& j)
{
  StepState s;
  s.step = j.at("step").get<int>();
  s.nominal = j.at("nominal_steps").get<int>();
  s.t = j.at("t").get<double>();
  s.k = j.at("k").get<double>();
  s.k_last = j.at("k_last").get<double>();
  s.k_J = j.at("k_J").get<double>();
  s.events = j.at("events").get<std::size_t>();
  s.file = j.at("file").get<std::string>();
  return s;
}

StateFile::StateFile(const Problem& problem) : _comm(problem.comm)
{
  // [u_x, u_y, (u_z,) phi] of x_n, x_{n-1}, x_J per vertex: owned dofs
  // first, then ghosts, of u (columns 0..d-1) and phi (column d)
  const int d = problem.dim();
  _width = d + 1;
  const std::size_t columns = 3 * _width;
  std::vector<std::int32_t> ghost_dofs;
  std::vector<std::int64_t> ghost_slots;
  const std::int64_t vertices = vertex_rows(*problem.mesh, _comm);
  std::int64_t last = vertices - 1;
  for (const auto& [V, dofs, column] :
       {std::tuple{problem.V_u, &problem.u_dofs, 0}, std::tuple{problem.V_phi, &problem.phi_dofs, d}})
  {
    const auto row = rows_of(node_keys(*V), vertices, _comm);
    const int bs = V->dofmap()->index_map_bs();
    const std::size_t owned = V->dofmap()->index_map->size_local();
    for (std::size_t i = 0; i < row.size(); ++i)
    {
      last = std::max(last, row[i]);
      for (int c = 0; c < bs; ++c)
      {
        auto& d = i < owned ? _dofs : ghost_dofs;
        auto& s = i < owned ? _slots : ghost_slots;
        d.push_back((*dofs)[bs * i + c]);
        s.push_back(row[i] * columns + column + c);
      }
    }
  }
  _num_owned = _dofs.size();
  _dofs.insert(_dofs.end(), ghost_dofs.begin(), ghost_dofs.end());
  _slots.insert(_slots.end(), ghost_slots.begin(), ghost_slots.end());
  MPI_Allreduce(MPI_IN_PLACE, &last, 1, MPI_INT64_T, MPI_MAX, _comm);
  _rows = last + 1;

  int size, rank;
  MPI_Comm_size(_comm, &size);
  MPI_Comm_rank(_comm, &rank);
  const int count = _num_owned;
  _counts.resize(rank == 0 ? size : 0);
  MPI_Gather(&count, 1, MPI_INT, _counts.data(), 1, MPI_INT, 0, _comm);
  _offsets.assign(_counts.size() + 1, 0);
  for (std::size_t r = 0; r < _counts.size(); ++r)
    _offsets[r + 1] = _offsets[r] + _counts[r];
  _all_slots.resize(_offsets.back());
  MPI_Gatherv(_slots.data(), count, MPI_INT64_T, _all_slots.data(), _counts.data(),
              _offsets.data(), MPI_INT64_T, 0, _comm);
}

void StateFile::write(const std::filesystem::path& path,
                      std::array<std::span<const double>, 3> states) const
{
  // Each state's owned values in turn: [x_n..., x_{n-1}..., x_J...]
  std::vector<double> values(3 * _num_owned);
  for (int s = 0; s < 3; ++s)
    for (std::size_t i = 0; i < _num_owned; ++i)
      values[s * _num_owned + i] = states[s][_dofs[i]];
  int rank;
  MPI_Comm_rank(_comm, &rank);
  std::vector<int> counts(_counts), offsets(_offsets);
  for (auto& c : counts)
    c *= 3;
  for (auto& o : offsets)
    o *= 3;
  std::vector<double> all(rank == 0 ? offsets.back() : 0);
  MPI_Gatherv(values.data(), values.size(), MPI_DOUBLE, all.data(), counts.data(),
              offsets.data(), MPI_DOUBLE, 0, _comm);
  collectively(_comm, rank == 0,
               [&]
               {
                 std::vector<double> table(_rows * 3 * _width);
                 for (std::size_t r = 0; r < counts.size(); ++r)
                 {
                   const std::size_t n = _counts[r];
                   const double* v = all.data() + offsets[r];
                   const std::int64_t* slot = _all_slots.data() + _offsets[r];
                   for (int s = 0; s < 3; ++s)
                     for (std::size_t i = 0; i < n; ++i)
                       table[slot[i] + _width * s] = v[s * n + i];
                 }
                 write_npy(path, table, _rows, 3 * _width);
               });
}

void StateFile::read(const std::filesystem::path& path, const States& states) const
{
  const auto [table, rows, cols] = read_npy(path);
  const std::size_t columns = 3 * _width;
  if (rows != _rows or cols != columns)
    throw std::runtime_error(path.string() + ": holds " + std::to_string(rows) + " x "
                             + std::to_string(cols) + " values, the mesh needs "
                             + std::to_string(_rows) + " x " + std::to_string(columns));
  for (std::size_t i = 0; i < _dofs.size(); ++i)
    for (int s = 0; s < 3; ++s)
      states[s][_dofs[i]] = table[_slots[i] + _width * s];
}
} // namespace piezocontact
