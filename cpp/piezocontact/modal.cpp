#include "modal.h"
#include "matrices.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
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
  Vec x = nullptr, Mz = nullptr;
  ~Owned()
  {
    for (Mat* m : {&K, &M})
      if (*m)
        MatDestroy(m);
    for (Vec* v : {&x, &Mz})
      if (*v)
        VecDestroy(v);
  }
};

/// ||K - K^T||_F <= 1e-12 ||K||_F
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
  std::vector<double> out = owned_entries(x);
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

namespace
{
/// An eigenpair of the pencil in the reduced space: lambda, SLEPc's error
/// and the vector (owned by the caller)
struct Pair
{
  double lambda, error;
  Vec z;
};

/// MUMPS' LDL^T for a symmetric K - sigma M (half the factors), its LU
/// otherwise
void use_mumps(KSP ksp, bool symmetric)
{
  KSPSetType(ksp, KSPPREONLY);
  PC pc;
  KSPGetPC(ksp, &pc);
  PCSetType(pc, symmetric ? PCCHOLESKY : PCLU);
  PCFactorSetMatSolverType(pc, MATSOLVERMUMPS);
}

/// The number of dofs with mass (M_ii > 0), over the ranks
PetscInt dofs_with_mass(Mat M)
{
  Vec d;
  MatCreateVecs(M, &d, nullptr);
  MatGetDiagonal(M, d);
  PetscInt n;
  VecGetLocalSize(d, &n);
  const PetscScalar* v;
  VecGetArrayRead(d, &v);
  PetscInt count = 0;
  for (PetscInt i = 0; i < n; ++i)
    count += v[i] > 0;
  VecRestoreArrayRead(d, &v);
  MPI_Comm comm;
  PetscObjectGetComm(PetscObject(M), &comm);
  VecDestroy(&d);
  MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPIU_INT, MPI_SUM, comm);
  return count;
}

/// The entries of a KSP's MUMPS factors (0 if not MUMPS)
double factor_entries(KSP ksp)
{
  PC pc;
  KSPGetPC(ksp, &pc);
  Mat F;
  if (PCFactorGetMatrix(pc, &F) != 0)
    return 0.0;
  PetscInt entries = 0;
  if (MatMumpsGetInfog(F, 29, &entries) != 0)
    return 0.0;
  return entries < 0 ? -1e6 * entries : entries; // MUMPS: negative means millions
}

/// The time of one solve on a factorised KSP (s)
double one_solve(KSP ksp, Mat K)
{
  Vec b, x;
  MatCreateVecs(K, &x, &b);
  VecSet(b, 1.0);
  const auto t0 = std::chrono::steady_clock::now();
  KSPSolve(ksp, b, x);
  const auto t1 = std::chrono::steady_clock::now();
  VecDestroy(&b);
  VecDestroy(&x);
  return std::chrono::duration<double>(t1 - t0).count();
}

/// `factorise` (the LU of K - sigma M), then the eigensolver, each timed
/// into `cost`; the first error code
PetscErrorCode timed_solve(const std::function<PetscErrorCode()>& factorise, EPS eps,
                           ModalCost& cost)
{
  const auto t0 = std::chrono::steady_clock::now();
  PetscErrorCode ierr = factorise();
  const auto t1 = std::chrono::steady_clock::now();
  if (ierr == 0)
    ierr = EPSSolve(eps);
  const auto t2 = std::chrono::steady_clock::now();
  cost.factorisation_s = std::chrono::duration<double>(t1 - t0).count();
  cost.eigensolver_s = std::chrono::duration<double>(t2 - t1).count();
  return ierr;
}

