#include "harmonic.h"
#include "config.h"
#include "linear_solver.h"

#include <chrono>
#include <cmath>
#include <numbers>
#include <petscksp.h>
#include <stdexcept>

namespace piezocontact
{
namespace
{
void check(PetscErrorCode ierr, const char* what)
{
  if (ierr != 0)
    throw std::runtime_error(std::string("PETSc failed in ") + what);
}

std::vector<double> owned_entries(Vec x)
{
  const PetscScalar* v;
  PetscInt n;
  VecGetLocalSize(x, &n);
  VecGetArrayRead(x, &v);
  std::vector<double> out(v, v + n);
  VecRestoreArrayRead(x, &v);
  return out;
}

/// Entries of a vector at some global indices (owned) set to a value, or
/// to another vector's
void set_at(Vec b, const std::vector<PetscInt>& rows, Vec from)
{
  std::vector<PetscScalar> values(rows.size(), 0.0);
  if (from and !rows.empty())
    VecGetValues(from, PetscInt(rows.size()), rows.data(), values.data());
  if (!rows.empty())
    VecSetValues(b, PetscInt(rows.size()), rows.data(), values.data(), INSERT_VALUES);
  VecAssemblyBegin(b);
  VecAssemblyEnd(b);
}
} // namespace

HarmonicSolver::HarmonicSolver(Problem& p, const Linearisation& lin, const std::string& source)
    : _lin(lin)
{
  _K = lin.reduced(lin.K(), 1.0);
  _C = lin.reduced(lin.C(), 0.0);
  _M = lin.reduced(lin.M(), 0.0);
  MatCreateVecs(lin.K().mat(), &_L, &_g);
  VecDuplicate(_L, &_F);
  // the loads at the data's values (their amplitudes)
  const auto L = p.assemble(p.model.L);
  PetscInt n;
  VecGetLocalSize(_L, &n);
  PetscScalar* l;
  VecGetArray(_L, &l);
  std::copy_n(L.array().begin(), n, l);
  VecRestoreArray(_L, &l);
  lin.restrict_to(_L, _F);
  // a floating electrode's charge: sum over it of K x = sum of L - Q
  const auto Q = p.target_charges();
  for (std::size_t e = 0; e < p.electrodes.size(); ++e)
    if (p.electrodes[e].floating and Q[e] != 0.0)
    {
      PetscInt r0, r1, rep = lin.representative()[e];
      VecGetOwnershipRange(_F, &r0, &r1);
      if (rep >= r0 and rep < r1)
        VecSetValue(_F, rep, -Q[e], ADD_VALUES);
    }
  VecAssemblyBegin(_F);
  VecAssemblyEnd(_F);
  // prescribed values (the floating electrodes' conditions are not data)
  std::vector<double> g(n, 0.0);
  {
    auto x = p.x->x()->mutable_array();
    std::vector<double> saved(x.begin(), x.end());
    std::fill(x.begin(), x.end(), 0.0);
    for (const auto& bc : p.bcs())
    {
      bool floating = false;
      for (const auto& e : p.electrodes)
        floating = floating or (e.floating and e.bc == bc);
      if (!floating)
        compat::set_bc_values(*bc, x);
    }
    std::copy_n(x.begin(), n, g.begin());
    std::copy(saved.begin(), saved.end(), x.begin());
  }
  PetscScalar* gv;
  VecGetArray(_g, &gv);
  std::copy(g.begin(), g.end(), gv);
  VecRestoreArray(_g, &gv);
  PetscReal drive[2];
  VecNorm(_F, NORM_INFINITY, &drive[0]);
  VecNorm(_g, NORM_INFINITY, &drive[1]);
  if (drive[0] == 0.0 and drive[1] == 0.0)
    throw ConfigError(source + ": analysis.harmonic: nothing is driven (give a load, a "
                               "prescribed displacement or potential, or a floating "
                               "electrode's charge: their values are the amplitudes)");
  // the lifting: the unconstrained reduced matrices times g
  for (auto [A, out, diag] : {std::tuple{&lin.K(), &_Kg, 1.0}, std::tuple{&lin.C(), &_Cg, 0.0},
                              std::tuple{&lin.M(), &_Mg, 0.0}})
  {
    Mat R = lin.reduced_unconstrained(*A);
    VecDuplicate(_F, out);
    MatMult(R, _g, *out);
    MatDestroy(&R);
  }
}

HarmonicSolver::~HarmonicSolver()
{
  for (Mat* m : {&_K, &_C, &_M})
    if (*m)
      MatDestroy(m);
  for (Vec* v : {&_F, &_g, &_Kg, &_Cg, &_Mg, &_L})
    if (*v)
      VecDestroy(v);
}

HarmonicResponse HarmonicSolver::solve(double f)
{
  const double w = 2 * std::numbers::pi * f;
  const auto t0 = std::chrono::steady_clock::now();
  Mat A11, A12, A21;
  MatDuplicate(_K, MAT_COPY_VALUES, &A11);
  MatAXPY(A11, -w * w, _M, DIFFERENT_NONZERO_PATTERN);
  MatDuplicate(_C, MAT_COPY_VALUES, &A21);
  MatScale(A21, w);
  MatDuplicate(_C, MAT_COPY_VALUES, &A12);
  MatScale(A12, -w);
  MPI_Comm comm;
  PetscObjectGetComm(PetscObject(_K), &comm);
  Mat blocks[4] = {A11, A12, A21, A11}, nest, A;
  check(MatCreateNest(comm, 2, nullptr, 2, nullptr, blocks, &nest), "MatCreateNest");
  check(MatConvert(nest, MATAIJ, MAT_INITIAL_MATRIX, &A), "MatConvert");
  IS rows[2];
  MatNestGetISs(nest, rows, nullptr);
  // right-hand side: F - (K - w^2 M) g, -w C g; the removed dofs hold g, 0
  Vec b, x, b_re, b_im;
  MatCreateVecs(A, &x, &b);
  VecGetSubVector(b, rows[0], &b_re);
  VecCopy(_F, b_re);
  VecAXPY(b_re, -1.0, _Kg);
  VecAXPY(b_re, w * w, _Mg);
  set_at(b_re, _lin.removed(), _g);
  VecRestoreSubVector(b, rows[0], &b_re);
  VecGetSubVector(b, rows[1], &b_im);
  VecCopy(_Cg, b_im);
  VecScale(b_im, -w);
  set_at(b_im, _lin.removed(), nullptr);
  VecRestoreSubVector(b, rows[1], &b_im);
  KSP ksp;
  KSPCreate(comm, &ksp);
  KSPSetOptionsPrefix(ksp, "piezo_harmonic_");
  KSPSetType(ksp, KSPPREONLY);
  PC pc;
  KSPGetPC(ksp, &pc);
  PCSetType(pc, PCLU);
  PCFactorSetMatSolverType(pc, MATSOLVERMUMPS);
  KSPSetOperators(ksp, A, A);
  const auto t1 = std::chrono::steady_clock::now();
  PetscErrorCode ierr = KSPSetUp(ksp); // the LU
  const auto t2 = std::chrono::steady_clock::now();
  if (ierr == 0)
    ierr = KSPSolve(ksp, b, x);
  const auto t3 = std::chrono::steady_clock::now();
  KSPConvergedReason reason;
  KSPGetConvergedReason(ksp, &reason);
  KSPDestroy(&ksp);
  for (Mat* m : {&A11, &A12, &A21})
    MatDestroy(m);
  if (ierr != 0 or reason < 0)
  {
    MatDestroy(&nest);
    MatDestroy(&A);
    VecDestroy(&b);
    VecDestroy(&x);
    throw LinearSolveFailure("the harmonic system at " + std::to_string(f)
                                 + " Hz is singular (a natural frequency, or a body held by "
                                   "nothing at 0 Hz)",
                             false);
  }
  HarmonicResponse out;
  out.frequency = f;
  out.assembly_s = std::chrono::duration<double>(t1 - t0).count();
  out.factorisation_s = std::chrono::duration<double>(t2 - t1).count();
  out.solve_s = std::chrono::duration<double>(t3 - t2).count();
  Vec full, r;
  MatCreateVecs(_lin.K().mat(), &full, &r);
  for (int part = 0; part < 2; ++part)
  {
    Vec z;
    VecGetSubVector(x, rows[part], &z);
    _lin.prolong(z, full);
    VecRestoreSubVector(x, rows[part], &z);
    MatMult(_lin.K().mat(), full, r);
    if (part == 0)
      VecAXPY(r, -1.0, _L);
    (part == 0 ? out.re : out.im) = owned_entries(full);
    (part == 0 ? out.residual_re : out.residual_im) = owned_entries(r);
  }
  VecDestroy(&full);
  VecDestroy(&r);
  MatDestroy(&nest); // after its index sets' last use
  MatDestroy(&A);
  VecDestroy(&b);
  VecDestroy(&x);
  return out;
}
} // namespace piezocontact
