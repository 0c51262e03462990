#include "linear_solver.h"
#include "matrices.h"

#include <petscmat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <array>

namespace piezocontact
{
namespace
{
std::string reason_name(KSPConvergedReason reason)
{
  return KSPConvergedReasons[reason]; // PETSc offsets the table: negative indices valid
}

bool is_type(PC pc, PCType type)
{
  PetscBool same = PETSC_FALSE;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), type, &same);
  return same;
}

/// The sub-KSPs of a fieldsplit PC (valid after its set-up)
std::vector<KSP> sub_ksps(PC pc)
{
  PetscInt n = 0;
  KSP* subs = nullptr;
  PCFieldSplitGetSubKSP(pc, &n, &subs);
  std::vector<KSP> out(subs, subs + n);
  PetscFree(subs);
  return out;
}
} // namespace

LinearSolverSetup::LinearSolverSetup(KSP ksp, const Problem& p, LinearSolver kind,
                                     bool symmetric)
    : _ksp(ksp), _kind(kind), _comm(p.comm), _dim(p.dim()),
      _symmetric(symmetric and kind == LinearSolver::direct)
{
  make_splits(p);
  if (_symmetric)
    make_signs(p);
  KSPSetPreSolve(_ksp, &LinearSolverSetup::pre_solve, this);
  KSPSetPostSolve(_ksp, &LinearSolverSetup::post_solve, this);
  if (!iterative())
    return;
  // The user's (or our default) relative tolerance and iteration limit stay;
  // the absolute one is set per solve
  PetscReal atol, dtol;
  KSPGetTolerances(_ksp, &_rtol, &atol, &dtol, &_max_it);
}

LinearSolverSetup::~LinearSolverSetup()
{
  KSPSetPreSolve(_ksp, nullptr, nullptr);
  KSPSetPostSolve(_ksp, nullptr, nullptr);
  VecDestroy(&_sign);
  VecDestroy(&_s);
  VecDestroy(&_b_saved);
  ISDestroy(&_is_u);
  ISDestroy(&_is_phi);
}

// With pc_type fieldsplit (the iterative default, or a user's options),
// PETSc is told which dofs are u and which phi: fieldsplit_u_*,
// fieldsplit_phi_* options configure each block
void LinearSolverSetup::make_splits(const Problem& p)
{
  PC pc;
  KSPGetPC(_ksp, &pc);
  if (!is_type(pc, PCFIELDSPLIT))
    return;
  const auto& imap = *p.W->dofmap()->index_map;
  const int bs = p.W->dofmap()->index_map_bs();
  const std::int32_t owned = imap.size_local() * bs;
  const std::int64_t offset = imap.local_range()[0] * bs;
  // u: owned nodes with their d components, in W order (PETSc wants sorted
  // splits); a node's components are consecutive W dofs in component order
  // (dolfinx numbers a mixed element's dofs cell by cell, unreordered):
  // checked, since the u block size and the near null space rely on it
  const std::size_t d = _dim;
  std::vector<std::pair<std::int32_t, std::size_t>> nodes; // (first W dof, V_u node)
  bool blocks = true;
  for (std::size_t node = 0; node * d < p.u_dofs.size(); ++node)
  {
    const std::int32_t w0 = p.u_dofs[node * d];
    if (w0 >= owned)
      continue;
    for (std::size_t c = 1; c < d; ++c)
      blocks = blocks and p.u_dofs[node * d + c] == w0 + std::int32_t(c);
    nodes.emplace_back(w0, node);
  }
  std::sort(nodes.begin(), nodes.end());
  int all_blocks = blocks;
  MPI_Allreduce(MPI_IN_PLACE, &all_blocks, 1, MPI_INT, MPI_LAND, _comm);

  std::vector<PetscInt> u_global, phi_global;
  if (all_blocks)
  {
    const auto X = p.V_u->tabulate_dof_coordinates(false); // (nodes, 3)
    for (const auto& [w0, node] : nodes)
      for (std::size_t c = 0; c < d; ++c)
      {
        u_global.push_back(offset + w0 + c);
        _node_x.push_back(X[3 * node + c]);
      }
  }
  else // no blocks: plain sorted u dofs, no near null space
    for (auto w : p.u_dofs)
      if (w < owned)
        u_global.push_back(offset + w);
  for (auto w : p.phi_dofs)
    if (w < owned)
      phi_global.push_back(offset + w);
  std::sort(u_global.begin(), u_global.end());
  std::sort(phi_global.begin(), phi_global.end());
  ISCreateGeneral(_comm, u_global.size(), u_global.data(), PETSC_COPY_VALUES, &_is_u);
  ISCreateGeneral(_comm, phi_global.size(), phi_global.data(), PETSC_COPY_VALUES, &_is_phi);
  if (all_blocks)
    ISSetBlockSize(_is_u, d);
  PCFieldSplitSetIS(pc, "u", _is_u);
  PCFieldSplitSetIS(pc, "phi", _is_phi);
}

