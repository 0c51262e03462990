#include "compiled_model.h"
#include "manufactured_2d.h"  // ffcx's, from forms/manufactured_2d.ufl
#include "manufactured_3d.h"
#include "piezo_contact_2d.h" // ffcx's, from forms/piezo_contact_2d.ufl
#include "piezo_contact_3d.h"
#include "piezo_forms_meta.h"

#include <dolfinx/fem/utils.h>
#include <functional>
#include <numeric>

namespace piezocontact::app
{
using namespace dolfinx;

namespace
{
using compat::Coefficients;
using compat::Constants;
/// The entities a term is integrated over (null: only its unmarked integrals)
using Piece = const std::vector<std::int32_t>*;

/// The ahead-of-time forms of one cell type (see forms/entry_points.py)
struct Kernels
{
  compat::UfcxSpaceFactory space;
  ufcx_form *F_region, *J_region, *L_region, *F_boundary, *L_boundary, *F_contact,
      *J_contact, *boundary_measure, *electrode_charge, *contact_pressure_load,
      *contact_nodal_area;
  std::vector<ufcx_form*> contact_force;
  ufcx_expression *electric_displacement, *stress;
};

/// The terms that differ in a manufactured-solution run
struct ManufacturedKernels
{
  ufcx_form *F_region, *L_region, *F_exterior, *L_exterior, *F_contact, *L_contact;
  std::map<std::string, ufcx_form*> squared_errors;
  ufcx_expression *u_exact, *phi_exact;
};

#define PIEZO_KERNELS(P)                                                                \
  Kernels                                                                               \
  {                                                                                     \
    PIEZO_UFCX_SPACE(functionspace_form_##P##_F_region), form_##P##_F_region, form_##P##_J_region,        \
        form_##P##_L_region, form_##P##_F_boundary, form_##P##_L_boundary,              \
        form_##P##_F_contact, form_##P##_J_contact, form_##P##_boundary_measure,        \
        form_##P##_electrode_charge, form_##P##_contact_pressure_load,                  \
        form_##P##_contact_nodal_area, {}, expression_##P##_electric_displacement,      \
        expression_##P##_stress                                                         \
  }
#define PIEZO_MANUFACTURED(P)                                                           \
  ManufacturedKernels                                                                   \
  {                                                                                     \
    form_##P##_F_region, form_##P##_L_region, form_##P##_F_exterior,                    \
        form_##P##_L_exterior, form_##P##_F_contact, form_##P##_L_contact,              \
        {{"u_L2", form_##P##_u_L2},                                                     \
         {"u_H1", form_##P##_u_H1},                                                     \
         {"phi_L2", form_##P##_phi_L2},                                                 \
         {"phi_H1", form_##P##_phi_H1}},                                                \
        expression_##P##_u_exact, expression_##P##_phi_exact                           \
  }

Kernels kernels(int d)
{
  Kernels k = d == 2 ? PIEZO_KERNELS(piezo_contact_2d) : PIEZO_KERNELS(piezo_contact_3d);
  k.contact_force = d == 2 ? std::vector{form_piezo_contact_2d_contact_force_x,
                                         form_piezo_contact_2d_contact_force_y}
                           : std::vector{form_piezo_contact_3d_contact_force_x,
                                         form_piezo_contact_3d_contact_force_y,
                                         form_piezo_contact_3d_contact_force_z};
  return k;
}

ManufacturedKernels manufactured_kernels(int d)
{
  return d == 2 ? PIEZO_MANUFACTURED(manufactured_2d) : PIEZO_MANUFACTURED(manufactured_3d);
}

ConstantMap zero_constants(const forms::Shapes& shapes)
{
  ConstantMap out;
  for (const auto& [name, shape] : shapes)
  {
    const std::size_t size
        = std::accumulate(shape.begin(), shape.end(), std::size_t(1), std::multiplies{});
    const std::vector<double> zeros(size, 0.0);
    out[name] = std::make_shared<fem::Constant<double>>(std::span<const double>(zeros),
                                                        std::span<const std::size_t>(shape));
  }
  return out;
}

/// The union of Constant maps, as create_form takes them
Constants merged(std::initializer_list<const ConstantMap*> maps)
{
  Constants out;
  for (const auto* m : maps)
    out.insert(m->begin(), m->end());
  return out;
}
} // namespace

Model compiled_model(const NamedMesh& named, const json& cfg)
{
  Model m;
  m.mesh = named;
  auto mesh = named.mesh;
  const int d = mesh->geometry().dim();
  const Kernels k = kernels(d);
  m.W = compat::mixed_p1_space(mesh, k.space);
  m.x = std::make_shared<fem::Function<double>>(m.W);
  m.x->name = "x";
  m.x_prev = std::make_shared<fem::Function<double>>(m.W);
  m.x_prev->name = "x_prev";
  const bool manufactured = cfg.contains("manufactured");
  m.constants = zero_constants(forms::constant_shapes(d));
  if (manufactured)
    m.constants.merge(zero_constants(forms::manufactured_constant_shapes));

  const Coefficients coefficients = {{"x", m.x}, {"x_prev", m.x_prev}};
  // One term: a form over the entities of `piece` (dx(1) or ds(1))
  auto form = [&](const ufcx_form* f, int rank, const Constants& constants,
                  fem::IntegralType type, Piece piece)
  {
    std::vector<std::shared_ptr<const compat::FunctionSpace>> spaces(rank, m.W);
    return compat::create_form(*f, spaces, coefficients, constants, type, piece, mesh);
  };
  auto expression = [&](const ufcx_expression* e, const Coefficients& c, const Constants& consts)
  { return compat::create_expression(*e, c, consts, mesh); };
  const auto cell = fem::IntegralType::cell, facet = fem::IntegralType::exterior_facet;
  const Constants shared = merged({&m.constants});
  const auto mms = manufactured_kernels(d);

  for (const auto& [name, _] : named.region_of)
  {
    auto& material = m.materials[name] = zero_constants(forms::material_shapes(d));
    const auto cells = named.region_cells(name);
    const Constants c = merged({&m.constants, &material});
    m.F.push_back(form(manufactured ? mms.F_region : k.F_region, 1, c, cell, &cells));
    m.J.push_back(form(k.J_region, 2, c, cell, &cells));
    m.L.push_back(form(manufactured ? mms.L_region : k.L_region, 1, c, cell, &cells));
    m.fields.push_back({cells, expression(k.electric_displacement, coefficients, c),
                        expression(k.stress, coefficients, c)});
    if (manufactured) // one region (checked): the exact solution's surface loads
    {
      m.F.push_back(form(mms.F_exterior, 1, c, facet, nullptr));
      m.L.push_back(form(mms.L_exterior, 1, c, facet, nullptr));
    }
  }
  for (const auto& [name, _] : named.tag_of)
  {
    auto& load = m.loads[name] = zero_constants(forms::load_shapes(d));
    const auto facets = named.boundary_facets(name);
    const Constants c = merged({&m.constants, &load});
    m.F.push_back(form(k.F_boundary, 1, c, facet, &facets));
    m.L.push_back(form(k.L_boundary, 1, c, facet, &facets));
    m.boundary_measures[name] = form(k.boundary_measure, 0, {}, facet, &facets);
  }
  for (const auto& [name, bc] : cfg["boundaries"].items())
    if (bc.value("contact", false) and named.tag_of.contains(name))
    {
      const auto facets = named.boundary_facets(name);
      m.contact_facets.insert(m.contact_facets.end(), facets.begin(), facets.end());
    }
  const Piece contact = &m.contact_facets;
  m.F.push_back(form(manufactured ? mms.F_contact : k.F_contact, 1, shared, facet, contact));
  m.J.push_back(form(k.J_contact, 2, shared, facet, contact));
  m.J_contact.push_back(m.J.back());
  if (manufactured)
    m.L.push_back(form(mms.L_contact, 1, shared, facet, contact));
  for (const auto* f : k.contact_force)
    m.contact_force.push_back(form(f, 0, shared, facet, contact));
  m.contact_pressure_load = form(k.contact_pressure_load, 1, shared, facet, contact);
  m.contact_nodal_area = form(k.contact_nodal_area, 1, shared, facet, contact);
  // every boundary with a potential condition is an electrode: its charge,
  // one term per region it bounds (on every rank, whatever it holds)
  for (const auto& [name, bc] : cfg["boundaries"].items())
    if ((bc.contains("potential") or bc.contains("floating")) and named.tag_of.contains(name))
      for (const auto& [region, material] : m.materials)
      {
        const auto facets = named.boundary_facets_of(name, region);
        m.electrode_charge[name].push_back(
            form(k.electrode_charge, 0, merged({&m.constants, &material}), facet, &facets));
      }

  if (manufactured)
  {
    // the exact fields are the "exact" Dirichlet data
    m.u_exact = expression(mms.u_exact, {}, shared);
    m.phi_exact = expression(mms.phi_exact, {}, shared);
    for (const auto& [name, f] : mms.squared_errors)
      m.squared_errors[name] = form(f, 0, shared, cell, nullptr);
  }
  return m;
}
} // namespace piezocontact::app
