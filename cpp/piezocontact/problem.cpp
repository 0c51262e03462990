#include "problem.h"

#include <algorithm>
#include "config.h"
#include "json_input.h"

#include <limits>
#include <numeric>

#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/Vector.h>
#include <cmath>

namespace piezocontact
{
using namespace dolfinx;

namespace
{
std::shared_ptr<fem::Function<double>> named_function(std::shared_ptr<compat::FunctionSpace> V,
                                                      const std::string& name)
{
  auto f = std::make_shared<fem::Function<double>>(V);
  f->name = name;
  return f;
}

/// The contact boundary's forms on some rank, or an obstacle's: a pressure
/// field to fill
bool has_contact(const Model& model)
{
  std::int64_t facets = model.contact_facets.size();
  MPI_Allreduce(MPI_IN_PLACE, &facets, 1, MPI_INT64_T, MPI_SUM, model.mesh.mesh->comm());
  return (model.contact_pressure_load and model.contact_nodal_area and facets > 0)
         or !model.obstacles.empty();
}
} // namespace

Problem::Collapsed Problem::collapse(const compat::FunctionSpace& W, int i)
{
  auto [V, dofs] = compat::collapse(*compat::sub(W, i));
  return {std::make_shared<compat::FunctionSpace>(std::move(V)), std::move(dofs)};
}

Problem::Problem(Model model_, const std::vector<DirichletSettings>& dirichlet,
                 const std::string& source, const std::vector<TimedConstant>& timed,
                 const std::vector<SpatialLoad>& spatial)
    : Problem(std::move(model_), collapse(*model_.W, 0), collapse(*model_.W, 1), dirichlet,
              source, timed, spatial)
{
}

// model_ is an rvalue reference: it is moved from only by the first
// initialiser, after the collapses above were evaluated
Problem::Problem(Model&& model_, Collapsed u_, Collapsed phi_,
                 const std::vector<DirichletSettings>& dirichlet, const std::string& source,
                 const std::vector<TimedConstant>& timed, const std::vector<SpatialLoad>& spatial)
    : model(std::move(model_)), comm(model.mesh.mesh->comm()), mesh(model.mesh.mesh),
      W(model.W), V_u(u_.V), V_phi(phi_.V), u_dofs(std::move(u_.dofs)),
      phi_dofs(std::move(phi_.dofs)), x(model.x), x_prev(model.x_prev),
      u(named_function(V_u, "u")), phi(named_function(V_phi, "phi")),
      u_exact(model.u_exact ? named_function(V_u, "u_exact") : nullptr),
      phi_exact(model.phi_exact ? named_function(V_phi, "phi_exact") : nullptr),
      contact_pressure(has_contact(model) ? named_function(
                           std::const_pointer_cast<compat::FunctionSpace>(model.P),
                           "contact_pressure")
                                          : nullptr)
{
  for (const auto& c : timed)
  {
    if (c.history.kind == History::Kind::constant)
      continue;
    auto& values = (c.boundary.empty() ? model.constants : model.loads.at(c.boundary))
                       .at(c.name)->value;
    _scaled.push_back({std::span(values), values, c.history});
  }
  _source = source;
  _extent = extent();
  for (const auto& s : spatial) // a boundary's data on its nodes, the shared ones everywhere
  {
    const auto facets = s.boundary.empty() ? std::vector<std::int32_t>{}
                                           : model.mesh.boundary_facets(s.boundary);
    place_spatial(s.boundary.empty() ? model.data_fields.at(s.name)
                                     : model.load_data_fields.at(s.boundary).at(s.name),
                  s.datum, s.boundary.empty() ? nullptr : &facets);
  }
  create_bcs(dirichlet, source);
  check_electrodes_apart(source);
  set_time(0.0, model.constants.at("k")->value.at(0));
}

void Problem::set_time(double t, double k)
{
  _t = t;
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
  if (t > 0) // from the first step on: nothing is solved at t = 0 ("1/t" is a datum)
    for (const auto& e : _evolving)
      evaluate(e, t, e.datum.history.factor(t));
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
  for (const auto& [name, comps] : _clamped_dofs)
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
  return reactions(compat::values(r).subspan(0, imap.size_local() * bs));
}

ForceBalance Problem::force_balance(std::span<const double> r) const
{
  std::vector<std::int32_t> constrained = _bc_dofs;
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
  return force_balance(compat::values(r).subspan(0, W->dofmap()->index_map->size_local() * bs));
}

double Problem::load_sum() const
{
  const int bs = W->dofmap()->index_map_bs();
  const auto L = assemble(model.L);
  std::vector<std::int32_t> constrained = _bc_dofs;
  std::sort(constrained.begin(), constrained.end());
  double local = 0.0, global = 0.0;
  const auto a = compat::values(L);
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
  // loads that vary in time by expressions (or by a hook of t outside a
  // manufactured run) have no amplitude to know in advance: the largest
  // seen so far keeps the scale when they pass through zero
  if (!_evolving.empty() or (model.constants.count("t") and model.squared_errors.empty()))
  {
    _load_peak = std::max(_load_peak, _applied_load);
    _applied_load = _load_peak;
  }
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
  // the terms' test space (W, or the contact pressure's P)
  const auto& V = terms.empty() ? *W : *terms.front()->function_spaces().at(0);
  la::Vector<double> b(V.dofmap()->index_map, V.dofmap()->index_map_bs());
  for (const auto& term : terms)
    fem::assemble_vector(compat::mutable_values(b), *term);
  b.scatter_rev(std::plus<double>());
  return b;
}

// In axisymmetry u_r = 0 on the axis: the hoop strain u_r / r stays finite
// (the facets on x = 0, to round-off of the mesh's size)
void Problem::fix_on_axis()
{
  const int fdim = compat::topology(*mesh).dim() - 1;
  const double tol = 1e-12 * _extent;
  const auto facets = compat::locate_boundary_facets(
      *mesh, [tol](double x, double, double) { return std::abs(x) <= tol; });
  auto zero = std::make_shared<fem::Function<double>>(V_u);
  auto Wr = compat::sub(*compat::sub(*W, 0), 0);
  auto dofs = compat::locate_dofs_topological(*Wr, *compat::sub(*V_u, 0), fdim, facets);
  _bc_dofs.insert(_bc_dofs.end(), dofs[0].begin(), dofs[0].end());
  _bcs.push_back(std::make_shared<fem::DirichletBC<double>>(zero, std::move(dofs), Wr));
}

// u and phi Dirichlet conditions on the collapsed sub-spaces (a Constant on a
// vector sub-space of a mixed space throws in 0.5.2).
void Problem::create_bcs(const std::vector<DirichletSettings>& dirichlet,
                         const std::string& source)
{
  const int fdim = compat::topology(*mesh).dim() - 1;
  const auto W_phi = compat::sub(*W, 1);
  if (model.axisymmetric)
    fix_on_axis();
  for (const auto& bc : dirichlet)
  {
    const auto facets = model.mesh.boundary_facets(bc.boundary);
    if (bc.displacement or bc.displacement_exact)
    {
      std::shared_ptr<fem::Function<double>> g = u_exact; // updated every step
      const int dim = V_u->dofmap()->index_map_bs();
      std::vector<bool> fixed(dim, true);
      if (!bc.displacement_exact)
      {
        g = std::make_shared<fem::Function<double>>(V_u);
        SpatialDatum datum{"boundaries." + bc.boundary + ".displacement", {},
                           bc.displacement_history};
        for (int i = 0; i < dim; ++i)
        {
          const auto& c = bc.displacement->at(i);
          fixed[i] = c.has_value();
          datum.components.push_back(c.value_or(Value{}));
        }
        if (std::any_of(datum.components.begin(), datum.components.end(),
                        [](const Value& v) { return v.varies(); }))
          place_spatial(g, datum, &facets);
        else
        {
          auto values = compat::mutable_values(*g->x());
          for (int i = 0; i < dim; ++i)
            for (std::size_t j = i; j < values.size(); j += dim)
              values[j] = datum.components[i].number;
          scale_in_time(g, bc.displacement_history);
        }
      }
      if (!g)
        throw ConfigError(source + ": boundaries." + bc.boundary
                          + ".displacement: \"exact\" needs a manufactured solution");
      // one condition per fixed component, its values taken from g on V_u
      // (W->sub({0, i}) is not W.sub(0).sub(i) in 0.5.2: chain single levels)
      auto& comp = _clamped_dofs[bc.boundary];
      comp.assign(dim, {});
      for (int i = 0; i < dim; ++i)
      {
        if (!fixed[i])
          continue; // free: no reaction along it
        auto Wi = compat::sub(*compat::sub(*W, 0), i);
        auto dofs = compat::locate_dofs_topological(*Wi, *compat::sub(*V_u, i), fdim, facets);
        comp[i] = dofs[0];
        _bc_dofs.insert(_bc_dofs.end(), dofs[0].begin(), dofs[0].end());
        _bcs.push_back(std::make_shared<fem::DirichletBC<double>>(g, std::move(dofs), Wi));
      }
    }
    if (bc.potential or bc.potential_exact)
    {
      std::shared_ptr<fem::Function<double>> g = phi_exact; // updated every step
      if (!bc.potential_exact)
      {
        g = std::make_shared<fem::Function<double>>(V_phi);
        if (bc.potential->varies())
          place_spatial(g, {"boundaries." + bc.boundary + ".potential", {*bc.potential},
                            bc.potential_history}, &facets);
        else
        {
          std::fill(compat::mutable_values(*g->x()).begin(), compat::mutable_values(*g->x()).end(),
                    bc.potential->number);
          scale_in_time(g, bc.potential_history);
        }
      }
      if (!g)
        throw ConfigError(source + ": boundaries." + bc.boundary
                          + ".potential: \"exact\" needs a manufactured solution");
      auto dofs = compat::locate_dofs_topological(*W_phi, *V_phi, fdim, facets);
      _bc_dofs.insert(_bc_dofs.end(), dofs[0].begin(), dofs[0].end());
      Electrode e;
      e.name = bc.boundary;
      e.dofs = dofs[0];
      _bcs.push_back(std::make_shared<fem::DirichletBC<double>>(g, std::move(dofs), W_phi));
      e.bc = _bcs.back();
      electrodes.push_back(std::move(e));
    }
    if (bc.floating)
    {
      // a Dirichlet condition whose value, the electrode's potential, the
      // solver sets (floating.h)
      auto g = std::make_shared<fem::Function<double>>(V_phi);
      auto dofs = compat::locate_dofs_topological(*W_phi, *V_phi, fdim, facets);
      _bc_dofs.insert(_bc_dofs.end(), dofs[0].begin(), dofs[0].end());
      Electrode e;
      e.name = bc.boundary;
      e.dofs = dofs[0];
      e.floating = true;
      e.potential = g;
      e.charge = bc.charge;
      e.history = bc.charge_history;
      _bcs.push_back(std::make_shared<fem::DirichletBC<double>>(g, std::move(dofs), W_phi));
      e.bc = _bcs.back();
      electrodes.push_back(std::move(e));
    }
  }
}

// A vertex on two electrodes is seen whole only by its owner: mark each
// electrode's dofs and gather the marks there
void Problem::check_electrodes_apart(const std::string& source) const
{
  const auto& imap = W->dofmap()->index_map;
  const int bs = W->dofmap()->index_map_bs();
  const std::int32_t owned = imap->size_local() * bs;
  std::vector<std::vector<char>> on(electrodes.size());
  for (std::size_t e = 0; e < electrodes.size(); ++e)
  {
    la::Vector<double> mark(imap, bs);
    for (auto d : electrodes[e].dofs)
      compat::mutable_values(mark)[d] = 1.0;
    mark.scatter_rev([](double a, double b) { return std::max(a, b); });
    on[e].assign(compat::values(mark).begin(), compat::values(mark).begin() + owned);
  }
  for (std::size_t e = 0; e < electrodes.size(); ++e)
  {
    std::int64_t count = std::count(on[e].begin(), on[e].end(), 1);
    MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_INT64_T, MPI_SUM, comm);
    if (electrodes[e].floating and count == 0)
      throw ConfigError(source + ": boundaries." + electrodes[e].name
                        + ".floating: the boundary has no vertices");
  }
  for (std::size_t e = 0; e < electrodes.size(); ++e)
    for (std::size_t f = e + 1; f < electrodes.size(); ++f)
    {
      if (!electrodes[e].floating and !electrodes[f].floating)
        continue; // two prescribed potentials: the last given wins, as before
      int shared = 0;
      for (std::int32_t i = 0; i < owned and !shared; ++i)
        shared = on[e][i] and on[f][i];
      MPI_Allreduce(MPI_IN_PLACE, &shared, 1, MPI_INT, MPI_LOR, comm);
      if (shared)
      {
        const auto& fl = electrodes[e].floating ? electrodes[e] : electrodes[f];
        const auto& other = electrodes[e].floating ? electrodes[f] : electrodes[e];
        throw ConfigError(source + ": boundaries." + fl.name + ".floating: the electrode "
                          "shares a vertex with the electrode " + other.name
                          + " (a floating potential must be apart from other electrodes)");
      }
    }
}

