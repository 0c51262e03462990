#include "problem.h"
#include "piezo_contact.h"
#include "piezo_forms_meta.h"

#include <algorithm>
#include <basix/finite-element.h>
#include <dolfinx/fem/utils.h>
#include <numeric>

namespace piezo
{
Problem::Problem(const json& cfg_, MPI_Comm comm_, const std::string& source,
                 const std::optional<std::filesystem::path>& mesh_file)
    : cfg(cfg_), comm(comm_)
{
  NamedMesh named = build_mesh(cfg, comm, mesh_file, source);
  mesh = named.mesh;
  facet_tags = named.facet_tags;
  tag_of = named.tag_of;

  if (static_cast<int>(tag_of.size()) > forms::max_boundaries)
    throw ConfigError(source + ": mesh: " + std::to_string(tag_of.size())
                      + " named boundaries, the forms support "
                      + std::to_string(forms::max_boundaries));
  for (const auto& [name, _] : cfg["boundaries"].items())
  {
    if (!tag_of.contains(name))
    {
      std::string have;
      for (const auto& [m, __] : tag_of)
        have += (have.empty() ? "" : ", ") + m;
      throw ConfigError(source + ": boundaries." + name
                        + ": the mesh has no boundary '" + name
                        + "' (it has: " + have + ")");
    }
  }

  W = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
      functionspace_form_piezo_contact_F, "x", mesh));
  x = std::make_shared<fem::Function<double>>(W);
  x->name = "x";
  x_prev = std::make_shared<fem::Function<double>>(W);
  x_prev->name = "x_prev";
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

  auto add_constants = [this](const auto& shapes)
  {
    for (const auto& [name, shape] : shapes)
    {
      const std::size_t size = std::accumulate(shape.begin(), shape.end(),
                                               std::size_t(1), std::multiplies{});
      const std::vector<double> zeros(size, 0.0);
      constants[name] = std::make_shared<fem::Constant<double>>(
          std::span<const double>(zeros), std::span<const std::size_t>(shape));
    }
  };
  add_constants(forms::constant_shapes);
  const bool is_manufactured = cfg.contains("manufactured");
  if (is_manufactured)
    add_constants(forms::manufactured_constant_shapes);
  set_constants();

  const Coefficients coefficients = {{"x", x}, {"x_prev", x_prev}};
  const Constants consts(constants.begin(), constants.end());
  const std::map<fem::IntegralType, const mesh::MeshTags<int>*> subdomains
      = {{fem::IntegralType::exterior_facet, facet_tags.get()}};
  if (is_manufactured)
  {
    manufactured = std::make_unique<ManufacturedSolution>(
        cfg["manufactured"], W, V_u, V_phi, coefficients, constants, *facet_tags);
    F = manufactured->F;
  }
  else
  {
    F = std::make_shared<fem::Form<double>>(fem::create_form<double>(
        *form_piezo_contact_F, {W}, coefficients, consts, subdomains));
  }
  J = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_piezo_contact_J, {W, W}, coefficients, consts, subdomains));
  J_contact = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_piezo_contact_J_contact, {W, W}, coefficients, consts, subdomains));
  contact_force[0] = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_piezo_contact_contact_force_x, {}, coefficients, consts, subdomains, mesh));
  contact_force[1] = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_piezo_contact_contact_force_y, {}, coefficients, consts, subdomains, mesh));
  D_expr = std::make_shared<fem::Expression<double>>(fem::create_expression<double>(
      *expression_piezo_contact_electric_displacement, coefficients, consts, mesh));
  stress_expr = std::make_shared<fem::Expression<double>>(fem::create_expression<double>(
      *expression_piezo_contact_stress, coefficients, consts, mesh));

  create_bcs();
}