/// The Hermitian pencil: SLEPc's generalised problem, shift-and-invert
std::vector<Pair> hermitian_pairs(Mat K, Mat M, double sigma, int nev, ModalCost& cost)
{
  MPI_Comm comm;
  PetscObjectGetComm(PetscObject(K), &comm);
  EPS eps;
  check(EPSCreate(comm, &eps), "EPSCreate");
  EPSSetOptionsPrefix(eps, "piezo_modal_");
  EPSSetOperators(eps, K, M);
  EPSSetProblemType(eps, EPS_GHEP);
  EPSSetDimensions(eps, nev, PETSC_DEFAULT, PETSC_DEFAULT);
  EPSSetTarget(eps, sigma);
  EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE);
  EPSSetTolerances(eps, 1e-12, 500);
  ST st;
  EPSGetST(eps, &st);
  STSetType(st, STSINVERT);
  KSP ksp;
  STGetKSP(st, &ksp);
  use_mumps(ksp, true);
  const PetscErrorCode ierr = timed_solve([&] { return EPSSetUp(eps); }, eps, cost);
  PetscInt solves = 0;
  KSPGetTotalIterations(ksp, &solves); // preonly: one per solve
  cost.solves = solves;
  cost.solve_s = one_solve(ksp, K);
  cost.factor_entries = factor_entries(ksp);
  std::vector<Pair> out;
  PetscInt converged = 0;
  if (ierr == 0)
    EPSGetConverged(eps, &converged);
  for (PetscInt i = 0; i < std::min<PetscInt>(converged, nev); ++i)
  {
    Pair p;
    MatCreateVecs(K, &p.z, nullptr);
    PetscScalar kr, ki;
    EPSGetEigenpair(eps, i, &kr, &ki, p.z, nullptr);
    p.lambda = kr;
    EPSComputeError(eps, i, EPS_ERROR_RELATIVE, &p.error);
    out.push_back(p);
  }
  EPSDestroy(&eps);
  check(ierr, "EPSSolve (shift-and-invert on MUMPS' LDL^T)");
  return out;
}

/// The condensed operator of a non-Hermitian pencil: on the dofs with mass
/// (U), v -> R_U (K - sigma M)^-1 M E_U v, phi and the removed dofs
/// eliminated by the LU (a standard problem, no null space of M left)
struct Condensed
{
  KSP ksp;
  Mat M;
  IS U;
  Vec in, Min, out;
  int solves = 0;

  static PetscErrorCode mult(Mat S, Vec v, Vec y)
  {
    Condensed* c;
    PetscCall(MatShellGetContext(S, &c));
    PetscCall(VecZeroEntries(c->in));
    PetscCall(VecISCopy(c->in, c->U, SCATTER_FORWARD, v));
    PetscCall(MatMult(c->M, c->in, c->Min));
    PetscCall(KSPSolve(c->ksp, c->Min, c->out));
    ++c->solves;
    KSPConvergedReason reason;
    PetscCall(KSPGetConvergedReason(c->ksp, &reason));
    PetscCheck(reason >= 0, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "singular K - sigma M");
    PetscCall(VecISCopy(c->out, c->U, SCATTER_REVERSE, y));
    return 0;
  }
};

