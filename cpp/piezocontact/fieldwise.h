// Per-field Newton convergence test of the C++ time loop (the reference
// engine has a test of its own, on the increments:
// python/piezocontact/reference.py).
//
// In SI units the u-block of the Jacobian is ~1e11 and the phi-block ~1e-10,
// so one residual norm sees only u. Both fields are measured in the
// Jacobi-scaled system D^-1/2 J D^-1/2 (D^1/2 x) = D^-1/2 F, D = |diag J|,
// where both blocks are O(1). Per field f:
//   r_f = ||D^-1/2 F||_f,  s_f = ||D^1/2 x||_f,  d_f = ||D^1/2 dx||_f,
// converged when r_f <= rtol s_f + atol s_f^0 and d_f <= rtol s_f + atol
// s_f^0 for every f, s_f^0 = s_f at the solve's first iterate (the
// predictor), dx the last Newton update. The update bounds the error of the
// iterate it corrected (the residual alone leaves up to cond(J) rtol in x),
// so a solve takes at least one update: with the LU kept, one triangular
// solve and one residual. One update also suffices where it was an exact
// solve of a problem linear across it (the time loop's exact_update: LU, and
// J at the new iterate is the J solved with): its error is then the LU's
// round-off, whatever its size. A field that is zero (phi in a
// short-circuited piezoelectric) has s_f at round-off and its residual is
// the round-off of terms that cancel (e eps(u) of neighbouring cells): no
// rtol s_f can be met. Where s_f <= 1000 eps c_f, c_f the norm of
// D^-1/2 sum_j |J_ij x_j| over f's rows i and the other fields' columns j
// (the size of what they put into f's equations), the field is taken as
// zero and r_f, d_f <= 1000 eps c_f accepted. c_f is computed only for a field
// that fails its test after a Newton step (|J| costs a matrix copy). A field that is not zero has s_f
// of the order of c_f (at D = 0, beta grad phi balances e eps), so the
// gate never opens for it. Each field in its own scale: a floor
// from the other field's (a huge contact penalty inflates s_u) would accept
// a phi that was never solved for. The time loop also requires the forces to
// balance (diagnostics.h). Where coupling terms dwarf a field's diagonal
// (e 1e9 times a real material's) its scaled residual stalls at round-off
// above rtol: the loop then stops (exit 3) rather than accept it unverified.
// Dirichlet dofs are left out: their rows hold x - g under an arbitrary unit
// diagonal, so a 20 V electrode would otherwise weigh 20 in s_phi where a
// free dof weighs ~1e-4.
#pragma once

#include <dolfinx/la/petsc.h>
#include <limits>
#include <map>
#include <memory>
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
  double relative;        ///< r_f / s_f (r_f / c_f for a zero field); NaN (null in JSON) if 0 < r_f
  /// the last Newton update ||D^1/2 dx||_f in the same scale (NaN before
  /// the first update)
  double update = std::numeric_limits<double>::quiet_NaN();
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

  /// Take D = |diag J| from an assembled Jacobian (and |J| if a zero field
  /// needs it). `scaled_in_place`: the caller then scales A to
  /// D^-1/2 A D^-1/2 (the iterative solver), which |J| is read as
  void set_scaling(Mat A, bool scaled_in_place = false);

  /// Half the scaled residual the test would accept at the last recorded
  /// iterate, for the field that asks most (never below round-off of the
  /// state): what a linear solve of the next Newton step must reach
  double krylov_atol() const { return _krylov_atol; }

  /// Record one iterate (owned parts of x and F); true when converged. A
  /// solve starts with an empty `history`.
  bool check(std::span<const double> x, std::span<const double> b);

  /// At the last check, after an update: every field passed the residual
  /// part of the test (the update part aside)
  bool residuals_converged() const { return _residuals_converged; }

  /// Norms of every recorded iterate of the current solve
  std::vector<std::map<std::string, FieldNorms>> history;

private:
  /// c_f of each field (in _dofs order) at x (owned entries), by J as last
  /// set_scaling. Collective.
  std::vector<double> coupling(std::span<const double> x);
  Mat _A = nullptr;
  bool _scaled = false; ///< _A holds D^-1/2 J D^-1/2
  bool _abs_stale = true;
  double _krylov_atol = 0.0;
  /// |J| entry by entry (null if J is not an AIJ matrix: no c_f then)
  std::unique_ptr<dolfinx::la::petsc::Matrix> _abs_A;
  std::unique_ptr<dolfinx::la::petsc::Vector> _in, _out;
  std::map<std::string, std::vector<std::int32_t>> _dofs;
  std::vector<double> _sqrt_d;
  double _rtol, _atol;
  std::map<std::string, double> _s_start; ///< s_f at the solve's first iterate
  std::vector<double> _x_last;            ///< the last iterate checked (owned entries)
  bool _residuals_converged = false;
  MPI_Comm _comm;
};
} // namespace piezocontact