void LinearSolverSetup::scale(Mat M)
{
  if (!_s)
    MatCreateVecs(M, &_s, nullptr);
  jacobi_scaling(M, _s);
  MatDiagonalScale(M, _s, _s);
}

void LinearSolverSetup::make_signs(const Problem& p)
{
  const auto& imap = *p.W->dofmap()->index_map;
  const PetscInt owned = imap.size_local() * p.W->dofmap()->index_map_bs();
  VecCreateMPI(_comm, owned, PETSC_DETERMINE, &_sign);
  VecSet(_sign, 1.0);
  PetscScalar* a;
  VecGetArray(_sign, &a);
  for (auto w : p.phi_dofs)
    if (w < owned)
    {
      a[w] = -1.0;
      ++_phi_rows;
    }
  VecRestoreArray(_sign, &a);
  MPI_Allreduce(MPI_IN_PLACE, &_phi_rows, 1, MPIU_INT, MPI_SUM, _comm);
}

void LinearSolverSetup::choose_factorisation(Mat M)
{
  const double defect = scaled_asymmetry(M, _sign);
  symmetry_defect = std::max(symmetry_defect, defect);
  _negated = defect <= symmetry_tolerance;
  _operator = M;
  if (_negated)
  {
    MatDiagonalScale(M, _sign, nullptr);
    MatSetOption(M, MAT_SYMMETRIC, PETSC_TRUE);
  }
  PC pc;
  KSPGetPC(_ksp, &pc);
  const PCType wanted = _negated ? PCCHOLESKY : PCLU;
  if (!is_type(pc, wanted))
  {
    PCSetType(pc, wanted);
#if PETSC_HAVE_MUMPS
    PCFactorSetMatSolverType(pc, MATSOLVERMUMPS);
#endif
  }
  ++(_negated ? ldlt : lu);
}

// D J is quasi-definite (K + Kc positive definite, -P negative definite):
// an LDL^T exists for every symmetric ordering without pivoting (Vanderbei
// 1995), and MUMPS without pivoting (CNTL(1) = 0) factorises 30 % faster
// than with it (docs/benchmarks.md). Sylvester's law of inertia checks the
// premise: the factors must have exactly one negative pivot per phi row
// (MUMPS' INFOG(12)). A body nothing holds, or a term that makes K
// indefinite, breaks it: the factorisation is then redone with threshold
// pivoting, for this run's remaining factorisations too.
void LinearSolverSetup::factorise_quasi_definite()
{
  PC pc;
  KSPGetPC(_ksp, &pc);
  const char* prefix = nullptr;
  PCGetOptionsPrefix(pc, &prefix);
  PetscBool user = PETSC_FALSE;
  PetscOptionsHasName(nullptr, prefix, "-mat_mumps_cntl_1", &user);
  MatSolverType package = nullptr;
  PCFactorGetMatSolverType(pc, &package);
  PetscBool mumps = PETSC_FALSE;
  if (package)
    PetscStrcmp(package, MATSOLVERMUMPS, &mumps);
  if (user or !mumps or _pivoting)
  {
    KSPSetUp(_ksp);
    return;
  }
  // MUMPS reads its options when it creates its factor, with the user's
  // (solver.petsc_options) under the same prefix; this one only for LDL^T
  const std::string name = std::string("-") + (prefix ? prefix : "") + "mat_mumps_cntl_1";
  PetscOptionsSetValue(nullptr, name.c_str(), "0");
  KSPSetUp(_ksp);
  PetscOptionsClearValue(nullptr, name.c_str());
  Mat F = nullptr;
  PCFactorGetMatrix(pc, &F);
  PetscInt info = 0, negative = -1;
  MatMumpsGetInfog(F, 1, &info);
  if (info >= 0)
    MatMumpsGetInfog(F, 12, &negative);
  if (negative == _phi_rows)
    return;
  _pivoting = true;
  PCReset(pc); // a new factor, with MUMPS' default threshold pivoting
  KSPSetOperators(_ksp, _operator, _operator);
  KSPSetUp(_ksp);
}

