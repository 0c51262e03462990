#include "compiled_model.h"
#include "manufactured.h"  // ffcx's, from forms/manufactured.ufl
#include "piezo_contact.h" // ffcx's, from forms/piezo_contact.ufl
#include "piezo_forms_meta.h"

#include <dolfinx/fem/utils.h>
#include <functional>
#include <numeric>

namespace piezocontact::app
{
using namespace dolfinx;

namespace
{
using Coefficients = std::map<std::string, std::shared_ptr<const fem::Function<double>>>;
using Constants = std::map<std::string, std::shared_ptr<const fem::Constant<double>>>;
using Shapes = std::map<std::string, std::vector<std::size_t>>;

void add_constants(ConstantMap& constants, const Shapes& shapes)
{
  for (const auto& [name, shape] : shapes)
  {
    const std::size_t size
        = std::accumulate(shape.begin(), shape.end(), std::size_t(1), std::multiplies{});
    const std::vector<double> zeros(size, 0.0);
    constants[name] = std::make_shared<fem::Constant<double>>(
        std::span<const double>(zeros), std::span<const std::size_t>(shape));
  }
}
} // namespace

Model compiled_model(const NamedMesh& named, const json& cfg)
{
  Model m;
  m.mesh = named;
  auto mesh = named.mesh;
  m.W = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_piezo_contact_F, "x", mesh));
  m.x = std::make_shared<fem::Function<double>>(m.W);
  m.x->name = "x";
  m.x_prev = std::make_shared<fem::Function<double>>(m.W);
  m.x_prev->name = "x_prev";
  const bool manufactured = cfg.contains("manufactured");
  add_constants(m.constants, forms::constant_shapes);
  if (manufactured)
    add_constants(m.constants, forms::manufactured_constant_shapes);

  const Coefficients coefficients = {{"x", m.x}, {"x_prev", m.x_prev}};
  const Constants consts(m.constants.begin(), m.constants.end());
  const std::map<fem::IntegralType, const mesh::MeshTags<int>*> subdomains
      = {{fem::IntegralType::exterior_facet, named.facet_tags.get()}};
  auto form = [&](const ufcx_form& f, int rank)
  {
    std::vector<std::shared_ptr<const fem::FunctionSpace>> spaces(rank, m.W);
    return std::make_shared<const fem::Form<double>>(
        fem::create_form<double>(f, spaces, coefficients, consts, subdomains, mesh));
  };
  auto expression = [&](const ufcx_expression& e, const Coefficients& c)
  {
    return std::make_shared<const fem::Expression<double>>(
        fem::create_expression<double>(e, c, consts, mesh));
  };
  m.F = form(manufactured ? *form_manufactured_F : *form_piezo_contact_F, 1);
  m.J = form(*form_piezo_contact_J, 2);
  m.L = form(manufactured ? *form_manufactured_L : *form_piezo_contact_L, 1);
  m.J_contact = form(*form_piezo_contact_J_contact, 2);
  m.contact_force = {form(*form_piezo_contact_contact_force_x, 0),
                     form(*form_piezo_contact_contact_force_y, 0)};
  m.electric_displacement = expression(*expression_piezo_contact_electric_displacement,
                                       coefficients);
  m.stress = expression(*expression_piezo_contact_stress, coefficients);
  for (const auto& [name, tag] : named.tag_of)
  {
    // The form measures the facets tagged 1: tag this boundary's so
    std::vector<std::int32_t> facets;
    for (std::size_t i = 0; i < named.facet_tags->indices().size(); ++i)
      if (named.facet_tags->values()[i] == tag)
        facets.push_back(named.facet_tags->indices()[i]);
    const mesh::MeshTags<int> only(mesh, mesh->topology().dim() - 1, facets,
                                   std::vector<int>(facets.size(), 1));
    m.boundary_measures[name] = std::make_shared<const fem::Form<double>>(fem::create_form<double>(
        *form_piezo_contact_boundary_measure, {}, coefficients, consts,
        {{fem::IntegralType::exterior_facet, &only}}, mesh));
  }
  if (manufactured)
  {
    // the loads of the exact solution are in its F; the exact fields are
    // the "exact" Dirichlet data
    m.u_exact = expression(*expression_manufactured_u_exact, {});
    m.phi_exact = expression(*expression_manufactured_phi_exact, {});
    m.squared_errors = {{"u_L2", form(*form_manufactured_u_L2, 0)},
                        {"u_H1", form(*form_manufactured_u_H1, 0)},
                        {"phi_L2", form(*form_manufactured_phi_L2, 0)},
                        {"phi_H1", form(*form_manufactured_phi_H1, 0)}};
  }
  return m;
}
} // namespace piezocontact::app
