// The dolfinx objects one run is made of, wherever their kernels come from:
// ffcx ahead of time (the executable) or dolfinx's JIT (the Python package).
// The library never builds a form itself; it drives the ones given here.
#pragma once

#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/MeshTags.h>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace piezocontact
{
/// A mesh with its named boundaries: facet tag of boundary name (1-based
/// slots in sorted name order, the index into per-boundary Constants + 1)
struct NamedMesh
{
  std::shared_ptr<dolfinx::mesh::Mesh> mesh;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> facet_tags;
  std::map<std::string, int> tag_of;
};

using ConstantMap = std::map<std::string, std::shared_ptr<dolfinx::fem::Constant<double>>>;

struct Model
{
  NamedMesh mesh;
  /// The mixed space of x = (u, phi): sub-space 0 is u, 1 is phi
  std::shared_ptr<const dolfinx::fem::FunctionSpace> W;
  /// The unknown at t_n and the state at t_{n-1}, coefficients of the forms
  std::shared_ptr<dolfinx::fem::Function<double>> x, x_prev;
  /// Every runtime Constant of the forms, by name (forms/piezo_forms.py
  /// constant_shapes); the library sets "k" (and "t" if present) each step
  ConstantMap constants;

  /// Residual, its Jacobian, and the contact part of the Jacobian alone
  /// (only contact facets: J changes between iterates only if it does)
  std::shared_ptr<const dolfinx::fem::Form<double>> F, J, J_contact;
  /// The applied loads, a linear form (F = internal forces - L): its size
  /// scales the force balance that accepts a step. Optional.
  std::shared_ptr<const dolfinx::fem::Form<double>> L;
  /// Components of the foundation's resultant force on the body (N/m)
  std::vector<std::shared_ptr<const dolfinx::fem::Form<double>>> contact_force;
  /// Cell-wise electric displacement and Voigt stress, for output
  std::shared_ptr<const dolfinx::fem::Expression<double>> electric_displacement, stress;

  /// Optional exact fields at the Constant "t", for Dirichlet data given as
  /// "exact" (manufactured solutions), and squared error functionals
  /// reported per step as their square roots
  std::shared_ptr<const dolfinx::fem::Expression<double>> u_exact, phi_exact;
  std::map<std::string, std::shared_ptr<const dolfinx::fem::Form<double>>> squared_errors;

  /// The functional 1 ds over each named boundary: its length (area in 3D)
  std::map<std::string, std::shared_ptr<const dolfinx::fem::Form<double>>> boundary_measures;
};
} // namespace piezocontact
