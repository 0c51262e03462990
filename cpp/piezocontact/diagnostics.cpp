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
  const auto tree = compat::cell_tree(mesh);
  const auto candidates = geometry::compute_collisions(tree, std::span<const double>(flat));
  const auto colliding
      = geometry::compute_colliding_cells(mesh, candidates, std::span<const double>(flat));

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

std::vector<std::vector<double>> Probes::evaluate(const Problem& problem) const
{
  const std::size_t d = problem.dim(), w = d + 1; // [u..., phi] per probe
  std::vector<double> values(w * points.size(), 0.0);
  if (!_mine.empty())
  {
    std::vector<double> x;
    for (auto i : _mine)
      x.insert(x.end(), points[i].begin(), points[i].end());
    const std::size_t m = _mine.size();
    std::vector<double> u(d * m), phi(m);
    compat::eval(*problem.u, x, _cells, u, d);
    compat::eval(*problem.phi, x, _cells, phi, 1);
    for (std::size_t j = 0; j < m; ++j)
    {
      std::copy_n(u.begin() + d * j, d, values.begin() + w * _mine[j]);
      values[w * _mine[j] + d] = phi[j];
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, values.data(), values.size(), MPI_DOUBLE, MPI_SUM,
                problem.comm);
  std::vector<std::vector<double>> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    out[i].assign(values.begin() + w * i, values.begin() + w * (i + 1));
  return out;
}

namespace
{
/// Unit normal of a facet (2 vertices in 2D, 3 in 3D) pointing away from
/// the point c inside its cell
std::array<double, 3> outward_normal(const std::vector<const double*>& v, const double* c)
{
  std::array<double, 3> n;
  const std::array<double, 3> a = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
  if (v.size() == 2)
    n = {a[1], -a[0], 0.0};
  else
  {
    const std::array<double, 3> b = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
    n = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  }
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  double side = 0.0;
  for (int i = 0; i < 3; ++i)
  {
    n[i] /= len;
    side += n[i] * (v[0][i] - c[i]);
  }
  if (side < 0)
    for (double& ni : n)
      ni = -ni;
  return n;
}
} // namespace

ContactGeometry::ContactGeometry(const Problem& problem, std::span<const std::int32_t> facets)
{
  const auto& mesh = *problem.mesh;
  const int tdim = compat::topology(mesh).dim();
  // (0.9's entities_to_geometry needs both directions)
  compat::topology_mutable(mesh).create_connectivity(tdim - 1, tdim);
  compat::topology_mutable(mesh).create_connectivity(tdim, tdim - 1);
  const auto f_to_c = compat::topology(mesh).connectivity(tdim - 1, tdim);
  std::vector<std::int32_t> cells;
  for (auto f : facets)
    cells.push_back(f_to_c->links(f)[0]);
  const auto fgeo = compat::entities_to_geometry(mesh, tdim - 1, facets);
  const auto cgeo = compat::entities_to_geometry(mesh, tdim, cells);
  const std::size_t nf = tdim, nc = tdim + 1; // vertices of a facet, of a cell
  const auto x = mesh.geometry().x(); // (num_nodes, 3)
  for (std::size_t i = 0; i < facets.size(); ++i)
  {
    std::vector<const double*> v;
    for (std::size_t j = 0; j < nf; ++j)
      v.push_back(&x[3 * fgeo[nf * i + j]]);
    std::array<double, 3> c = {0, 0, 0};
    for (std::size_t j = 0; j < nc; ++j)
      for (int k = 0; k < 3; ++k)
        c[k] += x[3 * cgeo[nc * i + j] + k] / nc;
    const auto n = outward_normal(v, c.data());
    for (const double* p : v)
    {
      _points.insert(_points.end(), p, p + 3);
      _cells.push_back(cells[i]);
      _normals.push_back(n);
    }
  }
}

std::optional<double>
ContactGeometry::max_normal_gap(const Problem& problem, double gap,
                                const dolfinx::fem::Function<double>* gap_field) const
{
  double local = -std::numeric_limits<double>::infinity();
  if (!_cells.empty())
  {
    const std::size_t m = _cells.size(), d = problem.dim();
    std::vector<double> u(d * m), g(m, 0.0);
    compat::eval(*problem.u, _points, _cells, u, d);
    // a gap given by an expression: its field, the Constant being zero
    if (gap_field)
      compat::eval(*gap_field, _points, _cells, g, 1);
    for (std::size_t j = 0; j < m; ++j)
    {
      double un = 0.0;
      for (std::size_t i = 0; i < d; ++i)
        un += u[d * j + i] * _normals[j][i];
      local = std::max(local, un - gap - g[j]);
    }
  }
  double largest;
  MPI_Allreduce(&local, &largest, 1, MPI_DOUBLE, MPI_MAX, problem.comm);
  if (largest == -std::numeric_limits<double>::infinity())
    return std::nullopt;
  return largest;
}

namespace
{
/// Each functional of `forms` assembled and summed over the ranks
std::vector<double> assemble_each(const FormList& forms, MPI_Comm comm)
{
  std::vector<double> f(forms.size());
  for (std::size_t i = 0; i < f.size(); ++i)
  {
    const double local = fem::assemble_scalar(*forms[i]);
    MPI_Allreduce(&local, &f[i], 1, MPI_DOUBLE, MPI_SUM, comm);
  }
  return f;
}
} // namespace

std::vector<double> obstacle_force(const Problem& problem, const std::string& boundary)
{
  std::vector<double> f;
  for (const auto& terms : problem.model.obstacles.at(boundary).force)
  {
    const auto each = assemble_each(terms, problem.comm);
    f.push_back(std::accumulate(each.begin(), each.end(), 0.0));
  }
  return f;
}

double obstacle_contact_measure(const Problem& problem, const std::string& boundary)
{
  const auto each = assemble_each(problem.model.obstacles.at(boundary).contact_measure,
                                  problem.comm);
  return std::accumulate(each.begin(), each.end(), 0.0);
}

std::vector<double> contact_force(const Problem& problem)
{
  auto f = assemble_each(problem.model.contact_force, problem.comm);
  for (const auto& [name, _] : problem.model.obstacles)
  {
    const auto g = obstacle_force(problem, name);
    f.resize(std::max(f.size(), g.size()), 0.0);
    for (std::size_t i = 0; i < g.size(); ++i)
      f[i] += g[i];
  }
  return f;
}

namespace
{
/// Whether a contact boundary's data give an obstacle's geometry (a plane's
/// normal, a sphere's or a cylinder's radius), or the paper's foundation
bool has_geometry(const ConstantMap& data)
{
  const auto nonzero = [&](const char* name)
  {
    const auto& v = data.at(name)->value;
    return std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; });
  };
  return nonzero("plane_N") or nonzero("sphere_R") or nonzero("cylinder_R");
}
} // namespace

