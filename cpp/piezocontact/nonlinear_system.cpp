#include "nonlinear_system.h"
#include "matrices.h"

#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/SparsityPattern.h>
#include <dolfinx/la/petsc.h>

#include <algorithm>
#include <optional>

namespace piezocontact
{
using namespace dolfinx;
namespace
{
/// This rank's stored values of an AIJ matrix M (its sparsity is fixed):
/// read from the CSR arrays, O(entries), not O(rows): J_contact has entries
/// on the contact facets' rows only. Mat-level MatEqual/MatCopy fail on
/// MPIAIJ matrices assembled like this.
std::vector<double> local_values(Mat M)
{
  PetscBool mpi, seq;
  PetscObjectTypeCompare((PetscObject)M, MATMPIAIJ, &mpi);
  PetscObjectTypeCompare((PetscObject)M, MATSEQAIJ, &seq);
  std::vector<double> out;
  if (!mpi and !seq) // another type: row by row, O(rows)
  {
    PetscInt r0, r1;
    MatGetOwnershipRange(M, &r0, &r1);
    for (PetscInt row = r0; row < r1; ++row)
    {
      PetscInt ncols;
      const PetscScalar* vals;
      MatGetRow(M, row, &ncols, nullptr, &vals);
      out.insert(out.end(), vals, vals + ncols);
      MatRestoreRow(M, row, &ncols, nullptr, &vals);
    }
    return out;
  }
  std::vector<Mat> blocks{M};
  if (mpi)
  {
    Mat Ad, Ao;
    const PetscInt* colmap;
    MatMPIAIJGetSeqAIJ(M, &Ad, &Ao, &colmap);
    blocks = {Ad, Ao};
  }
  for (Mat B : blocks)
  {
    MatInfo info;
    MatGetInfo(B, MAT_LOCAL, &info);
    const PetscScalar* values;
    MatSeqAIJGetArrayRead(B, &values);
    out.insert(out.end(), values, values + static_cast<std::size_t>(info.nz_used));
    MatSeqAIJRestoreArrayRead(B, &values);
  }
  return out;
}

/// J without Dirichlet conditions where floating electrodes need it (no
/// matrix otherwise)
std::optional<la::petsc::Matrix> unconstrained_jacobian(const Problem& p)
{
  if (std::none_of(p.electrodes.begin(), p.electrodes.end(),
                   [](const Electrode& e) { return e.floating; }))
    return std::nullopt;
  la::petsc::Matrix J(create_matrix(p.model.J, *p.W), false);
  assemble_into(J.mat(), p.model.J, {}, *p.W);
  return J;
}
} // namespace

NonlinearSystem::NonlinearSystem(Problem& p, FieldwiseConvergence& monitor, KSP ksp,
                                 bool reuse_lu, LinearSolver linear_solver, bool symmetric)
    : b(la::petsc::create_vector(*p.W->dofmap()->index_map, p.W->dofmap()->index_map_bs()),
        false),
      A(create_matrix(p.model.J, *p.W), false), linear(ksp, p, linear_solver, symmetric),
      floating(p, unconstrained_jacobian(p)), _p(p), _monitor(monitor), _ksp(ksp), _reuse(reuse_lu),
      _Jc(create_matrix(p.model.J_contact, *p.W), false)
{
}

void NonlinearSystem::F(const Vec x, Vec r)
{
  ScopedTimer timer(residual, "residual");
  Vec r_local;
  VecGhostGetLocalForm(r, &r_local);
  VecSet(r_local, 0.0);
  VecGhostRestoreLocalForm(r, &r_local);
  for (const auto& term : _p.model.F)
    fem::petsc::assemble_vector(r, *term);
  // lifting is linear in the bilinear form: term by term is the sum's
  for (const auto& term : _p.model.J)
    compat::apply_lifting(r, term, _p.bcs(), x, -1.0);
  VecGhostUpdateBegin(r, ADD_VALUES, SCATTER_REVERSE);
  VecGhostUpdateEnd(r, ADD_VALUES, SCATTER_REVERSE);
  record_reactions(r);
  if (!floating.empty())
  {
    PetscInt n;
    VecGetLocalSize(r, &n);
    const PetscScalar *ra, *xa;
    VecGetArrayRead(r, &ra);
    VecGetArrayRead(x, &xa);
    floating.residual(std::span<const double>(ra, n), std::span<const double>(xa, n));
    VecRestoreArrayRead(x, &xa);
    VecRestoreArrayRead(r, &ra);
  }
  compat::set_bc(r, _p.bcs(), x, -1.0);
}

// At a Dirichlet row the residual before set_bc is the unconstrained one
// (the lifting adds A(g - x), zero once x holds the boundary values)
void NonlinearSystem::record_reactions(Vec r)
{
  const PetscScalar* a;
  VecGetArrayRead(r, &a);
  PetscInt n;
  VecGetLocalSize(r, &n);
  unconstrained.assign(a, a + n);
  balance = _p.force_balance(std::span<const double>(a, n));
  VecRestoreArrayRead(r, &a);
}

void NonlinearSystem::J(const Vec, Mat M)
{
  bool same = false;
  const double k = _p.model.constants.at("k")->value[0];
  {
    ScopedTimer timer(contact_jacobian, "contact Jacobian");
    assemble_into(_Jc.mat(), _p.model.J_contact, {}, *_p.W);
    std::vector<double> values = local_values(_Jc.mat());
    int equal = _reuse and k == _k_last and values == _Jc_last;
    MPI_Allreduce(MPI_IN_PLACE, &equal, 1, MPI_INT, MPI_LAND, _p.comm);
    same = equal;
    _k_last = k;
    _Jc_last = std::move(values);
  }
  if (same)
  {
    ++reused; // M unchanged: its state too, so PETSc keeps the LU (or AMG)
    linear.set_newton_tolerance(_monitor.krylov_atol());
    return;
  }
  {
    ScopedTimer timer(jacobian, "Jacobian");
    assemble_into(M, _p.model.J, _p.bcs(), *_p.W);
  }
  const auto x = compat::values(*_p.x->x());
  x_assembled.assign(x.begin(), x.end());
  const bool k_changed = k != k_assembled;
  k_assembled = k;
  _monitor.set_scaling(M, linear.iterative()); // reads the unscaled diagonal
  {
    // Factorise (set up the preconditioner) here, timed apart from the
    // solves of KSPSolve
    compat::Timer timer(linear.iterative() ? "piezocontact: preconditioner set-up"
                                           : "piezocontact: LU factorisation");
    const bool fresh = linear.operator_changed(M, k_changed);
    factorisation.seconds += timer.stop();
    ++(fresh ? factorisation.count : lagged);
  }
  if (!floating.empty())
  {
    linear.set_relative_tolerance();
    floating.factorised(_ksp, [this] { linear.check_solve("a floating electrode's unit response"); });
  }
  linear.set_newton_tolerance(_monitor.krylov_atol());
}

bool NonlinearSystem::exact_update()
{
  if (linear.iterative())
    return false; // a Krylov solve stops at a tolerance
  const double k = _p.model.constants.at("k")->value[0];
  int equal;
  {
    ScopedTimer timer(contact_jacobian, "contact Jacobian");
    assemble_into(_Jc.mat(), _p.model.J_contact, {}, *_p.W);
    equal = k == _k_last and local_values(_Jc.mat()) == _Jc_last;
  }
  MPI_Allreduce(MPI_IN_PLACE, &equal, 1, MPI_INT, MPI_LAND, _p.comm);
  return equal;
}

void NonlinearSystem::update(Vec dx, Vec x)
{
  linear.check_solve("Newton step");
  floating.update(dx, x);
}
} // namespace piezocontact
