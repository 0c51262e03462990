#include "diagnostics.h"

#include <cmath>
#include <numeric>

#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/geometry/BoundingBoxTree.h>
#include <dolfinx/geometry/utils.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/utils.h>
#include <limits>
#include <petscvec.h>

namespace piezocontact
{
using namespace dolfinx;
Probes::Probes(const Problem& problem, const std::vector<std::array<double, 3>>& points_,
               const std::string& source)
    : points(points_)
{
  const auto& mesh = *problem.mesh;
  std::vector<double> flat;
  for (const auto& p : points)
    flat.insert(flat.end(), p.begin(), p.end());
  const int tdim = mesh.topology().dim();
  geometry::BoundingBoxTree tree(mesh, tdim);
  const auto candidates = geometry::compute_collisions(tree, flat);
  const auto colliding = geometry::compute_colliding_cells(mesh, candidates, flat);

  int rank, size;
  MPI_Comm_rank(problem.comm, &rank);
  MPI_Comm_size(problem.comm, &size);
  std::vector<std::int32_t> cells(points.size(), -1);
  std::vector<int> have(points.size(), size), owner(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!colliding.links(i).empty())
    {
      cells[i] = colliding.links(i)[0]; // a ghost cell is fine: ghosts are up to date
      have[i] = rank;
    }
  }
  MPI_Allreduce(have.data(), owner.data(), have.size(), MPI_INT, MPI_MIN,
                problem.comm);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (owner[i] == size)
      throw ConfigError(source + ": probes[" + std::to_string(i)
                        + "] = " + json(std::vector<double>(points[i].begin(), points[i].begin() + mesh.geometry().dim())).dump() + ": outside the mesh");
    if (owner[i] == rank)
    {
      _mine.push_back(i);
      _cells.push_back(cells[i]);
    }
  }
}

std::vector<std::array<double, 3>> Probes::evaluate(const Problem& problem) const
{
  std::vector<double> values(3 * points.size(), 0.0);
  if (!_mine.empty())
  {
    std::vector<double> x;
    for (auto i : _mine)
      x.insert(x.end(), points[i].begin(), points[i].end());
    const std::size_t m = _mine.size();
    std::vector<double> u(2 * m), phi(m);
    problem.u->eval(x, {m, 3}, _cells, u, {m, 2});
    problem.phi->eval(x, {m, 3}, _cells, phi, {m, 1});
    for (std::size_t j = 0; j < m; ++j)
    {
      values[3 * _mine[j]] = u[2 * j];
      values[3 * _mine[j] + 1] = u[2 * j + 1];
      values[3 * _mine[j] + 2] = phi[j];
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, values.data(), values.size(), MPI_DOUBLE, MPI_SUM,
                problem.comm);
  std::vector<std::array<double, 3>> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    out[i] = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
  return out;
}

ContactGeometry::ContactGeometry(const Problem& problem)
{
  const auto& mesh = *problem.mesh;
  const int tdim = mesh.topology().dim();
  const auto& chi = problem.model.constants.at("chi")->value;
  std::vector<std::int32_t> facets;
  const auto& idx = problem.model.mesh.facet_tags->indices();
  const auto& val = problem.model.mesh.facet_tags->values();
  for (std::size_t i = 0; i < idx.size(); ++i)
    if (chi.at(val[i] - 1) > 0)
      facets.push_back(idx[i]);
  mesh.topology_mutable().create_connectivity(tdim - 1, tdim);
  const auto f_to_c = mesh.topology().connectivity(tdim - 1, tdim);
  std::vector<std::int32_t> cells;
  for (auto f : facets)
    cells.push_back(f_to_c->links(f)[0]);
  const auto fgeo = mesh::entities_to_geometry(mesh, tdim - 1, facets, false);
  const auto cgeo = mesh::entities_to_geometry(mesh, tdim, cells, false);
  const auto x = mesh.geometry().x(); // (num_nodes, 3)
  for (std::size_t i = 0; i < facets.size(); ++i)
  {
    const double* a = &x[3 * fgeo[2 * i]];
    const double* b = &x[3 * fgeo[2 * i + 1]];
    double cx = 0, cy = 0;
    for (int v = 0; v < 3; ++v)
    {
      cx += x[3 * cgeo[3 * i + v]] / 3.0;
      cy += x[3 * cgeo[3 * i + v] + 1] / 3.0;
    }
    const double tx = b[0] - a[0], ty = b[1] - a[1];
    const double len = std::sqrt(tx * tx + ty * ty);
    std::array<double, 2> n = {ty / len, -tx / len};
    if (n[0] * (a[0] - cx) + n[1] * (a[1] - cy) <= 0)
      n = {-n[0], -n[1]};
    for (const double* v : {a, b})
    {
      _points.insert(_points.end(), {v[0], v[1], 0.0});
      _cells.push_back(cells[i]);
      _normals.push_back(n);
    }
  }
}

std::optional<double> ContactGeometry::max_normal_gap(const Problem& problem,
                                                      double gap) const
{
  double local = -std::numeric_limits<double>::infinity();
  if (!_cells.empty())
  {
    const std::size_t m = _cells.size();
    std::vector<double> u(2 * m);
    problem.u->eval(_points, {m, 3}, _cells, u, {m, 2});
    for (std::size_t j = 0; j < m; ++j)
      local = std::max(local, u[2 * j] * _normals[j][0] + u[2 * j + 1] * _normals[j][1] - gap);
  }
  double largest;
  MPI_Allreduce(&local, &largest, 1, MPI_DOUBLE, MPI_MAX, problem.comm);
  if (largest == -std::numeric_limits<double>::infinity())
    return std::nullopt;
  return largest;
}

std::vector<double> contact_force(const Problem& problem)
{
  std::vector<double> f(problem.model.contact_force.size());
  for (std::size_t i = 0; i < f.size(); ++i)
  {
    const double local = fem::assemble_scalar(*problem.model.contact_force[i]);
    MPI_Allreduce(&local, &f[i], 1, MPI_DOUBLE, MPI_SUM, problem.comm);
  }
  return f;
}

double force_imbalance(const ForceBalance& balance, const std::vector<double>& contact_force,
                       double applied_load)
{
  const auto norm = [](const std::vector<double>& v)
  { return std::sqrt(std::inner_product(v.begin(), v.end(), v.begin(), 0.0)); };
  const double forces = balance.supported + norm(contact_force) + applied_load;
  const double left = norm(balance.unbalanced);
  if (forces == 0.0)
    return std::isfinite(left) ? 0.0 : left;
  return left / forces; // NaN or inf stay so
}

double force_imbalance(const Problem& problem, const ForceBalance& balance,
                       const std::vector<double>& contact_force)
{
  const double quick = force_imbalance(balance, contact_force, 0.0);
  return quick <= balance_tolerance
             ? quick
             : force_imbalance(balance, contact_force, problem.applied_load());
}

std::map<std::string, double> boundary_measures(const Problem& problem)
{
  std::map<std::string, double> out;
  for (const auto& [name, form] : problem.model.boundary_measures)
  {
    const double local = fem::assemble_scalar(*form); // owned facets only
    MPI_Allreduce(&local, &out[name], 1, MPI_DOUBLE, MPI_SUM, problem.comm);
  }
  return out;
}
} // namespace piezocontact