void Problem::set_constants()
{
  auto set = [this](const std::string& name, const json& value)
  {
    auto& v = constants.at(name)->value;
    if (!value.is_array())
      v.assign(1, value.get<double>());
    else
    {
      // row-major order of the nested lists
      std::size_t i = 0;
      std::function<void(const json&)> walk = [&](const json& node)
      {
        if (node.is_array())
          for (const auto& item : node)
            walk(item);
        else
          v.at(i++) = node.get<double>();
      };
      walk(value);
    }
  };
  const json& mat = cfg["material"];
  set("Bv", mat["elastic"]);
  set("Av", mat["viscosity"]);
  set("e", mat["piezoelectric"]);
  set("beta", mat["permittivity"]);
  set("c_p", cfg["contact"]["c_p"]);
  set("g", cfg["contact"]["gap"]);
  set("k", cfg["time"]["T"].get<double>() / cfg["time"]["steps"].get<double>());
  set("f0", cfg["loads"]["body_force"]);
  set("q0", cfg["loads"]["charge_density"]);
  for (const auto& [name, bc] : cfg["boundaries"].items())
  {
    const std::size_t s = tag_of.at(name) - 1;
    const json traction = bc.value("traction", json::array({0.0, 0.0}));
    constants.at("fF")->value.at(2 * s) = traction[0].get<double>();
    constants.at("fF")->value.at(2 * s + 1) = traction[1].get<double>();
    constants.at("qF")->value.at(s) = bc.value("surface_charge", 0.0);
    constants.at("chi")->value.at(s) = bc.value("contact", false) ? 1.0 : 0.0;
  }
}

std::vector<std::int32_t>
Problem::boundary_facets(const std::string& name) const
{
  std::vector<std::int32_t> facets;
  const auto& idx = facet_tags->indices();
  const auto& val = facet_tags->values();
  for (std::size_t i = 0; i < idx.size(); ++i)
    if (val[i] == tag_of.at(name))
      facets.push_back(idx[i]);
  return facets;
}

// u and phi Dirichlet conditions on the collapsed sub-spaces (a Constant on a
// vector sub-space of a mixed space throws in 0.5.2).
void Problem::create_bcs()
{
  std::map<std::string, json> sorted_bcs; // same order as the Python twin
  for (const auto& [name, bc] : cfg["boundaries"].items())
    sorted_bcs[name] = bc;
  for (const auto& [name, bc] : sorted_bcs)
  {
    const auto facets = boundary_facets(name);
    if (bc.contains("displacement"))
    {
      std::shared_ptr<fem::Function<double>> g;
      if (bc["displacement"] == "exact")
        g = manufactured->u_exact; // updated every step
      else
      {
        g = std::make_shared<fem::Function<double>>(V_u);
        auto values = g->x()->mutable_array();
        for (std::size_t i = 0; i < values.size(); ++i)
          values[i] = bc["displacement"][i % 2].get<double>();
      }
      auto dofs = fem::locate_dofs_topological({*W->sub({0}), *V_u}, 1, facets);
      bc_dofs.insert(bc_dofs.end(), dofs[0].begin(), dofs[0].end());
      bcs.push_back(std::make_shared<fem::DirichletBC<double>>(g, std::move(dofs), W->sub({0})));
      std::array<std::vector<std::int32_t>, 2> comp;
      for (int i = 0; i < 2; ++i)
      {
        const auto Vi = V_u->sub({i})->collapse().first;
        // W->sub({0, i}) is not W.sub(0).sub(i) in 0.5.2: chain single levels
        comp[i] = fem::locate_dofs_topological({*W->sub({0})->sub({i}), Vi}, 1, facets)[0];
      }
      clamped_dofs[name] = comp;
    }
    if (bc.contains("potential"))
    {
      std::shared_ptr<fem::Function<double>> g;
      if (bc["potential"] == "exact")
        g = manufactured->phi_exact; // updated every step
      else
      {
        g = std::make_shared<fem::Function<double>>(V_phi);
        std::fill(g->x()->mutable_array().begin(), g->x()->mutable_array().end(),
                  bc["potential"].get<double>());
      }
      auto dofs = fem::locate_dofs_topological({*W->sub({1}), *V_phi}, 1, facets);
      bc_dofs.insert(bc_dofs.end(), dofs[0].begin(), dofs[0].end());
      bcs.push_back(std::make_shared<fem::DirichletBC<double>>(g, std::move(dofs), W->sub({1})));
    }
  }
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
} // namespace piezo