std::vector<double> Problem::electrode_potentials(std::span<const double> x) const
{
  const std::int32_t owned
      = W->dofmap()->index_map->size_local() * W->dofmap()->index_map_bs();
  std::vector<double> local(2 * electrodes.size(), 0.0), global(local.size());
  for (std::size_t e = 0; e < electrodes.size(); ++e)
    for (auto d : electrodes[e].dofs)
      if (d < owned)
      {
        local[2 * e] += x[d];
        local[2 * e + 1] += 1.0;
      }
  MPI_Allreduce(local.data(), global.data(), global.size(), MPI_DOUBLE, MPI_SUM, comm);
  std::vector<double> out(electrodes.size());
  for (std::size_t e = 0; e < electrodes.size(); ++e)
    out[e] = global[2 * e + 1] > 0 ? global[2 * e] / global[2 * e + 1] : 0.0;
  return out; // the mean: exactly the value where it is uniform (to round-off)
}

void Problem::hold_floating_potentials(std::span<const double> x)
{
  const auto V = electrode_potentials(x);
  for (std::size_t e = 0; e < electrodes.size(); ++e)
    if (electrodes[e].floating)
      hold(electrodes[e], V[e]);
}

void Problem::hold(Electrode& e, double V)
{
  auto g = compat::mutable_values(*e.potential->x());
  std::fill(g.begin(), g.end(), V);
  e.held = V;
}