std::string LinearSolverSetup::factorisations() const
{
  if (iterative())
    return "";
  if (ldlt > 0 and lu > 0)
    return "LDLT and LU";
  return ldlt > 0 ? "LDLT" : "LU";
}

bool LinearSolverSetup::operator_changed(Mat M, bool k_changed)
{
  if (_symmetric)
    choose_factorisation(M);
  else if (!iterative())
  {
    PC pc; // the user's choice
    KSPGetPC(_ksp, &pc);
    ++(is_type(pc, PCCHOLESKY) ? ldlt : lu);
  }
  if (iterative())
    scale(M);
  const bool lag = iterative() and setups > 0 and !k_changed and !_stale;
  KSPSetReusePreconditioner(_ksp, lag ? PETSC_TRUE : PETSC_FALSE);
  KSPSetOperators(_ksp, M, M);
  if (_negated)
    factorise_quasi_definite();
  else
    KSPSetUp(_ksp);
  if (lag)
  {
    ++lagged;
    return false;
  }
  ++setups;
  record_factor_entries();
  _best_rate = std::numeric_limits<double>::infinity();
  _stale = false;
  set_up_blocks();
  return true;
}

void LinearSolverSetup::record_factor_entries()
{
  PC pc;
  KSPGetPC(_ksp, &pc);
  factor_entries = 0.0;
  factor_ordering.clear();
#if PETSC_HAVE_MUMPS
  if (!is_type(pc, PCLU) and !is_type(pc, PCCHOLESKY))
    return;
  Mat F = nullptr;
  PCFactorGetMatrix(pc, &F);
  MatSolverType package = nullptr;
  MatFactorGetSolverType(F, &package);
  PetscBool mumps = PETSC_FALSE;
  PetscStrcmp(package, MATSOLVERMUMPS, &mumps);
  if (!mumps)
    return;
  PetscInt entries = 0, ordering = -1;
  MatMumpsGetInfog(F, 29, &entries); // negative: millions (MUMPS' users' guide)
  factor_entries = entries < 0 ? -1e6 * double(entries) : double(entries);
  // the ordering MUMPS ran (a requested one it lacks falls back)
  MatMumpsGetInfog(F, 7, &ordering);
  static const char* names[] = {"AMD", "user", "AMF", "SCOTCH", "PORD", "METIS", "QAMD"};
  factor_ordering = ordering >= 0 and ordering <= 6 ? names[ordering] : "";
#endif
}

// The near null space goes on the u block's own matrix, which exists once
// the fieldsplit PC is set up and before its blocks are: their AMG set-up
// happens here, not lazily in the first solve (and is timed with it)
void LinearSolverSetup::set_up_blocks()
{
  PC pc;
  KSPGetPC(_ksp, &pc);
  if (!is_type(pc, PCFIELDSPLIT))
    return;
  const std::vector<KSP> subs = sub_ksps(pc);
  if (iterative() and !subs.empty())
    attach_near_nullspace();
  for (KSP sub : subs)
    KSPSetUp(sub);
}

