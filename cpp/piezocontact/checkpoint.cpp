#include "checkpoint.h"
#include "output.h"

#include <algorithm>

namespace piezocontact
{
using namespace dolfinx;
namespace
{

/// Input (file) index of the vertex of each local dof (owned and ghost) of a
/// P1 space: P1 dofs and P1 geometry nodes follow the same cell-local order
std::vector<std::int64_t> input_vertex_of_dofs(const compat::FunctionSpace& V)
{
  const auto& mesh = *V.mesh();
  const auto& imap = *V.dofmap()->index_map;
  std::vector<std::int64_t> vertex(imap.size_local() + imap.num_ghosts(), -1);
  const auto& input = mesh.geometry().input_global_indices();
  const int tdim = compat::topology(mesh).dim();
  const auto cells = compat::topology(mesh).index_map(tdim);
  const std::int32_t num_cells = cells->size_local() + cells->num_ghosts();
  for (std::int32_t c = 0; c < num_cells; ++c)
  {
    const auto nodes = compat::cell_nodes(mesh, c);
    const auto dofs = V.dofmap()->cell_dofs(c);
    for (std::size_t j = 0; j < dofs.size(); ++j)
      vertex[dofs[j]] = input[nodes[j]];
  }
  return vertex;
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
  std::int64_t last = -1;
  for (const auto& [V, dofs, column] :
       {std::tuple{problem.V_u, &problem.u_dofs, 0}, std::tuple{problem.V_phi, &problem.phi_dofs, d}})
  {
    const auto vertex = input_vertex_of_dofs(*V);
    const int bs = V->dofmap()->index_map_bs();
    const std::size_t owned = V->dofmap()->index_map->size_local();
    for (std::size_t i = 0; i < vertex.size(); ++i)
    {
      last = std::max(last, vertex[i]);
      for (int c = 0; c < bs; ++c)
      {
        auto& d = i < owned ? _dofs : ghost_dofs;
        auto& s = i < owned ? _slots : ghost_slots;
        d.push_back((*dofs)[bs * i + c]);
        s.push_back(vertex[i] * columns + column + c);
      }
    }
  }
  _num_owned = _dofs.size();
  _dofs.insert(_dofs.end(), ghost_dofs.begin(), ghost_dofs.end());
  _slots.insert(_slots.end(), ghost_slots.begin(), ghost_slots.end());
  // Input indices need not be 0..N-1 (a file may hold nodes no cell uses)
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