/// The non-Hermitian pencil (Nitsche on a piezoelectric contact boundary):
/// Krylov-Schur on the condensed operator, theta = 1 / (lambda - sigma)
std::vector<Pair> condensed_pairs(Mat K, Mat M, double sigma, int nev, ModalCost& cost)
{
  MPI_Comm comm;
  PetscObjectGetComm(PetscObject(K), &comm);
  Condensed c;
  Mat A;
  MatDuplicate(K, MAT_COPY_VALUES, &A);
  MatAXPY(A, -sigma, M, DIFFERENT_NONZERO_PATTERN);
  KSPCreate(comm, &c.ksp);
  KSPSetOptionsPrefix(c.ksp, "piezo_modal_condensed_");
  use_mumps(c.ksp, false);
  KSPSetOperators(c.ksp, A, A);
  c.M = M;
  MatCreateVecs(K, &c.in, &c.out);
  VecDuplicate(c.in, &c.Min);
  { // U: the owned dofs with mass
    Vec d;
    MatCreateVecs(M, &d, nullptr);
    MatGetDiagonal(M, d);
    PetscInt r0, r1;
    VecGetOwnershipRange(d, &r0, &r1);
    const PetscScalar* dv;
    VecGetArrayRead(d, &dv);
    std::vector<PetscInt> rows;
    for (PetscInt i = 0; i < r1 - r0; ++i)
      if (dv[i] > 0)
        rows.push_back(r0 + i);
    VecRestoreArrayRead(d, &dv);
    VecDestroy(&d);
    ISCreateGeneral(comm, PetscInt(rows.size()), rows.data(), PETSC_COPY_VALUES, &c.U);
  }
  PetscInt n;
  ISGetLocalSize(c.U, &n);
  Mat S;
  MatCreateShell(comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, &c, &S);
  MatShellSetOperation(S, MATOP_MULT, (void (*)(void))Condensed::mult);
  EPS eps;
  EPSCreate(comm, &eps);
  EPSSetOptionsPrefix(eps, "piezo_modal_condensed_");
  EPSSetOperators(eps, S, nullptr);
  EPSSetProblemType(eps, EPS_NHEP);
  EPSSetDimensions(eps, nev, PETSC_DEFAULT, PETSC_DEFAULT);
  EPSSetWhichEigenpairs(eps, EPS_LARGEST_MAGNITUDE);
  EPSSetTolerances(eps, 1e-12, 500);
  const PetscErrorCode ierr = timed_solve([&] { return KSPSetUp(c.ksp); }, eps, cost);
  cost.solves = c.solves;
  cost.solve_s = one_solve(c.ksp, K);
  cost.factor_entries = factor_entries(c.ksp);
  std::vector<Pair> out;
  PetscInt converged = 0;
  if (ierr == 0)
    EPSGetConverged(eps, &converged);
  Vec v;
  MatCreateVecs(S, &v, nullptr);
  for (PetscInt i = 0; i < std::min<PetscInt>(converged, nev); ++i)
  {
    PetscScalar tr, ti;
    EPSGetEigenpair(eps, i, &tr, &ti, v, nullptr);
    Pair p;
    p.lambda = sigma + 1.0 / tr;
    EPSComputeError(eps, i, EPS_ERROR_RELATIVE, &p.error);
    // the whole vector: (K - sigma M)^-1 M E_U v / theta
    MatCreateVecs(K, &p.z, nullptr);
    Condensed::mult(S, v, v); // v <- S v, and c.out holds the full solve
    VecCopy(c.out, p.z);
    VecScale(p.z, 1.0 / tr);
    out.push_back(p);
  }
  VecDestroy(&v);
  EPSDestroy(&eps);
  MatDestroy(&S);
  ISDestroy(&c.U);
  for (Vec* w : {&c.in, &c.Min, &c.out})
    VecDestroy(w);
  KSPDestroy(&c.ksp);
  MatDestroy(&A);
  check(ierr, "EPSSolve (the condensed operator on MUMPS' LU)");
  return out;
}
} // namespace

std::vector<Mode> natural_modes(const Linearisation& lin, const AnalysisSettings& settings,
                                ModalCost* cost)
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
  // Krylov-Schur on the generalised non-Hermitian pencil with M singular
  // returns wrong modes (measured: 0.1 % off, or spurious ones): a
  // Hermitian pencil as SLEPc's GHEP, purified; else the condensed operator
  // no more modes than dofs with mass: fewer are reported (and refused)
  ModalCost spent;
  spent.dofs_with_mass = dofs_with_mass(o.M);
  const int nev = std::min<PetscInt>(settings.modes, spent.dofs_with_mass);
  spent.hermitian = scaled_asymmetry(o.K) <= symmetry_tolerance;
  const auto pairs = spent.hermitian
                         ? hermitian_pairs(o.K, o.M, sigma, nev, spent)
                         : condensed_pairs(o.K, o.M, sigma, nev, spent);
  if (cost)
    *cost = spent;
  MatCreateVecs(o.K, nullptr, &o.Mz);
  MatCreateVecs(lin.K().mat(), &o.x, nullptr);
  std::vector<Mode> out;
  for (const auto& p : pairs)
  {
    Mode m;
    m.eigenvalue = p.lambda;
    m.frequency = std::copysign(std::sqrt(std::abs(p.lambda)), p.lambda) / two_pi;
    m.error = p.error;
    PetscScalar mass;
    MatMult(o.M, p.z, o.Mz);
    VecDot(p.z, o.Mz, &mass);
    VecScale(p.z, 1.0 / std::sqrt(std::abs(mass)));
    lin.prolong(p.z, o.x);
    m.x = signed_entries(o.x);
    Vec z = p.z;
    VecDestroy(&z);
    out.push_back(std::move(m));
  }
  std::sort(out.begin(), out.end(),
            [](const Mode& a, const Mode& b) { return a.eigenvalue < b.eigenvalue; });
  return out;
}
} // namespace piezocontact
