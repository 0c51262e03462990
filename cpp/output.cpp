#include "output.h"

#include <basix/finite-element.h>
#include <cstdio>
#include <dolfinx/fem/utils.h>
#include <fstream>

namespace piezo
{
namespace
{
int rank_of(MPI_Comm comm)
{
  int r;
  MPI_Comm_rank(comm, &r);
  return r;
}

/// [x, y, values...] of the owned dofs of a collapsed P1 function, on rank 0
std::pair<std::vector<double>, std::size_t>
gather_nodal(const fem::Function<double>& f, MPI_Comm comm)
{
  const auto& V = *f.function_space();
  const int n = V.dofmap()->index_map->size_local();
  const int bs = V.dofmap()->index_map_bs();
  const std::size_t cols = 2 + bs;
  const auto coords = V.tabulate_dof_coordinates(false); // (num_dofs, 3)
  const auto values = f.x()->array();
  std::vector<double> rows;
  rows.reserve(n * cols);
  for (int i = 0; i < n; ++i)
  {
    rows.insert(rows.end(), {coords[3 * i], coords[3 * i + 1]});
    for (int c = 0; c < bs; ++c)
      rows.push_back(values[bs * i + c]);
  }
  int size;
  MPI_Comm_size(comm, &size);
  const int count = rows.size();
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  for (int r = 0; r < size; ++r)
    offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> all(rank_of(comm) == 0 ? offsets[size] : 0);
  MPI_Gatherv(rows.data(), count, MPI_DOUBLE, all.data(), counts.data(),
              offsets.data(), MPI_DOUBLE, 0, comm);
  return {all, cols};
}
} // namespace

void write_json_atomic(const std::filesystem::path& path, const json& value)
{
  const auto tmp = path.parent_path() / ("." + path.filename().string() + ".tmp");
  {
    std::ofstream out(tmp);
    out << value.dump(1) << "\n";
    if (!out)
      throw std::runtime_error("cannot write " + tmp.string());
  }
  std::filesystem::rename(tmp, path);
}

void write_npy(const std::filesystem::path& path, const std::vector<double>& data,
               std::size_t rows, std::size_t cols)
{
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': ("
                       + std::to_string(rows) + ", " + std::to_string(cols) + "), }";
  // magic(6) + version(2) + length(2) + header, padded to 64 bytes with '\n'
  header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
  header += '\n';
  std::ofstream out(path, std::ios::binary);
  out.write("\x93NUMPY\x01\x00", 8);
  const std::uint16_t len = header.size();
  out.put(static_cast<char>(len & 0xff));
  out.put(static_cast<char>(len >> 8));
  out << header;
  out.write(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(double));
  if (!out)
    throw std::runtime_error("cannot write " + path.string());
}

Writer::Writer(const Problem& problem, const std::filesystem::path& dir)
    : _problem(problem), _dir(dir)
{
  const json& out = problem.cfg["output"];
  _nodal = out["nodal"].get<std::string>();
  if (rank_of(problem.comm) == 0)
    std::filesystem::create_directories(dir / "nodal");
  MPI_Barrier(problem.comm);
  if (out["xdmf"].get<bool>())
  {
    const auto dg0 = basix::create_element(
        basix::element::family::P, basix::cell::type::triangle, 0,
        basix::element::lagrange_variant::unset, true);
    auto mesh = problem.mesh;
    _D = std::make_shared<fem::Function<double>>(std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(mesh, dg0, 2)));
    _D->name = "D";
    _stress = std::make_shared<fem::Function<double>>(
        std::make_shared<fem::FunctionSpace>(fem::create_functionspace(mesh, dg0, 3)));
    _stress->name = "stress_voigt";
    _xdmf = dir / "solution.xdmf";
    io::XDMFFile f(problem.comm, _xdmf, "w");
    f.write_mesh(*mesh);
    f.close();
  }
}

void Writer::write_step(int step, double t, bool final)
{
  if (!_xdmf.empty())
  {
    _D->interpolate(*_problem.D_expr);
    _stress->interpolate(*_problem.stress_expr);
    // open and close at every step: a killed run leaves a file that is
    // complete up to its last step (HDF5 flushed, XML rewritten)
    io::XDMFFile xdmf(_problem.comm, _xdmf, "a");
    for (const auto& f : {_problem.u, _problem.phi, _D, _stress})
      xdmf.write_function(*f, t);
    xdmf.close();
  }
  if (_nodal == "all" or (_nodal == "final" and final))
  {
    char num[16];
    std::snprintf(num, sizeof(num), "%04d", step);
    for (const auto& [name, f] : {std::pair{"u", _problem.u}, std::pair{"phi", _problem.phi}})
    {
      const auto [rows, cols] = gather_nodal(*f, _problem.comm);
      if (rank_of(_problem.comm) == 0)
        write_npy(_dir / "nodal" / (std::string(name) + "_" + num + ".npy"), rows,
                  rows.size() / cols, cols);
    }
  }
}
} // namespace piezo
