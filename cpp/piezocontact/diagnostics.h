// Quantities of interest: per step, probe values, the contact resultant and the largest u.nu - g
// on Gamma_C (the reactions come from the residual: nonlinear_system.h).
#pragma once

#include "acceptance.h"
#include "config.h"
#include "problem.h"

#include <array>
#include <optional>

namespace piezocontact
{
/// Point evaluation of (u, phi); each point on the lowest rank holding it
class Probes
{
public:
  Probes(const Problem& problem, const std::vector<std::array<double, 3>>& points,
         const std::string& source);
  /// (u_x, u_y, (u_z,) phi) per probe, identical on all ranks
  std::vector<std::vector<double>> evaluate(const Problem& problem) const;
  std::vector<std::array<double, 3>> points;

private:
  std::vector<std::size_t> _mine;
  std::vector<std::int32_t> _cells;
};

/// Vertices of the contact facets, their cells and outward unit normals
class ContactGeometry
{
public:
  /// On some facets (local indices)
  ContactGeometry(const Problem& problem, std::span<const std::int32_t> facets);
  /// Largest u.nu - g on the facets (g: the Constant gap plus a field of
  /// it, when the config gives it by an expression); empty without facets
  /// on any rank. Collective.
  std::optional<double> max_normal_gap(const Problem& problem, double gap,
                                       const dolfinx::fem::Function<double>* gap_field) const;

private:
  std::vector<double> _points;  // (n, 3)
  std::vector<std::int32_t> _cells;
  std::vector<std::array<double, 3>> _normals;
};

/// The penetration r of each contact boundary with an obstacle, at the
/// nodes of u's space on its facets (Model::obstacles: the forms' r,
/// interpolated into a scalar field of u's degree on the facets' cells)
class ObstaclePenetration
{
public:
  explicit ObstaclePenetration(const Problem& problem);
  /// Largest r on the boundary's facets (> 0: inside the obstacle); empty
  /// if the boundary has no facets. Collective.
  std::optional<double> largest(const Problem& problem, const std::string& boundary) const;

private:
  struct Part
  {
    std::vector<std::int32_t> cells, dofs;
    std::shared_ptr<const dolfinx::fem::Expression<double>> expression;
  };
  std::map<std::string, std::vector<Part>> _parts;
  /// The boundaries whose block has no obstacle: the paper's foundation
  /// offset by their own gap, measured along the facets' normals
  std::map<std::string, ContactGeometry> _offset;
  std::shared_ptr<dolfinx::fem::Function<double>> _r;
};

/// Resultant force of the foundation and of every obstacle on the body (N/m
/// in 2D, N in 3D)
std::vector<double> contact_force(const Problem& problem);

/// The measure (length in 2D, area in 3D) of one obstacle's boundary where
/// its pressure is positive. Collective.
double obstacle_contact_measure(const Problem& problem, const std::string& boundary);

/// Resultant force of one obstacle on the body. Collective.
std::vector<double> obstacle_force(const Problem& problem, const std::string& boundary);

/// Resultant force of each spring bed on the body, per boundary (N/m in 2D,
/// N in 3D). Collective.
std::map<std::string, std::vector<double>> spring_forces(const Problem& problem);

/// The contact forces in play: the sum of the sizes of the foundation's
/// and of each obstacle's resultant force (obstacles that push from two
/// sides have a resultant near 0 but forces that count). Collective.
double contact_forces_in_play(const Problem& problem);

/// Newton's leftover on the free u dofs relative to the forces in play:
/// |unbalanced| / (supported + contact_forces + applied_load)
/// (ForceBalance, contact_forces_in_play, Problem::applied_load); 0 if no
/// force is in play. A step whose forces balance has it at round-off.
double force_imbalance(const ForceBalance& balance, double contact_forces, double applied_load);

/// force_imbalance at the current state and time, assembling the applied
/// loads only if the other forces do not already show the balance.
/// Collective.
double force_imbalance(const Problem& problem, const ForceBalance& balance);

/// Length (area in 3D) of each named boundary, from Model::boundary_measures.
/// Collective.
std::map<std::string, double> boundary_measures(const Problem& problem);

} // namespace piezocontact
