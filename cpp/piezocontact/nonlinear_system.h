// Residual and Jacobian callbacks of the Newton solver, in the way of dolfinx
// Python's NonlinearProblem.F/J (the 0.5.2 C++ hyperelasticity demo's F
// callback omits the lifting and is no model), plus:
//  * LU reuse (or, iterative, preconditioner reuse): the bulk of J is linear, so J changes between iterates only
//    if its contact part (form J_contact, contact facets only) or k does.
//    That part is assembled and compared exactly with the last one; if equal,
//    J is left untouched and PETSc keeps its factorisation. Any law p is
//    safe: a smooth p changes J_contact at every iterate and J is rebuilt.
//  * the residual of the current iterate before the Dirichlet rows are
//    overwritten (reactions, balance, electrode charges);
//  * floating electrodes (floating.h): their charge residuals, read there
//    too, and their unit responses after each factorisation;
//  * the linear solver's set-up and checks (linear_solver.h);
//  * timings and counts of every operation, for the benchmarks.
#pragma once

#include "fieldwise.h"
#include "floating.h"
#include "linear_solver.h"
#include "problem.h"
#include "timing.h"

#include <array>
#include <dolfinx/la/petsc.h>
#include <petscksp.h>

namespace piezocontact
{
class NonlinearSystem
{
public:
  /// After the KSP's options were set
  /// `symmetric`: LDL^T of the Jacobian with its electric rows negated
  /// whenever that is symmetric (linear_solver.h)
  NonlinearSystem(Problem& p, FieldwiseConvergence& monitor, KSP ksp, bool reuse_lu,
                  LinearSolver linear, bool symmetric);

  void F(const Vec x, Vec r);
  void J(const Vec x, Mat M);
  /// Newton's update after a linear solve (checked: LinearSolveFailure)
  void update(Vec dx, Vec x);

  /// Whether the last update solved the problem exactly (to the LU's
  /// round-off): the solve was direct, and the Jacobian at the current
  /// iterate is the one it used (same contact part, same k), so that F is
  /// affine across the update (with the piecewise-linear p: the same set of
  /// quadrature points in contact at both ends) and F(x) is the LU's
  /// residual. Collective.
  bool exact_update();

  /// The residual vector and the Jacobian matrix (RAII: PETSc objects
  /// destroyed with the system)
  dolfinx::la::petsc::Vector b;
  dolfinx::la::petsc::Matrix A;
  /// factorisation: LU factorisations, or preconditioner set-ups (iterative)
  OperationStats residual, jacobian, contact_jacobian, factorisation;
  int reused = 0; ///< Newton iterations that kept the last factorisation
  /// iterative: Jacobians that kept the last preconditioner set-up (lagged)
  int lagged = 0;
  LinearSolverSetup linear;
  /// the residual at the last evaluation before its Dirichlet rows are set
  /// (owned entries): the accepted step's reactions and charges are read
  /// from it, with no assembly of their own
  std::vector<double> unconstrained;
  /// ... and the balance of forces in it
  ForceBalance balance;
  /// The floating electrodes' potentials and charge equations
  FloatingPotentials floating;
  /// The iterate (local dofs, with ghosts) and k at which the Jacobian in use
  /// was assembled: a resumed run rebuilds the same matrix, LU and scaling
  std::vector<double> x_assembled;
  double k_assembled = 0.0;

private:
  void record_reactions(Vec r);
  Problem& _p;
  FieldwiseConvergence& _monitor;
  KSP _ksp;
  bool _reuse;
  dolfinx::la::petsc::Matrix _Jc;
  std::vector<double> _Jc_last; ///< this rank's values of the last J_contact
  double _k_last = -1.0;
};
} // namespace piezocontact
