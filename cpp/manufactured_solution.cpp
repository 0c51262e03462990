#include "manufactured_solution.h"
#include "manufactured.h" // ffcx's, from forms/manufactured.ufl

#include <cmath>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/utils.h>

namespace piezo
{
ManufacturedSolution::ManufacturedSolution(
    const json& settings, std::shared_ptr<const fem::FunctionSpace> W,
    std::shared_ptr<const fem::FunctionSpace> V_u,
    std::shared_ptr<const fem::FunctionSpace> V_phi, const Coefficients& coefficients,
    const std::map<std::string, std::shared_ptr<fem::Constant<double>>>& constants,
    const mesh::MeshTags<std::int32_t>& facet_tags)
    : _t(constants.at("t"))
{
  constants.at("space_smooth")->value = {settings["space"] == "smooth" ? 1.0 : 0.0};
  constants.at("time_smooth")->value = {settings["time"] == "smooth" ? 1.0 : 0.0};
  const Constants consts(constants.begin(), constants.end());
  auto mesh = W->mesh();
  const std::map<fem::IntegralType, const mesh::MeshTags<int>*> subdomains
      = {{fem::IntegralType::exterior_facet, &facet_tags}};
  F = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_manufactured_F, {W}, coefficients, consts, subdomains));
  for (const auto& [name, form] :
       {std::pair{"u_L2", form_manufactured_u_L2}, std::pair{"u_H1", form_manufactured_u_H1},
        std::pair{"phi_L2", form_manufactured_phi_L2},
        std::pair{"phi_H1", form_manufactured_phi_H1}})
  {
    _squared_errors[name] = std::make_shared<fem::Form<double>>(
        fem::create_form<double>(*form, {}, coefficients, consts, {}, mesh));
  }
  _u_expr = std::make_shared<fem::Expression<double>>(fem::create_expression<double>(
      *expression_manufactured_u_exact, Coefficients{}, consts, mesh));
  _phi_expr = std::make_shared<fem::Expression<double>>(fem::create_expression<double>(
      *expression_manufactured_phi_exact, Coefficients{}, consts, mesh));
  u_exact = std::make_shared<fem::Function<double>>(V_u);
  u_exact->name = "u_exact";
  phi_exact = std::make_shared<fem::Function<double>>(V_phi);
  phi_exact->name = "phi_exact";
  set_time(0.0);
}

void ManufacturedSolution::set_time(double t)
{
  _t->value = {t};
  u_exact->interpolate(*_u_expr);
  phi_exact->interpolate(*_phi_expr);
}

json ManufacturedSolution::errors(MPI_Comm comm) const
{
  json out = json::object();
  for (const char* name : {"u_L2", "u_H1", "phi_L2", "phi_H1"})
  {
    double local = fem::assemble_scalar(*_squared_errors.at(name)), global = 0.0;
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
    out[name] = std::sqrt(global);
  }
  return out;
}
} // namespace piezo
