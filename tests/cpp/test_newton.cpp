// The Newton seam (newton.h): the contract the time loop relies on, whatever
// iteration runs behind it (dolfinx's NewtonSolver today, SNES for 0.12):
// the callbacks' order, the stop on our own test, running out of iterations
// without an exception, and a callback's exception leaving solve().
// On x_i^2 = a_i (2 dofs), from x = 1.
#include <piezocontact/newton.h>

#include <cmath>
#include <gtest/gtest.h>
#include <petscmat.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using namespace piezocontact;

constexpr std::array<double, 2> a = {2.0, 9.0};

struct Squares
{
  Squares()
  {
    VecCreateSeq(PETSC_COMM_SELF, 2, &x);
    VecDuplicate(x, &b);
    MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 1, nullptr, &A);
    VecSet(x, 1.0);
  }
  ~Squares()
  {
    VecDestroy(&x);
    VecDestroy(&b);
    MatDestroy(&A);
  }

  NewtonCallbacks callbacks()
  {
    return {.F = [this](const Vec xi, Vec r)
            {
              calls += "F";
              const double* xa;
              VecGetArrayRead(xi, &xa);
              for (PetscInt i = 0; i < 2; ++i)
                VecSetValue(r, i, xa[i] * xa[i] - a[i], INSERT_VALUES);
              VecRestoreArrayRead(xi, &xa);
              VecAssemblyBegin(r);
              VecAssemblyEnd(r);
            },
            .b = b,
            .J = [this](const Vec xi, Mat M)
            {
              calls += "J";
              const double* xa;
              VecGetArrayRead(xi, &xa);
              for (PetscInt i = 0; i < 2; ++i)
                MatSetValue(M, i, i, 2 * xa[i], INSERT_VALUES);
              VecRestoreArrayRead(xi, &xa);
              MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY);
              MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY);
            },
            .A = A,
            .converged = [this](const Vec r)
            {
              calls += "C";
              PetscReal norm;
              VecNorm(r, NORM_2, &norm);
              return std::pair<double, bool>{norm, norm < 1e-12};
            },
            .update = [this](const Vec dx, Vec xi)
            {
              calls += "U";
              if (++updates == throw_at)
                throw std::runtime_error("update " + std::to_string(updates));
              VecAXPY(xi, -1.0, dx);
            }};
  }

  Vec x, b;
  Mat A;
  std::string calls;
  int updates = 0, throw_at = -1;
};

TEST(Newton, SolvesOnOurTestInTheLoopsOrder)
{
  Squares s;
  Newton newton(PETSC_COMM_SELF, "newtontest_", 50);
  newton.set_callbacks(s.callbacks());
  const auto [its, converged] = newton.solve(s.x);
  EXPECT_TRUE(converged);
  const double* xa;
  VecGetArrayRead(s.x, &xa);
  for (int i = 0; i < 2; ++i)
    EXPECT_NEAR(xa[i], std::sqrt(a[i]), 1e-12 * std::sqrt(a[i]));
  VecRestoreArrayRead(s.x, &xa);
  // F and our test at x0, then per iteration J, the solve, the update, F,
  // the test; quadratic convergence from 1 to sqrt(9): 6 iterations
  std::string expected = "FC";
  for (int i = 0; i < its; ++i)
    expected += "JUFC";
  EXPECT_EQ(s.calls, expected);
  EXPECT_EQ(newton.iteration(), its);
  EXPECT_GE(its, 4);
  EXPECT_LE(its, 8);
  EXPECT_GE(newton.krylov_iterations(), its);
}

TEST(Newton, RunsOutOfIterationsWithoutAnException)
{
  Squares s;
  Newton newton(PETSC_COMM_SELF, "newtontest_", 2);
  newton.set_callbacks(s.callbacks());
  const auto [its, converged] = newton.solve(s.x);
  EXPECT_FALSE(converged);
  EXPECT_EQ(its, 2);
}

TEST(Newton, ACallbacksExceptionLeavesTheSolveAndTheSolverUsable)
{
  Squares s;
  Newton newton(PETSC_COMM_SELF, "newtontest_", 50);
  s.throw_at = 2;
  newton.set_callbacks(s.callbacks());
  EXPECT_THROW(newton.solve(s.x), std::runtime_error);
  EXPECT_EQ(s.updates, 2);
  EXPECT_EQ(s.calls, "FCJUFCJU");
  s.throw_at = -1;
  EXPECT_TRUE(newton.solve(s.x).second); // from where it stopped
}
} // namespace
