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

/// A boundary with a prescribed or floating potential
struct Electrode
{
  std::string name;
  /// W-dofs of the potential on it (local, ghosts included)
  std::vector<std::int32_t> dofs;
  bool floating = false;
  /// Floating: its Dirichlet values, the electrode's potential (uniform),
  /// set by the solver; the charge on it: charge * history
  std::shared_ptr<dolfinx::fem::Function<double>> potential;
  double charge = 0.0;
  History history;
  /// Its Dirichlet condition (the reference engine leaves out the floating
  /// ones: it constrains them its own way)
  std::shared_ptr<const dolfinx::fem::DirichletBC<double>> bc;
  /// Floating: the potential its condition holds now
  double held = 0.0;
};

class Problem
{
public:
  /// Throws ConfigError if a setting names a boundary the mesh lacks.
  /// `timed`: the model's Constants that vary in time (their values as
  /// set now are scaled by their history at every set_time); `spatial`:
  /// the data given by expressions, interpolated into the model's fields
  Problem(Model model, const std::vector<DirichletSettings>& dirichlet,
          const std::string& source, const std::vector<TimedConstant>& timed = {},
          const std::vector<SpatialLoad>& spatial = {});

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

  /// The potential of each electrode at x (the mean of its dofs' values:
  /// the value where it is uniform), on every rank. Collective.
  std::vector<double> electrode_potentials(std::span<const double> x) const;

  /// Set the potential of each floating electrode to the value x has on it
  /// (a step starts from x_{n-1}'s). Collective.
  void hold_floating_potentials(std::span<const double> x);

  /// Set the potential a floating electrode's condition holds
  void hold(Electrode& e, double V);

  /// The charge on each electrode by the reaction of the electric residual:
  /// minus the sum of `r` over its dofs (owned entries of an unconstrained
  /// residual), on every rank
  std::vector<double> reaction_charges(std::span<const double> r) const;

  /// The charge int D.nu ds on each electrode at the current x, on every rank
  std::vector<double> electrode_charges() const;

  /// The charge prescribed on each floating electrode at the current t
  /// (0 for the others)
  std::vector<double> target_charges() const;

  /// The lumped contact pressure on the P1 space P (the ratio of the model's
  /// contact_pressure_load and contact_nodal_area at each vertex of Gamma_C,
  /// and of each obstacle's, 0 elsewhere) at the current x, and the measure
  /// of the paper's foundation where it is positive (the contact length in
  /// 2D, area in 3D; the obstacles measure theirs at Gauss points:
  /// diagnostics.h obstacle_contact_measure); 0 without the forms.
  /// Collective.
  double update_contact_pressure();

  /// The largest lumped pressure of one obstacle on its boundary.
  /// Collective.
  double obstacle_max_pressure(const std::string& boundary) const;

  /// A sum of linear forms on one test space (W, or P), assembled (ghost
  /// contributions added to their owners)
  dolfinx::la::Vector<double> assemble(const FormList& terms) const;

  /// Spatial dimension
  int dim() const { return mesh->geometry().dim(); }

  /// The forms; their Constants change with set_time (and the loop's k)
  Model model;
  // What the model's spaces make, fixed at construction
  const MPI_Comm comm;
  const std::shared_ptr<compat::Mesh> mesh;
  const std::shared_ptr<const compat::FunctionSpace> W;
  const std::shared_ptr<compat::FunctionSpace> V_u, V_phi;
  const std::vector<std::int32_t> u_dofs, phi_dofs; ///< W-dofs of each field
  /// The state (x, x_prev on W) and its collapsed fields (update_fields)
  const std::shared_ptr<dolfinx::fem::Function<double>> x, x_prev, u, phi;
  /// Exact fields at the current time (null if the model has none)
  const std::shared_ptr<dolfinx::fem::Function<double>> u_exact, phi_exact;

  /// The Dirichlet conditions, electrodes' included
  const std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>>& bcs() const
  {
    return _bcs;
  }
  /// W-dofs of every Dirichlet condition
  const std::vector<std::int32_t>& bc_dofs() const { return _bc_dofs; }
  /// clamped boundary -> W-dofs of each of its u components
  const std::map<std::string, std::vector<std::vector<std::int32_t>>>& clamped_dofs() const
  {
    return _clamped_dofs;
  }
  /// Every boundary with a potential condition, by name (the solver holds
  /// the floating ones' potentials: hold)
  std::vector<Electrode> electrodes;
  /// The lumped contact pressure (update_contact_pressure; null without a
  /// contact boundary's forms)
  const std::shared_ptr<dolfinx::fem::Function<double>> contact_pressure;

private:
  /// The lumped pressure (the load terms over the area terms at each owned
  /// vertex) into p, and the measure where it is positive
  double lumped_pressure(const FormList& load, const FormList& area, std::span<double> p) const;

  /// A sub-space of W collapsed, and the W-dofs of its dofs
  struct Collapsed
  {
    std::shared_ptr<compat::FunctionSpace> V;
    std::vector<std::int32_t> dofs;
  };
  static Collapsed collapse(const compat::FunctionSpace& W, int i);
  Problem(Model&& model, Collapsed u, Collapsed phi, const std::vector<DirichletSettings>& dirichlet,
          const std::string& source, const std::vector<TimedConstant>& timed,
          const std::vector<SpatialLoad>& spatial);
  std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>> _bcs;
  std::vector<std::int32_t> _bc_dofs;
  std::map<std::string, std::vector<std::vector<std::int32_t>>> _clamped_dofs;
  double _t = 0.0;
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
  mutable double _load_peak = 0.0;       ///< the largest load_sum of loads of t so far
  double load_sum() const;
  std::vector<std::shared_ptr<dolfinx::fem::Function<double>>> _scaled_bc_values;
  /// A datum given by expressions, placed on nodes of its field (the
  /// nodes of its boundary, or all): their points, 3 coordinates each
  struct Placed
  {
    std::shared_ptr<dolfinx::fem::Function<double>> field;
    SpatialDatum datum;
    std::vector<std::int32_t> nodes;
    std::vector<double> points;
  };
  /// Those of them that use t: evaluated again at every set_time
  std::vector<Placed> _evolving;
  std::string _source;
  double _extent = 0.0; ///< the largest |coordinate| of the mesh (its scale)
  /// The largest |coordinate| over the ranks. Collective.
  double extent() const;
  /// Fill a field from a datum's expressions at the nodes on `facets` (all
  /// nodes if null), now and at every set_time (once and scaled by its
  /// history when no expression uses t). Collective.
  void place_spatial(const std::shared_ptr<dolfinx::fem::Function<double>>& field,
                     const SpatialDatum& datum, const std::vector<std::int32_t>* facets);
  /// The field's values at the placed nodes: the datum at time t, times
  /// factor; throws ConfigError where one is not finite. Collective.
  void evaluate(const Placed& placed, double t, double factor) const;
  void fix_on_axis();
  void create_bcs(const std::vector<DirichletSettings>& dirichlet, const std::string& source);
  /// Throws ConfigError if a floating electrode shares a vertex with
  /// another electrode (its potential would be two unknowns at once)
  void check_electrodes_apart(const std::string& source) const;
  /// Scale the values of a Dirichlet function by a history at set_time
  void scale_in_time(const std::shared_ptr<dolfinx::fem::Function<double>>& g,
                     const History& history);
};
} // namespace piezocontact
