// The discrete problem: the mixed P1 space on the mesh, the runtime
// Constants and the ffcx-compiled forms of forms/piezo_contact.ufl, the BCs.
// Mirrors demos/piezocontact/problem.py; no term of the weak form is written
// here.
#pragma once

#include "config.h"
#include "manufactured_solution.h"
#include "mesh.h"

#include <array>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/MeshTags.h>
#include <map>
#include <memory>
#include <mpi.h>
#include <string>
#include <vector>

namespace piezo
{
using namespace dolfinx;

struct Problem
{
  Problem(const json& cfg, MPI_Comm comm, const std::string& source,
          const std::optional<std::filesystem::path>& mesh_file);

  /// Copy the mixed solution x into the collapsed u and phi
  void update_fields();

  /// Facets (local indices) of a named boundary
  std::vector<std::int32_t> boundary_facets(const std::string& name) const;

  json cfg;
  MPI_Comm comm;
  std::shared_ptr<mesh::Mesh> mesh;
  std::shared_ptr<mesh::MeshTags<std::int32_t>> facet_tags;
  std::map<std::string, int> tag_of; ///< boundary name -> facet tag (slot + 1)

  std::shared_ptr<fem::FunctionSpace> W, V_u, V_phi;
  std::vector<std::int32_t> u_dofs, phi_dofs; ///< W-dofs of each field
  std::shared_ptr<fem::Function<double>> x, x_prev, u, phi;
  std::map<std::string, std::shared_ptr<fem::Constant<double>>> constants;

  std::shared_ptr<fem::Form<double>> F, J, J_contact;
  std::array<std::shared_ptr<fem::Form<double>>, 2> contact_force;
  std::shared_ptr<fem::Expression<double>> D_expr, stress_expr;
  /// Set with the config key "manufactured": its residual replaces the
  /// model's F, its exact fields are the "exact" Dirichlet data
  std::unique_ptr<ManufacturedSolution> manufactured;

  std::vector<std::shared_ptr<const fem::DirichletBC<double>>> bcs;
  std::vector<std::int32_t> bc_dofs; ///< W-dofs of every Dirichlet condition
  /// clamped boundary -> W-dofs of its u_x and u_y components
  std::map<std::string, std::array<std::vector<std::int32_t>, 2>> clamped_dofs;

private:
  void set_constants();
  void create_bcs();
};
} // namespace piezo
