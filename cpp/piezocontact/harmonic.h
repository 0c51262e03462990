// The steady response to time-harmonic data, x e^{i omega t}, about a
// state: (K + i omega C - omega^2 M) x = F on the reduced, constrained
// matrices of a Linearisation, as the real block system
//   [K - omega^2 M   -omega C      ] [x_re]   [F]
//   [omega C          K - omega^2 M] [x_im] = [0]
// (the data have phase 0: F real), factorised by MUMPS at every frequency
// (each is a new matrix). A real form rather than Debian's complex PETSc
// build: one build of PETSc, dolfinx and our kernels serves both analyses,
// and the block system's LU costs what the complex one does (the same
// fill, twice the scalars of half the size; docs/dynamics.md).
//
// F: the applied loads (Model::L) at the data's values, each floating
// electrode's charge on its merged row; a prescribed displacement or
// potential (a driven electrode) is lifted: x_re = its value on its dofs.
#pragma once

#include "linearisation.h"

#include <vector>

namespace piezocontact
{
/// The response at one frequency: x_re, x_im on the full space (owned
/// entries), and the residual K x - F of each (unconstrained, owned
/// entries) whose electric entries are the electrodes' reaction charges
struct HarmonicResponse
{
  double frequency = 0.0;
  std::vector<double> re, im, residual_re, residual_im;
  /// What it cost: forming the block system, its LU, the solve (s)
  double assembly_s = 0.0, factorisation_s = 0.0, solve_s = 0.0;
};

class HarmonicSolver
{
public:
  /// The drive of the Problem's data at its current time. Throws
  /// ConfigError (naming `source`) when nothing is driven. Collective.
  HarmonicSolver(Problem& p, const Linearisation& lin, const std::string& source);
  ~HarmonicSolver();
  HarmonicSolver(const HarmonicSolver&) = delete;
  HarmonicSolver& operator=(const HarmonicSolver&) = delete;

  /// The response at f Hz (a singular system: throws LinearSolveFailure). Collective.
  HarmonicResponse solve(double f);

private:
  const Linearisation& _lin;
  Mat _K = nullptr, _C = nullptr, _M = nullptr;     ///< reduced, constrained
  Vec _F = nullptr, _g = nullptr;                   ///< reduced drive; lifted values (full)
  Vec _Kg = nullptr, _Cg = nullptr, _Mg = nullptr;  ///< the unconstrained reduced matrices times g
  Vec _L = nullptr;                                 ///< full loads, for the residual
};
} // namespace piezocontact
