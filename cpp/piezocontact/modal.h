// Natural frequencies and mode shapes about a state: K x = omega^2 M x on
// the reduced, constrained matrices of a Linearisation (SLEPc).
//
// M has no phi block and K's electric block is negative definite once its
// rows are negated (K is then symmetric, an indefinite pencil with M only
// semi-definite): shift-and-invert, (K - sigma M)^-1 M, on the LU in use
// (MUMPS). Its eigenvalues 1 / (lambda - sigma) put the wanted lambda
// nearest sigma first and send the infinite ones (phi dofs, removed dofs:
// rows of K with nothing in M) to 0, out of reach; no phi elimination is
// needed, the LU condenses it. sigma: (2 pi target)^2, or, for the lowest
// modes, slightly below 0 so that K - sigma M stays regular when rigid-body
// modes make K singular (they come out at about 0 Hz). A pencil that is not
// Hermitian (Nitsche's method on a piezoelectric contact boundary: its normal
// stress holds the electric field) is solved as a standard problem on the
// dofs with mass, v -> (K - sigma M)^-1 M v restricted to them: phi is
// eliminated by the same LU.
#pragma once

#include "linearisation.h"
#include "settings.h"

#include <vector>

namespace piezocontact
{
struct Mode
{
  double eigenvalue = 0.0; ///< omega^2 (rad^2/s^2)
  double frequency = 0.0;  ///< Hz: sqrt(omega^2) / (2 pi), negative if omega^2 < 0 (round-off of a rigid mode)
  double error = 0.0;      ///< SLEPc's relative residual ||K x - lambda M x|| / ||lambda x||
  /// The shape on the full space (owned entries), normalised to x^T M x = 1
  /// (its largest entry positive)
  std::vector<double> x;
};

/// What a modal solve cost (docs/benchmarks.md): the LU of K - sigma M, the
/// eigensolver after it and the linear solves (operator applications) it made
struct ModalCost
{
  double factorisation_s = 0.0, eigensolver_s = 0.0;
  int solves = 0;
  /// One solve on the factorisation, timed after the eigensolver: the
  /// floor of shift-and-invert is factorisation_s + solves * solve_s
  double solve_s = 0.0;
  /// The pencil was Hermitian (GHEP), else solved condensed on the dofs with mass
  bool hermitian = true;
  /// At most as many modes as dofs with mass
  long dofs_with_mass = 0;
  /// Entries of the LU factors (MUMPS' INFOG(29)): a solve reads them twice
  double factor_entries = 0.0;
};

/// The `settings.modes` modes nearest the target (ascending frequency);
/// fewer if the eigensolver converged fewer. Collective.
std::vector<Mode> natural_modes(const Linearisation& lin, const AnalysisSettings& settings,
                                ModalCost* cost = nullptr);
} // namespace piezocontact
