// Newton's method for the time loop: the one place that knows whose Newton
// iteration runs. Today it is dolfinx's nls::petsc::NewtonSolver (0.5.2,
// 0.9, 0.11), which removes it after 0.11; a replacement changes newton.cpp
// only (docs/dolfinx-versions.md, "The Newton seam", says what it must keep).
//
// Everything that makes our Newton ours stays in the callbacks, so that it
// does not depend on the iteration behind them: the field-wise acceptance
// test (converged), the LU reuse and its checks (J), the floating
// electrodes' correction of the update (update).
#pragma once

#include <functional>
#include <memory>
#include <mpi.h>
#include <petscksp.h>
#include <string>
#include <utility>

namespace piezocontact
{
/// What an iteration calls, in this order: ghosts of x updated, F(x, b),
/// converged(b) (stop if true; its double is the norm reported), J(x, A),
/// KSP solve of A dx = b, update(dx, x).
struct NewtonCallbacks
{
  std::function<void(const Vec x, Vec b)> F;
  Vec b;
  std::function<void(const Vec x, Mat A)> J;
  Mat A;
  std::function<std::pair<double, bool>(const Vec b)> converged;
  std::function<void(const Vec dx, Vec x)> update;
};

class Newton
{
public:
  /// A Newton iteration on `comm` whose KSP reads the PETSc options under
  /// `prefix`; at most `max_iterations` iterations per solve, and no
  /// exception when they run out (solve() says so)
  Newton(MPI_Comm comm, const std::string& prefix, int max_iterations);
  ~Newton();
  Newton(const Newton&) = delete;
  Newton& operator=(const Newton&) = delete;

  /// The linear solver of the iterations, set from the options
  KSP ksp() const;
  void set_callbacks(NewtonCallbacks callbacks);

  /// Iterate from x, in place: (iterations, converged). An exception from a
  /// callback leaves the solve and keeps iteration() where it was thrown.
  std::pair<int, bool> solve(Vec x);
  int iteration() const;
  /// Krylov iterations of the last solve (1 per iteration for LU)
  int krylov_iterations() const;

private:
  struct Impl;
  std::unique_ptr<Impl> _impl;
};
} // namespace piezocontact