ObstaclePenetration::ObstaclePenetration(const Problem& problem)
{
  if (problem.model.obstacles.empty())
    return;
  const auto& mesh = *problem.mesh;
  const int tdim = compat::topology(mesh).dim();
  compat::topology_mutable(mesh).create_connectivity(tdim - 1, tdim);
  const auto f_to_c = compat::topology(mesh).connectivity(tdim - 1, tdim);
  // a component of u's space: the scalar space of its nodes
  auto [V, _] = compat::collapse(*compat::sub(*problem.V_u, 0));
  _r = std::make_shared<fem::Function<double>>(
      std::make_shared<compat::FunctionSpace>(std::move(V)));
  for (const auto& [name, contact] : problem.model.obstacles)
  {
    if (!has_geometry(problem.model.loads.at(name)))
    {
      _offset.emplace(name, ContactGeometry(problem, problem.model.mesh.boundary_facets(name)));
      continue;
    }
    for (const auto& p : contact.penetration)
    {
      Part part{{}, {}, p.expression};
      for (auto f : p.facets)
        part.cells.push_back(f_to_c->links(f)[0]);
      std::sort(part.cells.begin(), part.cells.end());
      part.cells.erase(std::unique(part.cells.begin(), part.cells.end()), part.cells.end());
      // every node of the facets here, ghosts too: a node's owner may not
      // hold a facet of the boundary (a maximum may count a node twice)
      part.dofs = compat::locate_nodes(*_r->function_space(), tdim - 1, p.facets);
      _parts[name].push_back(std::move(part));
    }
  }
}

std::optional<double> ObstaclePenetration::largest(const Problem& problem,
                                                   const std::string& boundary) const
{
  if (auto offset = _offset.find(boundary); offset != _offset.end())
  {
    const auto fields = problem.model.load_data_fields.find(boundary);
    const fem::Function<double>* field = nullptr;
    if (fields != problem.model.load_data_fields.end())
      if (auto g = fields->second.find("g_o"); g != fields->second.end())
        field = g->second.get();
    return offset->second.max_normal_gap(
        problem, problem.model.loads.at(boundary).at("g_o")->value[0], field);
  }
  double local = -std::numeric_limits<double>::infinity();
  if (auto parts = _parts.find(boundary); parts != _parts.end())
    for (const auto& part : parts->second)
    {
      _r->interpolate(*part.expression, part.cells);
      const auto r = compat::values(*_r->x());
      for (auto dof : part.dofs)
        local = std::max(local, r[dof]);
    }
  double largest;
  MPI_Allreduce(&local, &largest, 1, MPI_DOUBLE, MPI_MAX, problem.comm);
  if (largest == -std::numeric_limits<double>::infinity())
    return std::nullopt;
  return largest;
}

std::map<std::string, std::vector<double>> spring_forces(const Problem& problem)
{
  std::map<std::string, std::vector<double>> out;
  for (const auto& [name, forms] : problem.model.spring_force)
    out[name] = assemble_each(forms, problem.comm);
  return out;
}

namespace
{
double norm(const std::vector<double>& v)
{
  return std::sqrt(std::inner_product(v.begin(), v.end(), v.begin(), 0.0));
}
} // namespace

double contact_forces_in_play(const Problem& problem)
{
  double sum = norm(assemble_each(problem.model.contact_force, problem.comm));
  for (const auto& [name, _] : problem.model.obstacles)
    sum += norm(obstacle_force(problem, name));
  return sum;
}

double force_imbalance(const ForceBalance& balance, double contact_forces, double applied_load)
{
  const double forces = balance.supported + contact_forces + applied_load;
  const double left = norm(balance.unbalanced);
  if (forces == 0.0)
    return std::isfinite(left) ? 0.0 : left;
  return left / forces; // NaN or inf stay so
}

double force_imbalance(const Problem& problem, const ForceBalance& balance)
{
  const double contact = contact_forces_in_play(problem);
  const double quick = force_imbalance(balance, contact, 0.0);
  return quick <= balance_tolerance ? quick
                                    : force_imbalance(balance, contact, problem.applied_load());
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
