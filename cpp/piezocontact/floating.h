// Floating electrodes in Newton's method, on the factorisation in use.
//
// The potential of a floating electrode e is one unknown V_e: its dofs are
// held at V_e by a Dirichlet condition (Problem), and its equation is the
// charge, Q_e(x) = -sum_{i in e} F_i(x) = Q_e^target (F the unconstrained
// residual: the reaction of the electric equation at the electrode, i.e.
// F tested with the sum psi_e of its basis functions, the one test function
// a uniform potential leaves there). A Newton step of the bordered system
// in (x, V) is solved by its Schur complement:
//   J_D dx0 = b                 (the usual step, V held: J_D has identity
//                                rows and columns at every Dirichlet dof)
//   J_D z_f = l_f               (response to a unit potential on f, the rest
//                                held: l_f = -J 1_f off the conditions, 1 on f)
//   sum_f (c_e . z_f) dV_f = rho_e + c_e . dx0,   c_e = J^T 1_e,
//   rho_e = Q_e(x) - Q_e^target
//   x <- x - dx0 + sum_f dV_f z_f.
// The z_f cost one back-substitution per electrode per factorisation (none
// while the LU is reused) and the rest a few dot products per iteration:
// the matrix, its sparsity and the linear solver are the ones without
// floating electrodes. The electric rows of J and its columns at phi dofs
// are linear and state-independent (the contact term tests w only), so c_e
// and J 1_f are taken once from the unconstrained Jacobian; were a user's
// term to make them depend on the state, the steps stay consistent Newton
// steps in V, only with a frozen border, and the test on rho_e below still
// decides convergence.
#pragma once

#include "problem.h"
#include "timing.h"

#include <dolfinx/la/petsc.h>
#include <functional>
#include <optional>
#include <petscksp.h>
#include <span>
#include <vector>

namespace piezocontact
{
class FloatingPotentials
{
public:
  /// `J`: the unconstrained Jacobian (no Dirichlet rows), any state; none
  /// needed without floating electrodes
  FloatingPotentials(Problem& p, const std::optional<dolfinx::la::petsc::Matrix>& J);

  bool empty() const { return _index.empty(); }

  /// After J_D was factorised in `ksp`: the unit responses and the border;
  /// `check` after each solve (it throws if the solve failed)
  void factorised(KSP ksp, const std::function<void()>& check);

  /// Charge residuals from an unconstrained residual (owned entries, before
  /// its Dirichlet rows are set) at the iterate `x` (owned entries)
  void residual(std::span<const double> r, std::span<const double> x);

  /// The Newton update with the potentials: x <- x - dx0 + sum dV_f z_f,
  /// the floating conditions then hold the new potentials
  void update(Vec dx0, Vec x);

  /// max_e |rho_e| / (|c_e|.|x| + |Q_e^target|): round-off once solved
  /// (0 without floating electrodes)
  double relative_residual() const;
  /// max_e |rho_e| (C/m in 2D, C in 3D)
  double residual_norm() const;

  /// What the floating electrodes cost: unit responses, charge residuals,
  /// bordered updates
  OperationStats stats;

private:
  Problem& _p;
  std::vector<std::size_t> _index; ///< the floating ones among p.electrodes
  std::vector<dolfinx::la::petsc::Vector> _c, _abs_c, _l, _z;
  std::vector<double> _rho, _scale, _M; ///< _M: row-major, n x n
};
} // namespace piezocontact