// Rigid body modes of the owned u nodes about their centroid, times D^1/2
// (the modes of S K S are S^-1 Z), orthonormalised
void LinearSolverSetup::attach_near_nullspace()
{
  PC pc;
  KSPGetPC(_ksp, &pc);
  const std::vector<KSP> subs = sub_ksps(pc);
  Mat A_u, P_u;
  KSPGetOperators(subs[0], &A_u, &P_u);
  PC pc_u;
  KSPGetPC(subs[0], &pc_u);
  PetscInt bs = 1;
  MatGetBlockSize(P_u, &bs);
  std::int64_t n_nodes = _node_x.size();
  MPI_Allreduce(MPI_IN_PLACE, &n_nodes, 1, MPI_INT64_T, MPI_SUM, _comm);
  if (bs != _dim or n_nodes == 0)
    return; // u not split by node (same answer on every rank): no modes

  const std::size_t d = _dim, nodes = _node_x.size() / d;
  // centroid of all u nodes
  std::array<double, 4> sum = {0, 0, 0, double(nodes)};
  for (std::size_t i = 0; i < nodes; ++i)
    for (std::size_t c = 0; c < d; ++c)
      sum[c] += _node_x[d * i + c];
  MPI_Allreduce(MPI_IN_PLACE, sum.data(), 4, MPI_DOUBLE, MPI_SUM, _comm);
  std::array<double, 3> centre = {0, 0, 0};
  for (std::size_t c = 0; c < d; ++c)
    centre[c] = sum[3] > 0 ? sum[c] / sum[3] : 0.0;

  // translations only for smoothed aggregation; BoomerAMG builds them in
  const bool rotations_only = is_type(pc_u, PCHYPRE);
  const int n_rot = d == 3 ? 3 : 1;
  const int n_modes = rotations_only ? n_rot : int(d) + n_rot;
  // sqrt(|diag J|) on the u split, in its order
  Vec s_u;
  VecGetSubVector(_s, _is_u, &s_u);
  const PetscScalar* s;
  VecGetArrayRead(s_u, &s);
  std::vector<Vec> modes(n_modes);
  for (int m = 0; m < n_modes; ++m)
  {
    VecCreateMPI(_comm, nodes * d, PETSC_DETERMINE, &modes[m]);
    VecSetBlockSize(modes[m], d);
    PetscScalar* v;
    VecGetArray(modes[m], &v);
    for (std::size_t i = 0; i < nodes; ++i)
    {
      double r[3] = {0, 0, 0}, mode[3] = {0, 0, 0};
      for (std::size_t c = 0; c < d; ++c)
        r[c] = _node_x[d * i + c] - centre[c];
      const int rot = rotations_only ? m : m - int(d);
      if (rot < 0)
        mode[m] = 1.0; // translation along m
      else if (d == 2)
        mode[0] = -r[1], mode[1] = r[0];
      else if (rot == 0) // about z
        mode[0] = -r[1], mode[1] = r[0];
      else if (rot == 1) // about x
        mode[1] = -r[2], mode[2] = r[1];
      else // about y
        mode[0] = r[2], mode[2] = -r[0];
      for (std::size_t c = 0; c < d; ++c)
        v[d * i + c] = mode[c] / s[d * i + c];
    }
    VecRestoreArray(modes[m], &v);
  }
  VecRestoreArrayRead(s_u, &s);
  VecRestoreSubVector(_s, _is_u, &s_u);
  // modified Gram-Schmidt (MatNullSpaceCreate wants orthonormal vectors)
  for (int m = 0; m < n_modes; ++m)
  {
    for (int j = 0; j < m; ++j)
    {
      PetscScalar dot;
      VecDot(modes[m], modes[j], &dot);
      VecAXPY(modes[m], -dot, modes[j]);
    }
    VecNormalize(modes[m], nullptr);
  }
  MatNullSpace space;
  MatNullSpaceCreate(_comm, PETSC_FALSE, n_modes, modes.data(), &space);
  MatSetNearNullSpace(P_u, space);
  if (A_u != P_u)
    MatSetNearNullSpace(A_u, space);
  MatNullSpaceDestroy(&space);
  for (Vec& v : modes)
    VecDestroy(&v);
}

void LinearSolverSetup::set_newton_tolerance(double atol)
{
  if (iterative())
    KSPSetTolerances(_ksp, _rtol, atol, PETSC_DEFAULT, _max_it);
}

void LinearSolverSetup::set_relative_tolerance()
{
  if (iterative())
    KSPSetTolerances(_ksp, std::min<PetscReal>(_rtol, 1e-12), 0.0, PETSC_DEFAULT, _max_it);
}

int LinearSolverSetup::check_solve(const std::string& what)
{
  KSPConvergedReason reason;
  KSPGetConvergedReason(_ksp, &reason);
  // the same verdict on every rank (a PC can fail on one rank only)
  int worst = reason;
  MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_INT, MPI_MIN, _comm);
  reason = static_cast<KSPConvergedReason>(std::min<int>(worst, reason));
  PetscInt its = 0;
  KSPGetIterationNumber(_ksp, &its);
  if (reason >= 0)
  {
    PetscReal r = 0.0;
    KSPGetResidualNorm(_ksp, &r);
    if (iterative() and its >= 5 and r > 0.0 and _b_norm > r)
    {
      // iterations per decade: comparable between solves of any tolerance
      const double rate = its / std::max(0.5, std::log10(_b_norm / r));
      _best_rate = std::min(_best_rate, rate);
      _stale = _stale or rate > 2.0 * _best_rate;
    }
    return its;
  }
  char text[400];
  if (reason == KSP_DIVERGED_PC_FAILED and !iterative())
    factorisation_failed(what);
  std::snprintf(text, sizeof(text), "the %s solver did not converge in %d iterations (%s, %s)",
                iterative() ? "Krylov" : "linear", int(its), reason_name(reason).c_str(),
                what.c_str());
  throw LinearSolveFailure(text, true);
}

