#include "checkpoint.h"
#include "output.h"

#include <algorithm>

namespace piezo
{
namespace
{
constexpr int columns = 9; // [u_x, u_y, phi] of x_n, x_{n-1}, x_J

/// Input (file) index of the vertex of each local dof (owned and ghost) of a
/// P1 space: P1 dofs and P1 geometry nodes follow the same cell-local order
std::vector<std::int64_t> input_vertex_of_dofs(const fem::FunctionSpace& V)
{
  const auto& mesh = *V.mesh();
  const auto& imap = *V.dofmap()->index_map;
  std::vector<std::int64_t> vertex(imap.size_local() + imap.num_ghosts(), -1);
  const auto& x_dofmap = mesh.geometry().dofmap();
  const auto& input = mesh.geometry().input_global_indices();
  const int tdim = mesh.topology().dim();
  const auto cells = mesh.topology().index_map(tdim);
  const std::int32_t num_cells = cells->size_local() + cells->num_ghosts();
  for (std::int32_t c = 0; c < num_cells; ++c)
  {
    const auto nodes = x_dofmap.links(c);
    const auto dofs = V.dofmap()->cell_dofs(c);
    for (std::size_t j = 0; j < dofs.size(); ++j)
      vertex[dofs[j]] = input[nodes[j]];
  }
  return vertex;
}

/// Rows of the table: input indices need not be 0..N-1 (a file may hold
/// nodes no cell uses), so the largest one sets the size. Collective.
std::size_t table_rows(const fem::FunctionSpace& V, MPI_Comm comm)
{
  const auto vertex = input_vertex_of_dofs(V);
  std::int64_t last = vertex.empty() ? -1 : *std::max_element(vertex.begin(), vertex.end());
  MPI_Allreduce(MPI_IN_PLACE, &last, 1, MPI_INT64_T, MPI_MAX, comm);
  return last + 1;
}

/// (space, its W-dofs, first column of the field)
struct Field
{
  const fem::FunctionSpace& V;
  const std::vector<std::int32_t>& dofs;
  int column;
};
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

void write_states(const std::filesystem::path& path, const Problem& problem,
                  std::array<std::span<const double>, 3> states)
{
  // Rows [vertex, column, values of the 3 states] of owned dofs
  std::vector<double> rows;
  for (const Field& f : {Field{*problem.V_u, problem.u_dofs, 0},
                         Field{*problem.V_phi, problem.phi_dofs, 2}})
  {
    const auto vertex = input_vertex_of_dofs(f.V);
    const int bs = f.V.dofmap()->index_map_bs();
    const std::int32_t owned = f.V.dofmap()->index_map->size_local();
    for (std::int32_t i = 0; i < owned; ++i)
      for (int c = 0; c < bs; ++c)
      {
        rows.insert(rows.end(), {double(vertex[i]), double(f.column + c)});
        for (const auto& x : states)
          rows.push_back(x[f.dofs[bs * i + c]]);
      }
  }
  int size, rank;
  MPI_Comm_size(problem.comm, &size);
  MPI_Comm_rank(problem.comm, &rank);
  const int count = rows.size();
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, problem.comm);
  for (int r = 0; r < size; ++r)
    offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> all(rank == 0 ? offsets[size] : 0);
  MPI_Gatherv(rows.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
              MPI_DOUBLE, 0, problem.comm);
  const std::size_t num_vertices = table_rows(*problem.V_phi, problem.comm);
  collectively(problem.comm, rank == 0,
               [&]
               {
                 std::vector<double> table(num_vertices * columns);
                 for (std::size_t r = 0; r < all.size(); r += 5)
                 {
                   const auto v = std::size_t(all[r]);
                   const int c = int(all[r + 1]);
                   for (int s = 0; s < 3; ++s)
                     table[v * columns + 3 * s + c] = all[r + 2 + s];
                 }
                 write_npy(path, table, num_vertices, columns);
               });
}

void read_states(const std::filesystem::path& path, const Problem& problem,
                 const States& states)
{
  const auto [table, rows, cols] = read_npy(path);
  const std::size_t num_vertices = table_rows(*problem.V_phi, problem.comm);
  if (rows != num_vertices or cols != columns)
    throw std::runtime_error(path.string() + ": holds " + std::to_string(rows) + " x "
                             + std::to_string(cols) + " values, the mesh needs "
                             + std::to_string(num_vertices) + " x "
                             + std::to_string(columns));
  for (const Field& f : {Field{*problem.V_u, problem.u_dofs, 0},
                         Field{*problem.V_phi, problem.phi_dofs, 2}})
  {
    const auto vertex = input_vertex_of_dofs(f.V);
    const int bs = f.V.dofmap()->index_map_bs();
    for (std::size_t i = 0; i < vertex.size(); ++i)
      for (int c = 0; c < bs; ++c)
        for (int s = 0; s < 3; ++s)
          states[s][f.dofs[bs * i + c]] = table[vertex[i] * columns + 3 * s + f.column + c];
  }
}
} // namespace piezo
