// Per-field Newton convergence test of the C++ time loop (the reference
// engine has a test of its own, on the increments:
// python/piezocontact/reference.py).
//
// In SI units the u-block of the Jacobian is ~1e11 and the phi-block ~1e-10,
// so one residual norm sees only u. Both fields are measured in the
// Jacobi-scaled system D^-1/2 J D^-1/2 (D^1/2 x) = D^-1/2 F, D = |diag J|,
// where both blocks are O(1). Per field f:
//   r_f = ||D^-1/2 F||_f,  s_f = ||D^1/2 x||_f,
// converged when r_f <= rtol s_f + atol s_f^0 for every f, s_f^0 = s_f at the
// solve's first iterate (the predictor). Each field in its own scale: a floor
// from the other field's (a huge contact penalty inflates s_u) would accept
// a phi that was never solved for. The time loop also requires the forces to
// balance (diagnostics.h). Where coupling terms dwarf a field's diagonal
// (e 1e9 times a real material's) its scaled residual stalls at round-off
// above rtol: the loop then stops (exit 3) rather than accept it unverified.
// Dirichlet dofs are left out: their rows hold x - g under an arbitrary unit
// diagonal, so a 20 V electrode would otherwise weigh 20 in s_phi where a
// free dof weighs ~1e-4.
#pragma once

#include <map>
#include <mpi.h>
#include <petscmat.h>
#include <span>
#include <string>
#include <vector>

namespace piezocontact
{
struct FieldNorms
{
  double residual;        ///< ||F_f||_2 in SI units
  double scaled_residual; ///< r_f
  double relative;        ///< r_f / s_f; NaN (null in JSON) while s_f = 0 < r_f
};

class FieldwiseConvergence
{
public:
  /// field_dofs: field name -> local W-dofs (ghosts are filtered out);
  /// bc_dofs: W-dofs of Dirichlet conditions, left out
  FieldwiseConvergence(const std::map<std::string, std::vector<std::int32_t>>& field_dofs,
                       const std::vector<std::int32_t>& bc_dofs,
                       std::int32_t num_owned, double rtol, double atol,
                       MPI_Comm comm);

  /// Take D = |diag J| from an assembled Jacobian
  void set_scaling(Mat A);

  /// Record one iterate (owned parts of x and F); true when converged. A
  /// solve starts with an empty `history`.
  bool check(std::span<const double> x, std::span<const double> b);

  /// Norms of every recorded iterate of the current solve
  std::vector<std::map<std::string, FieldNorms>> history;

private:
  std::map<std::string, std::vector<std::int32_t>> _dofs;
  std::vector<double> _sqrt_d;
  double _rtol, _atol;
  std::map<std::string, double> _s_start; ///< s_f at the solve's first iterate
  MPI_Comm _comm;
};
} // namespace piezocontact