// An LU (or Cholesky) that failed: out of memory stops the run, with the
// way out; MUMPS says which (its INFOG(1)), other packages less
void LinearSolverSetup::factorisation_failed(const std::string& what) const
{
  PC pc;
  KSPGetPC(_ksp, &pc);
  char text[400];
  const char* kind = is_type(pc, PCCHOLESKY) ? "LDL^T" : "LU";
  if (!is_type(pc, PCLU) and !is_type(pc, PCCHOLESKY))
  {
    std::snprintf(text, sizeof(text), "the preconditioner failed (%s)", what.c_str());
    throw LinearSolveFailure(text, true);
  }
  Mat F = nullptr;
  PCFactorGetMatrix(pc, &F);
  MatFactorError error = MAT_FACTOR_NOERROR;
  MatFactorGetError(F, &error);
#if PETSC_HAVE_MUMPS
  MatSolverType package = nullptr;
  MatFactorGetSolverType(F, &package);
  PetscBool mumps = PETSC_FALSE;
  PetscStrcmp(package, MATSOLVERMUMPS, &mumps);
  PetscInt info = 0;
  if (mumps)
    MatMumpsGetInfog(F, 1, &info);
  if (mumps and (info == -8 or info == -9 or info == -14 or info == -15 or info == -17
                 or info == -20))
  {
    // its workspace estimate was too small: more slack usually cures it
    std::snprintf(text, sizeof(text),
                  "the %s factorisation failed (%s): MUMPS INFOG(1) = %d, its workspace "
                  "estimate was too small",
                  kind, what.c_str(), int(info));
    throw LinearSolveFailure(text, false,
                             "raise solver.petsc_options.mat_mumps_icntl_14 (percent of slack, "
                             "default 20), or use solver.linear = \"iterative\"");
  }
#endif
  if (error == MAT_FACTOR_OUTMEMORY)
  {
    std::snprintf(text, sizeof(text), "the %s factorisation ran out of memory (%s)", kind,
                  what.c_str());
    throw LinearSolveFailure(text, false,
                             "solver.linear = \"iterative\" needs a fraction of the memory");
  }
  std::snprintf(text, sizeof(text), "the %s factorisation failed (%s, %s)", kind, what.c_str(),
                error == MAT_FACTOR_NUMERIC_ZEROPIVOT ? "zero pivot" : "PC failed");
  throw LinearSolveFailure(text, true);
}

// The caller's b is kept and restored exactly (the floating electrodes
// reuse theirs across set-ups); a nonzero initial guess is mapped too
PetscErrorCode LinearSolverSetup::pre_solve(KSP ksp, Vec b, Vec x, void* ctx)
{
  auto* self = static_cast<LinearSolverSetup*>(ctx);
  if (!self->_negated and !self->iterative())
    return 0;
  if (!self->_b_saved)
    PetscCall(VecDuplicate(b, &self->_b_saved));
  PetscCall(VecCopy(b, self->_b_saved));
  if (self->_negated)
    PetscCall(VecPointwiseMult(b, b, self->_sign));
  if (!self->iterative())
    return 0;
  PetscCall(VecPointwiseMult(b, b, self->_s));
  PetscReal norm;
  PetscCall(VecNorm(b, NORM_2, &norm));
  self->_b_norm = norm;
  PetscBool guess;
  PetscCall(KSPGetInitialGuessNonzero(ksp, &guess));
  if (guess)
    PetscCall(VecPointwiseDivide(x, x, self->_s));
  return 0;
}

PetscErrorCode LinearSolverSetup::post_solve(KSP, Vec b, Vec x, void* ctx)
{
  auto* self = static_cast<LinearSolverSetup*>(ctx);
  if (!self->_negated and !self->iterative())
    return 0;
  if (self->iterative())
    PetscCall(VecPointwiseMult(x, x, self->_s));
  return VecCopy(self->_b_saved, b);
}
} // namespace piezocontact
