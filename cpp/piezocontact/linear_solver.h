// What the Newton KSP needs beyond its PETSc options.
//
// Either solver: with pc_type fieldsplit, the u and phi dofs as named
// splits (u blocked by d, for nodal AMG), and a check after every solve
// (dolfinx's KrylovSolver ignores a failed solve; here a failed LU or
// Krylov solve is an exception the time loop handles).
//
// The symmetric form (docs/solvers.md): J = [[K, C], [-C^T, beta]] of the
// paper's problem is symmetric once its electric rows are negated, D J with
// D = diag(1 on u, -1 on phi). At each factorisation D J is checked (its
// Jacobi-scaled entries symmetric to round-off); if it is, the KSP solves
// D J dx = D b with MUMPS' LDL^T (SYM = 2: half the factor entries, half
// the bytes each triangular solve reads), otherwise J dx = b with its LU.
// The hooks around every KSPSolve apply D to b (and restore b after), so
// the Newton step, the floating electrodes' responses and the residual the
// loop reads are those of J. A user's term that breaks the symmetry (a
// contact law or residual of theirs) falls back to LU at that factorisation.
//
// The iterative solver (solver.linear = "iterative"; docs/solvers.md):
//  * Jacobi scaling as a change of variables: J is scaled in place to
//    S J S, S = |diag J|^-1/2 (the variables of the fieldwise Newton test,
//    where u and phi are both O(1); in SI units their blocks differ by 1e22),
//    and hooks around every KSPSolve on this KSP map b <- S b before and
//    x <- S x after. Right-preconditioned GMRES then minimises the scaled
//    residual, the norm the Newton test measures.
//  * the Krylov tolerance of each solve tied to the Newton test: stop when
//    the scaled residual is half what Newton would accept for the current
//    iterate (FieldwiseConvergence::krylov_atol), so that an unchanged
//    operator gives Newton's iteration counts of LU.
//  * the rigid body modes (d translations, d(d-1)/2 rotations) as the near
//    null space of the u block, times D^1/2 (the modes of S K S), for AMG
//    on that block; rotations only for BoomerAMG (it has the translations).
//  * the preconditioner is set up when J changes, timed here (fieldsplit
//    sets its blocks up lazily in the first solve otherwise), kept while J
//    is unchanged, and lagged across changes of the contact part only (the
//    penalty rows are a boundary term of the u block) until a solve needs
//    more than twice the iterations per decade of residual reduction of the
//    best solve since the set-up. (GAMG keeps its prolongator across
//    set-ups with the same sparsity, PETSc's default: a set-up recomputes
//    the coarse operators.)
#pragma once

#include "problem.h"
#include "settings.h"

#include <limits>
#include <petscksp.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace piezocontact
{
/// A linear solve that failed (Krylov divergence, a failed factorisation).
/// `retry`: a shorter time step may cure it (not an out-of-memory LU);
/// `hint`: what to do instead
class LinearSolveFailure : public std::runtime_error
{
public:
  LinearSolveFailure(const std::string& what, bool retry, const std::string& hint = "")
      : std::runtime_error(what), retry(retry), hint(hint)
  {
  }
  bool retry;
  std::string hint;
};

class LinearSolverSetup
{
public:
  /// After the KSP's options were set: splits and hooks. `symmetric`: the
  /// direct solver may factorise D J by LDL^T when it is symmetric (the
  /// KSP's PC is then ours to switch between LU and Cholesky)
  LinearSolverSetup(KSP ksp, const Problem& p, LinearSolver kind, bool symmetric);
  ~LinearSolverSetup();
  LinearSolverSetup(const LinearSolverSetup&) = delete;
  LinearSolverSetup& operator=(const LinearSolverSetup&) = delete;

  bool iterative() const { return _kind == LinearSolver::iterative; }

  /// J was assembled anew (unscaled) into M: scale it (iterative), hand it
  /// to the KSP and set up the preconditioner, sub-blocks included (lagged
  /// if allowed: not after a change of k). Returns true if it was set up
  /// anew (false: lagged)
  bool operator_changed(Mat M, bool k_changed);

  /// The absolute tolerance of the next Newton solve, in the scaled norm
  void set_newton_tolerance(double atol);

  /// For other solves with the same operator (floating electrodes' unit
  /// responses): a relative tolerance
  void set_relative_tolerance();

  /// After a solve: throw LinearSolveFailure if it failed; returns its
  /// Krylov iterations
  int check_solve(const std::string& what);

  int setups = 0, lagged = 0;
  /// factorisations of D J by LDL^T and of J by LU (direct solver)
  int ldlt = 0, lu = 0;
  /// entries in the factors of the last factorisation (MUMPS INFOG(29); 0
  /// for other packages)
  double factor_entries = 0.0;
  /// the fill-reducing ordering MUMPS used (its INFOG(7)), "" for others
  std::string factor_ordering;
  /// LDL^T refactorised with pivoting, D J not being quasi-definite
  bool pivoting() const { return _pivoting; }
  /// largest scaled asymmetry of D J seen at a factorisation (matrices.h:
  /// LDL^T at most symmetry_tolerance): round-off for the paper's forms
  double symmetry_defect = 0.0;
  /// "LU", "LDLT" or "LDLT and LU" (direct), "" (iterative)
  std::string factorisations() const;

private:
  /// Direct solver: LDL^T of D M if it is symmetric (M negated in place),
  /// else LU of M
  void choose_factorisation(Mat M);
  void make_signs(const Problem& p);
  /// KSPSetUp of D J by LDL^T without pivoting, checked by its inertia
  /// (with pivoting if that fails)
  void factorise_quasi_definite();
  void make_splits(const Problem& p);
  void scale(Mat M);
  void attach_near_nullspace();
  void set_up_blocks();
  void record_factor_entries();
  [[noreturn]] void factorisation_failed(const std::string& what) const;
  static PetscErrorCode pre_solve(KSP, Vec b, Vec x, void* ctx);
  static PetscErrorCode post_solve(KSP, Vec b, Vec x, void* ctx);

  KSP _ksp;
  LinearSolver _kind;
  MPI_Comm _comm;
  IS _is_u = nullptr, _is_phi = nullptr;
  Vec _s = nullptr; ///< |diag J|^-1/2 (1 where the diagonal is 0)
  Vec _sign = nullptr;   ///< D: 1 on u dofs, -1 on phi dofs
  bool _negated = false; ///< the operator in the KSP is D J
  bool _pivoting = false; ///< D J was not quasi-definite: LDL^T with pivoting
  PetscInt _phi_rows = 0; ///< global: the negative pivots of quasi-definite D J
  Mat _operator = nullptr;
  int _dim;
  bool _symmetric; ///< LDL^T allowed
  /// coordinates of the owned u nodes, in the u split's order (x, y, z each)
  std::vector<double> _node_x;
  Vec _b_saved = nullptr; ///< the caller's right-hand side, restored exactly
  double _b_norm = 0.0;   ///< ||S b|| of the current solve
  PetscReal _rtol = 1e-12;
  PetscInt _max_it = 500;
  /// fewest Krylov iterations per decade of residual reduction since the set-up
  double _best_rate = std::numeric_limits<double>::infinity();
  bool _stale = false; ///< the lagged preconditioner has become too weak
};
} // namespace piezocontact
