// The discrete problem around a Model: collapsed field spaces, the W-dofs of
// each field, the Dirichlet conditions of the settings, and the exact fields
// (if the model has them) at the current time. No term of the weak form is
// written here: the model's forms are driven as they are.
#pragma once

#include "model.h"
#include "settings.h"

#include <array>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/la/Vector.h>
#include <map>
#include <memory>
#include <span>
#include <mpi.h>
#include <string>
#include <vector>

namespace piezocontact
{
/// What a residual says about equilibrium. `unbalanced`: its resultant over
/// the free u dofs, per component, what Newton left (the loads, the contact
/// force and the reactions balance when it is zero); `supported`: the sum
/// of |entries| at the clamped u dofs, the nodal reactions, i.e. the forces
/// that flow through the body to its supports (their resultant may be 0).
struct ForceBalance
{
  std::vector<double> unbalanced;
  double supported = 0.0;
};

class Problem
{
public:
  /// Throws ConfigError if a setting names a boundary the mesh lacks.
  /// `timed`: the model's Constants that vary in time (their values as
  /// set now are scaled by their history at every set_time)
  Problem(Model model, const std::vector<DirichletSettings>& dirichlet,
          const std::string& source, const std::vector<TimedConstant>& timed = {});

  /// Copy the mixed solution x into the collapsed u and phi
  void update_fields();

  /// Set the Constants "k" and (if the model has it) "t", the loads and
  /// Dirichlet values that have a history, and interpolate the exact fields
  /// at t
  void set_time(double t, double k);

  /// sqrt of each squared error functional of the model, on every rank
  std::map<std::string, double> errors() const;

  /// Reaction of each clamped boundary, per u component: the sums of a
  /// residual over its dofs (owned entries of `r`, before the Dirichlet rows
  /// are overwritten), on every rank
  std::map<std::string, std::vector<double>> reactions(std::span<const double> r) const;

  /// The reactions at the current x, from a residual assembled for them
  std::map<std::string, std::vector<double>> reactions() const;

  /// The balance of forces in a residual (owned entries of `r`, before its
  /// Dirichlet rows are set; collective)
  ForceBalance force_balance(std::span<const double> r) const;

  /// The same at the current x, from a residual assembled for it
  ForceBalance force_balance() const;

  /// Sum of |applied loads| over the free u dofs at the current t (the
  /// model's L; 0 without one), at least that of the loads' amplitude when
  /// some vary in time; assembled once per time. Collective.
  double applied_load() const;

  /// A sum of linear forms on W, assembled (ghost contributions added to
  /// their owners)
  dolfinx::la::Vector<double> assemble(const FormList& terms) const;

  /// Spatial dimension
  int dim() const { return mesh->geometry().dim(); }

  Model model;
  MPI_Comm comm;
  std::shared_ptr<dolfinx::mesh::Mesh> mesh;
  std::shared_ptr<const dolfinx::fem::FunctionSpace> W;
  std::shared_ptr<dolfinx::fem::FunctionSpace> V_u, V_phi;
  std::vector<std::int32_t> u_dofs, phi_dofs; ///< W-dofs of each field
  std::shared_ptr<dolfinx::fem::Function<double>> x, x_prev, u, phi;
  /// Exact fields at the current time (null if the model has none)
  std::shared_ptr<dolfinx::fem::Function<double>> u_exact, phi_exact;

  std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>> bcs;
  std::vector<std::int32_t> bc_dofs; ///< W-dofs of every Dirichlet condition
  /// clamped boundary -> W-dofs of each of its u components
  std::map<std::string, std::vector<std::vector<std::int32_t>>> clamped_dofs;

private:
  mutable double _applied_load = -1.0; ///< at the current t; < 0: not yet
  /// A datum scaled in time: where its values live, their value at
  /// factor 1, and its history
  struct Scaled
  {
    std::span<double> values;
    std::vector<double> base;
    History history;
  };
  mutable std::vector<Scaled> _scaled;
  mutable double _load_amplitude = -1.0; ///< applied_load at factor 1; < 0: not yet
  double load_sum() const;
  std::vector<std::shared_ptr<dolfinx::fem::Function<double>>> _scaled_bc_values;
  void create_bcs(const std::vector<DirichletSettings>& dirichlet, const std::string& source);
  /// Scale the values of a Dirichlet function by a history at set_time
  void scale_in_time(const std::shared_ptr<dolfinx::fem::Function<double>>& g,
                     const History& history);
};
} // namespace piezocontact