std::vector<double> Problem::reaction_charges(std::span<const double> r) const
{
  std::vector<double> local(electrodes.size(), 0.0), global(electrodes.size());
  for (std::size_t e = 0; e < electrodes.size(); ++e)
    for (auto d : electrodes[e].dofs)
      if (d < std::int32_t(r.size()))
        local[e] -= r[d];
  MPI_Allreduce(local.data(), global.data(), global.size(), MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

std::vector<double> Problem::electrode_charges() const
{
  std::vector<double> local(electrodes.size(), 0.0), global(electrodes.size());
  for (std::size_t e = 0; e < electrodes.size(); ++e)
    if (auto it = model.electrode_charge.find(electrodes[e].name);
        it != model.electrode_charge.end())
      for (const auto& term : it->second)
        local[e] += fem::assemble_scalar(*term);
  MPI_Allreduce(local.data(), global.data(), global.size(), MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

std::vector<double> Problem::target_charges() const
{
  std::vector<double> out;
  for (const auto& e : electrodes)
    out.push_back(e.floating ? e.charge * e.history.factor(_t) : 0.0);
  return out;
}

double Problem::update_contact_pressure()
{
  if (!contact_pressure)
    return 0.0;
  FormList load, area;
  if (model.contact_pressure_load and model.contact_nodal_area)
  {
    load.push_back(model.contact_pressure_load);
    area.push_back(model.contact_nodal_area);
  }
  if (model.obstacles.empty())
    return lumped_pressure(load, area, compat::mutable_values(*contact_pressure->x()));
  // the paper's foundation's measure alone; the field of every contact
  std::vector<double> scratch(compat::values(*contact_pressure->x()).size(), 0.0);
  const double foundation = lumped_pressure(load, area, scratch);
  for (const auto& [_, o] : model.obstacles)
  {
    load.insert(load.end(), o.pressure_load.begin(), o.pressure_load.end());
    area.insert(area.end(), o.nodal_area.begin(), o.nodal_area.end());
  }
  lumped_pressure(load, area, compat::mutable_values(*contact_pressure->x()));
  return foundation;
}

double Problem::obstacle_max_pressure(const std::string& boundary) const
{
  const auto& o = model.obstacles.at(boundary);
  std::vector<double> p(model.P->dofmap()->index_map->size_local()
                        + model.P->dofmap()->index_map->num_ghosts(), 0.0);
  lumped_pressure(o.pressure_load, o.nodal_area, p);
  double local = *std::max_element(p.begin(), p.end()), global;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, comm);
  return global;
}

double Problem::lumped_pressure(const FormList& load_terms, const FormList& area_terms,
                                std::span<double> p) const
{
  if (load_terms.empty())
    return 0.0;
  const auto load = assemble(load_terms);
  const auto area = assemble(area_terms);
  const std::int32_t owned = model.P->dofmap()->index_map->size_local();
  double local = 0.0, global = 0.0;
  for (std::int32_t i = 0; i < owned; ++i)
  {
    const double a = compat::values(area)[i];
    p[i] = a > 0.0 ? compat::values(load)[i] / a : 0.0;
    if (p[i] > 0.0)
      local += a;
  }
  if (contact_pressure and p.data() == compat::mutable_values(*contact_pressure->x()).data())
    contact_pressure->x()->scatter_fwd();
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

void Problem::scale_in_time(const std::shared_ptr<fem::Function<double>>& g,
                            const History& history)
{
  if (history.kind == History::Kind::constant)
    return;
  _scaled_bc_values.push_back(g); // kept alive with its values
  const auto values = compat::mutable_values(*g->x());
  _scaled.push_back({values, std::vector<double>(values.begin(), values.end()), history});
}

double Problem::extent() const
{
  const auto x = mesh->geometry().x();
  double size = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
    size = std::max(size, std::abs(x.data()[i]));
  MPI_Allreduce(MPI_IN_PLACE, &size, 1, MPI_DOUBLE, MPI_MAX, comm);
  return size;
}

namespace
{
std::string number(double v)
{
  return std::isnan(v) ? "nan" : std::isinf(v) ? (v > 0 ? "inf" : "-inf") : printable(json(v));
}
} // namespace

void Problem::place_spatial(const std::shared_ptr<fem::Function<double>>& field,
                            const SpatialDatum& datum, const std::vector<std::int32_t>* facets)
{
  const auto& V = *field->function_space();
  Placed placed{field, datum, {}, {}};
  if (facets)
    placed.nodes = compat::locate_nodes(V, compat::topology(*mesh).dim() - 1, *facets);
  else
  {
    const auto map = V.dofmap()->index_map;
    placed.nodes.resize(map->size_local() + map->num_ghosts());
    std::iota(placed.nodes.begin(), placed.nodes.end(), 0);
  }
  const std::vector<double> x = V.tabulate_dof_coordinates(false); // (nodes, 3)
  for (auto node : placed.nodes)
    for (int c = 0; c < 3; ++c)
    {
      // a node on a coordinate plane is there exactly (the push-forward
      // leaves round-off, which 1/x or sqrt(x) on the axis would read)
      const double xc = x[3 * node + c];
      placed.points.push_back(std::abs(xc) <= 1e-12 * _extent ? 0.0 : xc);
    }
  if (std::any_of(datum.components.begin(), datum.components.end(), [](const Value& v)
                  { return v.varies() and v.expression->uses_time(); }))
    return _evolving.push_back(std::move(placed)); // set_time evaluates it
  evaluate(placed, 0.0, 1.0);
  scale_in_time(field, datum.history);
}

void Problem::evaluate(const Placed& placed, double t, double factor) const
{
  const auto& components = placed.datum.components;
  const int bs = placed.field->function_space()->dofmap()->index_map_bs();
  if (std::size_t(bs) != components.size())
    throw std::logic_error(placed.datum.key + ": " + std::to_string(components.size())
                           + " components for a field of " + std::to_string(bs));
  auto values = compat::mutable_values(*placed.field->x());
  std::string error;
  for (std::size_t k = 0; k < placed.nodes.size(); ++k)
  {
    const std::array<double, 3> x
        = {placed.points[3 * k], placed.points[3 * k + 1], placed.points[3 * k + 2]};
    for (int i = 0; i < bs; ++i)
    {
      double& v = values[placed.nodes[k] * bs + i];
      v = factor * components[i].at(x, t);
      if (!std::isfinite(v) and error.empty())
        error = (bs > 1 ? "[" + std::to_string(i) + "]" : "") + ": "
                + printable(json(components[i].varies() ? components[i].expression->text() : ""))
                + " is " + number(v) + " at (" + number(x[0]) + ", " + number(x[1]) + ", "
                + number(x[2]) + ") at t = " + number(t);
    }
  }
  // every rank throws the first rank's message (one line, exit 2)
  int rank = 0, first = std::numeric_limits<int>::max();
  MPI_Comm_rank(comm, &rank);
  const int mine = error.empty() ? std::numeric_limits<int>::max() : rank;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == std::numeric_limits<int>::max())
    return;
  std::string message = printable(_source, 200) + ": " + placed.datum.key + error
                        + ": a datum must be finite everywhere";
  int length = message.size();
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  message.resize(length);
  MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
  throw ConfigError(message);
}

void Problem::update_fields()
{
  auto xa = compat::values(*x->x());
  auto ua = compat::mutable_values(*u->x());
  auto pa = compat::mutable_values(*phi->x());
  for (std::size_t i = 0; i < u_dofs.size(); ++i)
    ua[i] = xa[u_dofs[i]];
  for (std::size_t i = 0; i < phi_dofs.size(); ++i)
    pa[i] = xa[phi_dofs[i]];
}
} // namespace piezocontact
