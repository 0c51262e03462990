#include "problem.h"

#include <algorithm>
#include "config.h"

#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/Vector.h>
#include <cmath>

namespace piezocontact
{
using namespace dolfinx;

Problem::Problem(Model model_, const std::vector<DirichletSettings>& dirichlet,
                 const std::string& source, const std::vector<TimedConstant>& timed)
    : model(std::move(model_)), comm(model.mesh.mesh->comm()), mesh(model.mesh.mesh),
      W(model.W), x(model.x), x_prev(model.x_prev)
{
  // Collapsed sub-spaces and the W-dofs of each field
  auto [Vu, map_u] = W->sub({0})->collapse();
  V_u = std::make_shared<fem::FunctionSpace>(std::move(Vu));
  u_dofs = std::move(map_u);
  auto [Vphi, map_phi] = W->sub({1})->collapse();
  V_phi = std::make_shared<fem::FunctionSpace>(std::move(Vphi));
  phi_dofs = std::move(map_phi);
  u = std::make_shared<fem::Function<double>>(V_u);
  u->name = "u";
  phi = std::make_shared<fem::Function<double>>(V_phi);
  phi->name = "phi";
  if (model.u_exact)
  {
    u_exact = std::make_shared<fem::Function<double>>(V_u);
    u_exact->name = "u_exact";
  }
  if (model.phi_exact)
  {
    phi_exact = std::make_shared<fem::Function<double>>(V_phi);
    phi_exact->name = "phi_exact";
  }
  for (const auto& c : timed)
  {
    if (c.history.kind == History::Kind::constant)
      continue;
    auto& values = (c.boundary.empty() ? model.constants : model.loads.at(c.boundary))
                       .at(c.name)->value;
    _scaled.push_back({std::span(values), values, c.history});
  }
  create_bcs(dirichlet, source);
  set_time(0.0, model.constants.at("k")->value.at(0));
}

void Problem::set_time(double t, double k)
{
  _applied_load = -1.0; // loads may depend on t
  model.constants.at("k")->value = {k};
  if (auto it = model.constants.find("t"); it != model.constants.end())
    it->second->value = {t};
  for (auto& d : _scaled)
  {
    const double f = d.history.factor(t);
    for (std::size_t i = 0; i < d.base.size(); ++i)
      d.values[i] = f * d.base[i];
  }
  if (u_exact)
    u_exact->interpolate(*model.u_exact);
  if (phi_exact)
    phi_exact->interpolate(*model.phi_exact);
}

std::map<std::string, double> Problem::errors() const
{
  std::map<std::string, double> out;
  for (const auto& [name, form] : model.squared_errors)
  {
    double local = fem::assemble_scalar(*form), global = 0.0;
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
    out[name] = std::sqrt(global);
  }
  return out;
}

std::map<std::string, std::vector<double>>
Problem::reactions(std::span<const double> r) const
{
  std::map<std::string, std::vector<double>> out;
  for (const auto& [name, comps] : clamped_dofs)
  {
    std::vector<double> local(comps.size(), 0.0);
    for (std::size_t i = 0; i < comps.size(); ++i)
      for (auto d : comps[i])
        if (d < std::int32_t(r.size()))
          local[i] += r[d];
    auto& global = out[name];
    global.resize(local.size());
    MPI_Allreduce(local.data(), global.data(), local.size(), MPI_DOUBLE, MPI_SUM, comm);
  }
  return out;
}

// At a Dirichlet dof the lifting adds A(g - x), zero once x holds the
// boundary values: the assembled F alone is the unconstrained residual
std::map<std::string, std::vector<double>> Problem::reactions() const
{
  const auto& imap = *W->dofmap()->index_map;
  const int bs = W->dofmap()->index_map_bs();
  const auto r = assemble(model.F);
  return reactions(r.array().subspan(0, imap.size_local() * bs));
}

ForceBalance Problem::force_balance(std::span<const double> r) const
{
  std::vector<std::int32_t> constrained = bc_dofs;
  std::sort(constrained.begin(), constrained.end());
  const int dim = V_u->dofmap()->index_map_bs();
  std::vector<double> local(dim + 1, 0.0), global(dim + 1); // resultant, then supported
  for (std::size_t i = 0; i < u_dofs.size(); ++i)
  {
    const std::int32_t d = u_dofs[i];
    if (d >= std::int32_t(r.size()))
      continue;
    if (std::binary_search(constrained.begin(), constrained.end(), d))
      local[dim] += std::abs(r[d]);
    else
      local[i % dim] += r[d];
  }
  MPI_Allreduce(local.data(), global.data(), dim + 1, MPI_DOUBLE, MPI_SUM, comm);
  return {std::vector<double>(global.begin(), global.begin() + dim), global[dim]};
}

ForceBalance Problem::force_balance() const
{
  const int bs = W->dofmap()->index_map_bs();
  const auto r = assemble(model.F);
  return force_balance(r.array().subspan(0, W->dofmap()->index_map->size_local() * bs));
}

double Problem::load_sum() const
{
  const int bs = W->dofmap()->index_map_bs();
  const auto L = assemble(model.L);
  std::vector<std::int32_t> constrained = bc_dofs;
  std::sort(constrained.begin(), constrained.end());
  double local = 0.0, global = 0.0;
  const auto a = L.array();
  const std::int32_t owned = W->dofmap()->index_map->size_local() * bs;
  for (const std::int32_t d : u_dofs)
    if (d < owned and !std::binary_search(constrained.begin(), constrained.end(), d))
      local += std::abs(a[d]);
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

// With histories, the loads' amplitude (every timed datum at factor 1)
// keeps the scale where a varying load passes through zero: the round-off
// of the internal forces (elastic and viscous, cancelling) is measured
// against the forces of the run, not against a momentary zero
double Problem::applied_load() const
{
  if (_applied_load >= 0.0 or model.L.empty())
    return std::max(_applied_load, 0.0);
  _applied_load = load_sum();
  if (!_scaled.empty())
  {
    if (_load_amplitude < 0.0)
    {
      std::vector<std::vector<double>> now;
      for (auto& d : _scaled)
      {
        now.emplace_back(d.values.begin(), d.values.end());
        std::copy(d.base.begin(), d.base.end(), d.values.begin());
      }
      _load_amplitude = load_sum();
      for (std::size_t i = 0; i < _scaled.size(); ++i)
        std::copy(now[i].begin(), now[i].end(), _scaled[i].values.begin());
    }
    _applied_load = std::max(_applied_load, _load_amplitude);
  }
  return _applied_load;
}

la::Vector<double> Problem::assemble(const FormList& terms) const
{
  la::Vector<double> b(W->dofmap()->index_map, W->dofmap()->index_map_bs());
  for (const auto& term : terms)
    fem::assemble_vector(b.mutable_array(), *term);
  b.scatter_rev(std::plus<double>());
  return b;
}

// u and phi Dirichlet conditions on the collapsed sub-spaces (a Constant on a
// vector sub-space of a mixed space throws in 0.5.2).
void Problem::create_bcs(const std::vector<DirichletSettings>& dirichlet,
                         const std::string& source)
{
  const int fdim = mesh->topology().dim() - 1;
  for (const auto& bc : dirichlet)
  {
    if (!model.mesh.tag_of.contains(bc.boundary))
    {
      std::string have;
      for (const auto& [m, _] : model.mesh.tag_of)
        have += (have.empty() ? "" : ", ") + m;
      throw ConfigError(source + ": boundaries." + bc.boundary + ": the mesh has no boundary '"
                        + bc.boundary + "' (it has: " + have + ")");
    }
    const auto facets = model.mesh.boundary_facets(bc.boundary);
    if (bc.displacement or bc.displacement_exact)
    {
      std::shared_ptr<fem::Function<double>> g = u_exact; // updated every step
      const int dim = V_u->dofmap()->index_map_bs();
      std::vector<bool> fixed(dim, true);
      if (!bc.displacement_exact)
      {
        g = std::make_shared<fem::Function<double>>(V_u);
        auto values = g->x()->mutable_array();
        for (int i = 0; i < dim; ++i)
        {
          const auto& c = bc.displacement->at(i);
          fixed[i] = c.has_value();
          for (std::size_t j = i; j < values.size(); j += dim)
            values[j] = c.value_or(0.0);
        }
      }
      if (!g)
        throw ConfigError(source + ": boundaries." + bc.boundary
                          + ".displacement: \"exact\" needs a manufactured solution");
      scale_in_time(g, bc.displacement_history);
      // one condition per fixed component, its values taken from g on V_u
      // (W->sub({0, i}) is not W.sub(0).sub(i) in 0.5.2: chain single levels)
      auto& comp = clamped_dofs[bc.boundary];
      comp.assign(dim, {});
      for (int i = 0; i < dim; ++i)
      {
        if (!fixed[i])
          continue; // free: no reaction along it
        auto Wi = W->sub({0})->sub({i});
        auto dofs = fem::locate_dofs_topological({*Wi, *V_u->sub({i})}, fdim, facets);
        comp[i] = dofs[0];
        bc_dofs.insert(bc_dofs.end(), dofs[0].begin(), dofs[0].end());
        bcs.push_back(std::make_shared<fem::DirichletBC<double>>(g, std::move(dofs), Wi));
      }
    }
    if (bc.potential or bc.potential_exact)
    {
      std::shared_ptr<fem::Function<double>> g = phi_exact; // updated every step
      if (!bc.potential_exact)
      {
        g = std::make_shared<fem::Function<double>>(V_phi);
        std::fill(g->x()->mutable_array().begin(), g->x()->mutable_array().end(),
                  *bc.potential);
      }
      if (!g)
        throw ConfigError(source + ": boundaries." + bc.boundary
                          + ".potential: \"exact\" needs a manufactured solution");
      scale_in_time(g, bc.potential_history);
      auto dofs = fem::locate_dofs_topological({*W->sub({1}), *V_phi}, fdim, facets);
      bc_dofs.insert(bc_dofs.end(), dofs[0].begin(), dofs[0].end());
      bcs.push_back(std::make_shared<fem::DirichletBC<double>>(g, std::move(dofs), W->sub({1})));
    }
  }
}

void Problem::scale_in_time(const std::shared_ptr<fem::Function<double>>& g,
                            const History& history)
{
  if (history.kind == History::Kind::constant)
    return;
  _scaled_bc_values.push_back(g); // kept alive with its values
  const auto values = g->x()->mutable_array();
  _scaled.push_back({values, std::vector<double>(values.begin(), values.end()), history});
}

void Problem::update_fields()
{
  auto xa = x->x()->array();
  auto ua = u->x()->mutable_array();
  auto pa = phi->x()->mutable_array();
  for (std::size_t i = 0; i < u_dofs.size(); ++i)
    ua[i] = xa[u_dofs[i]];
  for (std::size_t i = 0; i < phi_dofs.size(); ++i)
    pa[i] = xa[phi_dofs[i]];
}
} // namespace piezocontact
