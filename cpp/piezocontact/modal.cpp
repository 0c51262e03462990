#include "modal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <slepceps.h>
#include <stdexcept>

namespace piezocontact
{
namespace
{
void check(PetscErrorCode ierr, const char* what)
{
  if (ierr != 0)
    throw std::runtime_error(std::string("SLEPc failed in ") + what);
}

/// Matrices owned here, destroyed on the way out
struct Owned
{
  Mat K = nullptr, M = nullptr;
  EPS eps = nullptr;
  Vec z = nullptr, zi = nullptr, x = nullptr, Mz = nullptr;
  ~Owned()
  {
    for (Mat* m : {&K, &M})
      if (*m)
        MatDestroy(m);
    for (Vec* v : {&z, &zi, &x, &Mz})
      if (*v)
        VecDestroy(v);
    if (eps)
      EPSDestroy(&eps);
  }
};

/// ||K - K^T||_F <= 1e-12 ||K||_F
bool symmetric(Mat K)
{
  Mat Kt;
  MatTranspose(K, MAT_INITIAL_MATRIX, &Kt);
  PetscReal norm = 0, diff = 0;
  MatNorm(K, NORM_FROBENIUS, &norm);
  MatAXPY(Kt, -1.0, K, DIFFERENT_NONZERO_PATTERN);
  MatNorm(Kt, NORM_FROBENIUS, &diff);
  MatDestroy(&Kt);
  return diff <= 1e-12 * norm;
}

/// The mean of K_ii / M_ii over the dofs with mass: the scale of the
/// highest eigenvalues (about c^2 / h^2)
double diagonal_ratio(Mat K, Mat M)
{
  Vec k, m;
  MatCreateVecs(K, &k, &m);
  MatGetDiagonal(K, k);
  MatGetDiagonal(M, m);
  const PetscScalar *kv, *mv;
  PetscInt n;
  VecGetLocalSize(k, &n);
  VecGetArrayRead(k, &kv);
  VecGetArrayRead(m, &mv);
  double sum[2] = {0.0, 0.0};
  for (PetscInt i = 0; i < n; ++i)
    if (mv[i] > 0)
    {
      sum[0] += kv[i] / mv[i];
      sum[1] += 1.0;
    }
  VecRestoreArrayRead(k, &kv);
  VecRestoreArrayRead(m, &mv);
  MPI_Comm comm;
  PetscObjectGetComm(PetscObject(K), &comm);
  MPI_Allreduce(MPI_IN_PLACE, sum, 2, MPI_DOUBLE, MPI_SUM, comm);
  VecDestroy(&k);
  VecDestroy(&m);
  return sum[1] > 0 ? sum[0] / sum[1] : 1.0;
}

/// The owned entries of x with its largest entry made positive
std::vector<double> signed_entries(Vec x)
{
  const PetscScalar* v;
  PetscInt n;
  VecGetLocalSize(x, &n);
  VecGetArrayRead(x, &v);
  std::vector<double> out(v, v + n);
  VecRestoreArrayRead(x, &v);
  std::array<double, 2> local = {0.0, 0.0}; // |largest|, its sign
  for (double a : out)
    if (std::abs(a) > local[0])
      local = {std::abs(a), a > 0 ? 1.0 : -1.0};
  MPI_Comm comm;
  PetscObjectGetComm(PetscObject(x), &comm);
  int size;
  MPI_Comm_size(comm, &size);
  std::vector<double> all(2 * size);
  MPI_Allgather(local.data(), 2, MPI_DOUBLE, all.data(), 2, MPI_DOUBLE, comm);
  double largest = -1.0, sign = 1.0;
  for (int r = 0; r < size; ++r) // the lowest rank of the largest wins
    if (all[2 * r] > largest)
    {
      largest = all[2 * r];
      sign = all[2 * r + 1];
    }
  if (sign < 0)
    for (double& a : out)
      a = -a;
  return out;
}
} // namespace

std::vector<Mode> natural_modes(const Linearisation& lin, const AnalysisSettings& settings)
{
  PetscBool slepc = PETSC_FALSE;
  SlepcInitialized(&slepc);
  if (!slepc)
    check(SlepcInitializeNoArguments(), "SlepcInitialize");
  Owned o;
  o.K = lin.reduced(lin.K(), 1.0, true);
  o.M = lin.reduced(lin.M(), 0.0);
  const double two_pi = 2 * std::numbers::pi;
  const double sigma = settings.target ? std::pow(two_pi * *settings.target, 2)
                                       : -1e-6 * diagonal_ratio(o.K, o.M);
  MPI_Comm comm;
  PetscObjectGetComm(PetscObject(o.K), &comm);
  check(EPSCreate(comm, &o.eps), "EPSCreate");
  EPSSetOptionsPrefix(o.eps, "piezo_modal_");
  EPSSetOperators(o.eps, o.K, o.M);
  // Krylov-Schur on a non-Hermitian pencil with M singular returns wrong
  // modes (measured: 0.1 % off, or spurious ones): only the Hermitian one
  if (!symmetric(o.K))
    throw NonHermitianPencil();
  EPSSetProblemType(o.eps, EPS_GHEP);
  EPSSetDimensions(o.eps, settings.modes, PETSC_DEFAULT, PETSC_DEFAULT);
  EPSSetTarget(o.eps, sigma);
  EPSSetWhichEigenpairs(o.eps, EPS_TARGET_MAGNITUDE);
  EPSSetTolerances(o.eps, 1e-12, 500);
  ST st;
  EPSGetST(o.eps, &st);
  STSetType(st, STSINVERT);
  KSP ksp;
  STGetKSP(st, &ksp);
  KSPSetType(ksp, KSPPREONLY);
  PC pc;
  KSPGetPC(ksp, &pc);
  PCSetType(pc, PCLU);
  PCFactorSetMatSolverType(pc, MATSOLVERMUMPS);
  check(EPSSolve(o.eps), "EPSSolve (shift-and-invert on MUMPS' LU)");
  PetscInt converged = 0;
  EPSGetConverged(o.eps, &converged);
  MatCreateVecs(o.K, &o.z, &o.Mz);
  VecDuplicate(o.z, &o.zi);
  MatCreateVecs(lin.K().mat(), &o.x, nullptr);
  std::vector<Mode> out;
  for (PetscInt i = 0; i < std::min<PetscInt>(converged, settings.modes); ++i)
  {
    PetscScalar kr, ki;
    EPSGetEigenpair(o.eps, i, &kr, &ki, o.z, o.zi);
    Mode m;
    m.eigenvalue = kr;
    m.frequency = std::copysign(std::sqrt(std::abs(kr)), kr) / two_pi;
    EPSComputeError(o.eps, i, EPS_ERROR_RELATIVE, &m.error);
    PetscScalar mass;
    MatMult(o.M, o.z, o.Mz);
    VecDot(o.z, o.Mz, &mass);
    VecScale(o.z, 1.0 / std::sqrt(std::abs(mass)));
    lin.prolong(o.z, o.x);
    m.x = signed_entries(o.x);
    out.push_back(std::move(m));
  }
  std::sort(out.begin(), out.end(),
            [](const Mode& a, const Mode& b) { return a.eigenvalue < b.eigenvalue; });
  return out;
}
} // namespace piezocontact
