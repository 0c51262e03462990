#include "newton.h"

#include <dolfinx/la/petsc.h>
#include <dolfinx/nls/NewtonSolver.h>
#include <iostream>
#include <optional>

namespace piezocontact
{
using dolfinx::nls::petsc::NewtonSolver;

namespace
{
/// std::cerr swallowed for a scope: dolfinx 0.11's NewtonSolver constructor
/// writes a deprecation notice there, on every rank and every run, and our
/// stderr carries one-line errors only
struct SilencedCerr
{
  SilencedCerr() : saved(std::cerr.rdbuf(nullptr)) {}
  ~SilencedCerr() { std::cerr.rdbuf(saved); } // also clears the bad bit
  SilencedCerr(const SilencedCerr&) = delete;
  SilencedCerr& operator=(const SilencedCerr&) = delete;
  std::streambuf* saved;
};
} // namespace

struct Newton::Impl
{
  explicit Impl(MPI_Comm comm) : solver(comm) { quiet.reset(); }
  std::optional<SilencedCerr> quiet{std::in_place}; ///< while `solver` is made
  NewtonSolver solver;
};

Newton::Newton(MPI_Comm comm, const std::string& prefix, int max_iterations)
    : _impl(std::make_unique<Impl>(comm))
{
  NewtonSolver& s = _impl->solver;
  s.get_krylov_solver().set_options_prefix(prefix);
  s.get_krylov_solver().set_from_options();
  s.max_it = max_iterations;
  s.report = false;
  s.error_on_nonconvergence = false;
}

Newton::~Newton() = default;

KSP Newton::ksp() const { return _impl->solver.get_krylov_solver().ksp(); }

void Newton::set_callbacks(NewtonCallbacks c)
{
  NewtonSolver& s = _impl->solver;
  s.setF(std::move(c.F), c.b);
  s.setJ(std::move(c.J), c.A);
  s.set_form(
      [](Vec x)
      {
        VecGhostUpdateBegin(x, INSERT_VALUES, SCATTER_FORWARD);
        VecGhostUpdateEnd(x, INSERT_VALUES, SCATTER_FORWARD);
      });
  // dolfinx's own test keeps residual0 across solves and sees only u
  s.set_convergence_check([converged = std::move(c.converged)](const NewtonSolver&, const Vec r)
                          { return converged(r); });
  s.set_update([update = std::move(c.update)](const NewtonSolver&, const Vec dx, Vec x)
               { update(dx, x); });
}

std::pair<int, bool> Newton::solve(Vec x) { return _impl->solver.solve(x); }

int Newton::iteration() const { return _impl->solver.iteration(); }

int Newton::krylov_iterations() const { return _impl->solver.krylov_iterations(); }
} // namespace piezocontact
