// The matrices of the model linearised about a state, for dynamic analyses
// (SPEC: dynamics): K x'' ... (K + i omega C - omega^2 M) x = F.
//
// K is the sum of Model::K (each residual term's derivative with the
// velocity held: the tangent of the equilibrium equations, contact law and
// user terms included, without the backward-Euler term), C of Model::C (the
// viscosity), M of Model::M (rho, on u only: no phi block). The state is
// the Problem's x, at rest (velocity zero).
//
// Constraints, as the quasistatic solve has them:
//  * a Dirichlet condition (a clamp, a prescribed potential: a short
//    circuit) holds its dofs; they are removed by zero rows and columns,
//    with 1 on K's diagonal and 0 on M's and C's: their eigenvalues are
//    infinite, mapped to 0 by shift-and-invert and never among the modes
//    requested, and a harmonic solve gives them the prescribed amplitude;
//  * a floating electrode (an open circuit) is one unknown, its uniform
//    potential, whose equation is its total charge: the reduction
//    x = P z merges its dofs into one (its representative, the lowest
//    global index), K_r = P^T K P (the merged row is the sum of the
//    electrode's rows: its charge), and the other dofs of the electrode are
//    removed like Dirichlet dofs.
#pragma once

#include "problem.h"

#include <dolfinx/la/petsc.h>
#include <optional>
#include <petscmat.h>
#include <vector>

namespace piezocontact
{
class Linearisation
{
public:
  /// Assemble K, C and M at p.x (the velocity set to zero). Collective.
  explicit Linearisation(Problem& p);

  /// The unconstrained sums (full space): the reactions and charges of a
  /// response are read from K (its electric rows have no C and no M)
  const dolfinx::la::petsc::Matrix& K() const { return _K; }

  /// A matrix (K, C or M) reduced and constrained: P^T A P, the removed
  /// dofs' rows and columns zero with `diagonal` on the diagonal; `flip`:
  /// the electric rows negated first (K: symmetric when the model is, so
  /// that the eigenproblem is a generalised Hermitian one). Caller owns.
  Mat reduced(const dolfinx::la::petsc::Matrix& A, double diagonal, bool flip = false) const;

  /// P^T A P only (the lifting of a harmonic solve needs it unconstrained).
  /// Caller owns.
  Mat reduced_unconstrained(const dolfinx::la::petsc::Matrix& A) const;

  /// z -> x = P z (into a full vector); x -> P^T x
  void prolong(Vec z, Vec x) const;
  void restrict_to(Vec x, Vec z) const;

  /// Global indices of the owned dofs removed (Dirichlet dofs and the
  /// non-representative dofs of floating electrodes)
  const std::vector<PetscInt>& removed() const { return _removed; }

  /// Global index of each floating electrode's representative dof, by
  /// index in p.electrodes (-1 for the others)
  const std::vector<PetscInt>& representative() const { return _representative; }

  /// Number of floating electrodes
  bool has_floating() const { return _P.has_value(); }

  const dolfinx::la::petsc::Matrix& C() const { return _C; }
  const dolfinx::la::petsc::Matrix& M() const { return _M; }

private:
  void build_reduction(Problem& p);
  dolfinx::la::petsc::Matrix _K, _C, _M;
  std::optional<dolfinx::la::petsc::Matrix> _P;
  std::vector<PetscInt> _removed, _representative;
  Vec _sign = nullptr; ///< +1 on u dofs, -1 on phi dofs
public:
  ~Linearisation();
  Linearisation(const Linearisation&) = delete;
  Linearisation& operator=(const Linearisation&) = delete;
};
} // namespace piezocontact
