// Manufactured-solution runs (config key "manufactured"): the forms of
// forms/manufactured.ufl -- the model's residual with the loads of an exact
// solution, the exact fields as Dirichlet data, the errors of a step.
// Mirrors demos/piezocontact/manufactured_solution.py.
#pragma once

#include "config.h"

#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/MeshTags.h>
#include <map>
#include <memory>
#include <string>

namespace piezo
{
using namespace dolfinx;

using Coefficients = std::map<std::string, std::shared_ptr<const fem::Function<double>>>;
using Constants = std::map<std::string, std::shared_ptr<const fem::Constant<double>>>;

class ManufacturedSolution
{
public:
  /// `constants` must hold the model's and manufactured.py's Constants
  /// (t, space_smooth, time_smooth); the switches are set here from `settings`.
  ManufacturedSolution(
      const json& settings, std::shared_ptr<const fem::FunctionSpace> W,
      std::shared_ptr<const fem::FunctionSpace> V_u,
      std::shared_ptr<const fem::FunctionSpace> V_phi, const Coefficients& coefficients,
      const std::map<std::string, std::shared_ptr<fem::Constant<double>>>& constants,
      const mesh::MeshTags<std::int32_t>& facet_tags);

  /// Set the time of the loads and interpolate the exact fields at t
  void set_time(double t);

  /// L2 and H1 norms of the error of x at the current time (u_L2, u_H1,
  /// phi_L2, phi_H1), the same on every rank
  json errors(MPI_Comm comm) const;

  std::shared_ptr<fem::Form<double>> F;  ///< the residual with the exact loads
  std::shared_ptr<fem::Function<double>> u_exact, phi_exact; ///< Dirichlet data

private:
  std::shared_ptr<fem::Constant<double>> _t;
  std::shared_ptr<fem::Expression<double>> _u_expr, _phi_expr;
  std::map<std::string, std::shared_ptr<fem::Form<double>>> _squared_errors;
};
} // namespace piezo
