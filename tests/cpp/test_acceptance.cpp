// The acceptance rule (acceptance.h) and its per-field test (fieldwise.h),
// on a 4-dof system with the scales of a piezoelectric one: u rows ~1e11,
// phi rows ~1e-10 (SI units).
#include <piezocontact/acceptance.h>
#include <piezocontact/fieldwise.h>

#include <cmath>
#include <gtest/gtest.h>
#include <petscmat.h>

namespace
{
using namespace piezocontact;

/// PETSc (and MPI) for the whole test program
class Petsc : public ::testing::Environment
{
public:
  void SetUp() override { PetscInitializeNoArguments(); }
  void TearDown() override { PetscFinalize(); }
};
const auto* const petsc = ::testing::AddGlobalTestEnvironment(new Petsc);

constexpr double rtol = 1e-10, atol = 1e-12;
const std::array<double, 4> diag = {2e11, 1e11, 4e-10, 1e-10};
const std::array<double, 4> solution = {1e-6, 2e-6, 10.0, 20.0};

/// J = diag(...) and the test of the fields u = {0, 1}, phi = {2, 3}
struct System
{
  explicit System(std::vector<std::int32_t> bc_dofs = {})
      : test({{"u", {0, 1}}, {"phi", {2, 3}}}, bc_dofs, 4, rtol, atol, PETSC_COMM_SELF)
  {
    MatCreateSeqAIJ(PETSC_COMM_SELF, 4, 4, 1, nullptr, &J);
    for (PetscInt i = 0; i < 4; ++i)
      MatSetValue(J, i, i, diag[i], INSERT_VALUES);
    MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY);
    test.set_scaling(J);
  }
  ~System() { MatDestroy(&J); }

  /// Check x with its residual F = J (x - solution)
  bool check(const std::array<double, 4>& x)
  {
    std::array<double, 4> F;
    for (int i = 0; i < 4; ++i)
      F[i] = diag[i] * (x[i] - solution[i]);
    return test.check(x, F);
  }
  Mat J;
  FieldwiseConvergence test;
};
} // namespace

TEST(Fieldwise, NeverAcceptsBeforeAnUpdate)
{
  System s;
  EXPECT_FALSE(s.check(solution)); // the exact solution, but unverified
  EXPECT_TRUE(s.check(solution));  // an update of zero verifies it
}

// ||F||_2 is 2e-12 here (phi off by 1e-3 of itself), far below any rtol of
// the u forces (~1e5): only a test per field sees it
TEST(Fieldwise, SeesAPotentialTheTwoNormMisses)
{
  System s;
  s.check(solution);
  auto x = solution;
  x[3] *= 1.0 + 1e-3;
  EXPECT_FALSE(s.check(x));
  const FieldNorms phi = s.test.history.back().at("phi");
  // r = D^-1/2 F, s = ||D^1/2 x||: r / s computed independently
  const double r = std::sqrt(diag[3]) * 1e-3 * solution[3];
  const double size = std::sqrt(diag[2] * 100.0 + diag[3] * x[3] * x[3]);
  EXPECT_NEAR(phi.relative, r / size, 1e-12 * r / size);
  EXPECT_LT(s.test.history.back().at("u").relative, rtol);
}

// A residual of zero after a large update is not accepted: the update
// bounds the error of the iterate it corrected
TEST(Fieldwise, WantsTheLastUpdateSmall)
{
  System s;
  auto x = solution;
  x[0] *= 2.0;
  s.check(x);
  EXPECT_FALSE(s.check(solution));
  EXPECT_TRUE(s.test.residuals_converged());
  EXPECT_TRUE(s.check(solution));
}

// Dirichlet rows hold x - g under an arbitrary unit diagonal: left out
TEST(Fieldwise, LeavesOutDirichletDofs)
{
  System s({3});
  auto x = solution;
  x[3] = 1e6;
  s.check(x);
  EXPECT_TRUE(s.check(x));
}

TEST(Acceptance, NeedsEveryPart)
{
  Acceptance a;
  a.fields = true;
  EXPECT_TRUE(a.accepted(rtol));
  a.charges = 10 * rtol;
  EXPECT_FALSE(a.accepted(rtol));
  a.charges = rtol;
  EXPECT_TRUE(a.accepted(rtol));
  a.imbalance = 2 * balance_tolerance;
  EXPECT_FALSE(a.accepted(rtol));
  a.imbalance = balance_tolerance;
  EXPECT_TRUE(a.accepted(rtol));
  a.fields = false;
  EXPECT_FALSE(a.accepted(rtol));
}

TEST(Acceptance, TheImbalanceClauseNamesThePenalty)
{
  Acceptance a;
  EXPECT_EQ(imbalance_clause(a, std::nullopt), "");
  a.imbalance = 0.25;
  EXPECT_EQ(imbalance_clause(a, std::nullopt),
            ", forces unbalanced by 2.500e-01 of the contact and support forces (too "
            "ill-conditioned for double precision?)");
  EXPECT_EQ(imbalance_clause(a, 1e30),
            ", forces unbalanced by 2.500e-01 of the contact and support forces (too "
            "ill-conditioned for double precision? contact.c_p = 1.000e+30)");
}
