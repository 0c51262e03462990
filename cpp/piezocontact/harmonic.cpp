#include "harmonic.h"
#include "config.h"
#include "linear_solver.h"
#include "matrices.h"

#include <chrono>
#include <cmath>
#include <numbers>
#include <petscksp.h>
#include <stdexcept>

namespace piezocontact
{
namespace
{
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
  std::copy_n(compat::values(L).begin(), n, l);
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
    auto x = compat::mutable_values(*p.x->x());
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

namespace
{
/// The block system [Kw, -w C; w C, Kw] with each dof's real and imaginary
/// parts next to each other (rows 2i, 2i + 1: block size 2). MUMPS then
/// orders the graph of the complex matrix: measured 1.5-1.7x faster to
/// factorise than the two halves one after the other (docs/dynamics.md).
/// C's sparsity is within Kw's (one pattern: linearisation.cpp).
Mat interleaved(Mat Kw, Mat C, double w)
{
  MPI_Comm comm;
  PetscObjectGetComm(PetscObject(Kw), &comm);
  PetscInt r0, r1;
  MatGetOwnershipRange(Kw, &r0, &r1);
  const PetscInt n = r1 - r0;
  std::vector<PetscInt> d(n), o(n);
  for (PetscInt i = 0; i < n; ++i)
  {
    PetscInt ncols;
    const PetscInt* cols;
    MatGetRow(Kw, r0 + i, &ncols, &cols, nullptr);
    for (PetscInt k = 0; k < ncols; ++k)
      (cols[k] >= r0 and cols[k] < r1 ? d[i] : o[i]) += 1;
    MatRestoreRow(Kw, r0 + i, &ncols, &cols, nullptr);
  }
  Mat A;
  MatCreate(comm, &A);
  MatSetSizes(A, 2 * n, 2 * n, PETSC_DETERMINE, PETSC_DETERMINE);
  MatSetBlockSize(A, 2);
  MatSetType(A, MATAIJ);
  MatXAIJSetPreallocation(A, 2, d.data(), o.data(), nullptr, nullptr);
  std::vector<PetscScalar> block;
  for (PetscInt i = 0; i < n; ++i)
  {
    PetscInt nk, nc;
    const PetscInt *kc, *cc;
    const PetscScalar *kv, *cv;
    MatGetRow(Kw, r0 + i, &nk, &kc, &kv);
    MatGetRow(C, r0 + i, &nc, &cc, &cv);
    block.assign(4 * nk, 0.0); // 2 rows of 2 nk values
    for (PetscInt k = 0, j = 0; k < nk; ++k)
    {
      const double c = (j < nc and cc[j] == kc[k]) ? w * cv[j++] : 0.0;
      block[2 * k] = kv[k];
      block[2 * k + 1] = -c;
      block[2 * nk + 2 * k] = c;
      block[2 * nk + 2 * k + 1] = kv[k];
    }
    const PetscInt row = r0 + i;
    MatSetValuesBlocked(A, 1, &row, nk, kc, block.data(), INSERT_VALUES);
    MatRestoreRow(C, r0 + i, &nc, &cc, &cv);
    MatRestoreRow(Kw, r0 + i, &nk, &kc, &kv);
  }
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  return A;
}

/// b[2i] = re[i], b[2i + 1] = im[i] (owned entries), or the reverse
void interleave(Vec re, Vec im, Vec b, bool into_b)
{
  PetscInt n;
  VecGetLocalSize(re, &n);
  PetscScalar *r, *m, *v;
  VecGetArray(re, &r);
  VecGetArray(im, &m);
  VecGetArray(b, &v);
  for (PetscInt i = 0; i < n; ++i)
    if (into_b)
    {
      v[2 * i] = r[i];
      v[2 * i + 1] = m[i];
    }
    else
    {
      r[i] = v[2 * i];
      m[i] = v[2 * i + 1];
    }
  VecRestoreArray(b, &v);
  VecRestoreArray(im, &m);
  VecRestoreArray(re, &r);
}
} // namespace

HarmonicResponse HarmonicSolver::solve(double f)
{
  const double w = 2 * std::numbers::pi * f;
  const auto t0 = std::chrono::steady_clock::now();
  Mat Kw;
  MatDuplicate(_K, MAT_COPY_VALUES, &Kw);
  MatAXPY(Kw, -w * w, _M, DIFFERENT_NONZERO_PATTERN);
  Mat A = interleaved(Kw, _C, w);
  MatDestroy(&Kw);
  MPI_Comm comm;
  PetscObjectGetComm(PetscObject(_K), &comm);
  // right-hand side: F - (K - w^2 M) g, -w C g; the removed dofs hold g, 0
  Vec b, x, b_re, b_im;
  MatCreateVecs(A, &x, &b);
  VecDuplicate(_F, &b_re);
  VecDuplicate(_F, &b_im);
  VecCopy(_F, b_re);
  VecAXPY(b_re, -1.0, _Kg);
  VecAXPY(b_re, w * w, _Mg);
  set_at(b_re, _lin.removed(), _g);
  VecCopy(_Cg, b_im);
  VecScale(b_im, -w);
  set_at(b_im, _lin.removed(), nullptr);
  interleave(b_re, b_im, b, true);
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
  MatDestroy(&A);
  VecDestroy(&b);
  if (ierr != 0 or reason < 0)
  {
    for (Vec* v : {&x, &b_re, &b_im})
      VecDestroy(v);
    throw LinearSolveFailure("the harmonic system at " + std::to_string(f)
                                 + " Hz is singular (a natural frequency, or a body held by "
                                   "nothing at 0 Hz)",
                             false);
  }
  interleave(b_re, b_im, x, false); // b_re, b_im <- the solution's parts
  HarmonicResponse out;
  out.frequency = f;
  out.assembly_s = std::chrono::duration<double>(t1 - t0).count();
  out.factorisation_s = std::chrono::duration<double>(t2 - t1).count();
  out.solve_s = std::chrono::duration<double>(t3 - t2).count();
  Vec full, r;
  MatCreateVecs(_lin.K().mat(), &full, &r);
  for (int part = 0; part < 2; ++part)
  {
    _lin.prolong(part == 0 ? b_re : b_im, full);
    MatMult(_lin.K().mat(), full, r);
    if (part == 0)
      VecAXPY(r, -1.0, _L);
    (part == 0 ? out.re : out.im) = owned_entries(full);
    (part == 0 ? out.residual_re : out.residual_im) = owned_entries(r);
  }
  for (Vec* v : {&full, &r, &x, &b_re, &b_im})
    VecDestroy(v);
  return out;
}
} // namespace piezocontact
