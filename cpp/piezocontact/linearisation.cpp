#include "linearisation.h"
#include "matrices.h"

#include <algorithm>
#include <dolfinx/la/petsc.h>
#include <limits>
#include <stdexcept>

namespace piezocontact
{
using namespace dolfinx;

namespace
{
/// Throws on a PETSc error code (the quiet handler turned its print off)
void check(PetscErrorCode ierr, const char* what)
{
  if (ierr != 0)
    throw std::runtime_error(std::string("PETSc failed in ") + what);
}

/// A matrix of the sum of some forms, on a copy of `pattern`'s sparsity
/// (K's holds C's and M's: one pattern, built once)
la::petsc::Matrix assembled(const FormList& terms, Mat pattern, const compat::FunctionSpace& W)
{
  Mat A;
  MatDuplicate(pattern, MAT_DO_NOT_COPY_VALUES, &A);
  assemble_into(A, terms, {}, W);
  return la::petsc::Matrix(A, false);
}

FormList all_forms(const Model& m)
{
  FormList out = m.K;
  out.insert(out.end(), m.C.begin(), m.C.end());
  out.insert(out.end(), m.M.begin(), m.M.end());
  return out;
}
} // namespace

Linearisation::Linearisation(Problem& p)
    : _K(nullptr, false), _C(nullptr, false), _M(nullptr, false)
{
  if (!p.model.x_dot)
    throw std::logic_error("the model has no linearisation (ModelSpec::linearised)");
  std::fill(compat::mutable_values(*p.model.x_dot->x()).begin(),
            compat::mutable_values(*p.model.x_dot->x()).end(), 0.0); // the state at rest
  la::petsc::Matrix pattern(create_matrix(all_forms(p.model), *p.W), false);
  _K = assembled(p.model.K, pattern.mat(), *p.W);
  _C = assembled(p.model.C, pattern.mat(), *p.W);
  _M = assembled(p.model.M, pattern.mat(), *p.W);
  check(MatCreateVecs(_K.mat(), &_sign, nullptr), "MatCreateVecs");
  PetscInt r0 = 0, r1 = 0;
  MatGetOwnershipRange(_K.mat(), &r0, &r1);
  VecSet(_sign, 1.0);
  for (auto d : p.phi_dofs)
    if (d < r1 - r0)
      VecSetValue(_sign, r0 + d, -1.0, INSERT_VALUES);
  VecAssemblyBegin(_sign);
  VecAssemblyEnd(_sign);
  build_reduction(p);
}

Linearisation::~Linearisation()
{
  if (_sign)
    VecDestroy(&_sign);
}

// Owned dofs are contiguous in PETSc's numbering: global = r0 + local
void Linearisation::build_reduction(Problem& p)
{
  PetscInt r0 = 0, r1 = 0;
  MatGetOwnershipRange(_K.mat(), &r0, &r1);
  const std::int32_t owned = r1 - r0;
  std::vector<std::int32_t> floating_dofs;
  _representative.assign(p.electrodes.size(), -1);
  for (std::size_t e = 0; e < p.electrodes.size(); ++e)
  {
    const Electrode& el = p.electrodes[e];
    if (!el.floating)
      continue;
    floating_dofs.insert(floating_dofs.end(), el.dofs.begin(), el.dofs.end());
    PetscInt lowest = std::numeric_limits<PetscInt>::max();
    for (auto d : el.dofs)
      if (d < owned)
        lowest = std::min<PetscInt>(lowest, r0 + d);
    MPI_Allreduce(MPI_IN_PLACE, &lowest, 1, MPIU_INT, MPI_MIN, p.comm);
    _representative[e] = lowest;
  }
  std::sort(floating_dofs.begin(), floating_dofs.end());
  for (auto d : p.bc_dofs())
    if (d < owned and !std::binary_search(floating_dofs.begin(), floating_dofs.end(), d))
      _removed.push_back(r0 + d);
  int any_floating = !floating_dofs.empty();
  MPI_Allreduce(MPI_IN_PLACE, &any_floating, 1, MPI_INT, MPI_LOR, p.comm);
  if (any_floating)
  {
    // P: identity, but an electrode's dofs all map to its representative
    std::vector<PetscInt> column(owned);
    for (std::int32_t i = 0; i < owned; ++i)
      column[i] = r0 + i;
    for (std::size_t e = 0; e < p.electrodes.size(); ++e)
      if (p.electrodes[e].floating)
        for (auto d : p.electrodes[e].dofs)
          if (d < owned)
          {
            column[d] = _representative[e];
            if (r0 + d != _representative[e])
              _removed.push_back(r0 + d);
          }
    Mat P;
    check(MatCreateAIJ(p.comm, owned, owned, PETSC_DETERMINE, PETSC_DETERMINE, 1, nullptr, 1,
                       nullptr, &P),
          "MatCreateAIJ");
    for (std::int32_t i = 0; i < owned; ++i)
      MatSetValue(P, r0 + i, column[i], 1.0, INSERT_VALUES);
    MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY);
    _P.emplace(P, false);
  }
  std::sort(_removed.begin(), _removed.end());
  _removed.erase(std::unique(_removed.begin(), _removed.end()), _removed.end());
}

Mat Linearisation::reduced_unconstrained(const la::petsc::Matrix& A) const
{
  Mat out;
  if (_P)
    check(MatPtAP(A.mat(), _P->mat(), MAT_INITIAL_MATRIX, 2.0, &out), "MatPtAP");
  else
    check(MatDuplicate(A.mat(), MAT_COPY_VALUES, &out), "MatDuplicate");
  return out;
}

Mat Linearisation::reduced(const la::petsc::Matrix& A, double diagonal, bool flip) const
{
  Mat out = reduced_unconstrained(A);
  if (flip)
    MatDiagonalScale(out, _sign, nullptr); // P keeps phi dofs phi dofs: the sign applies
  // every removed dof gets its diagonal entry (set below), present or not
  MatSetOption(out, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE);
  check(MatZeroRowsColumns(out, PetscInt(_removed.size()), _removed.data(), diagonal, nullptr,
                           nullptr),
        "MatZeroRowsColumns");
  return out;
}

void Linearisation::prolong(Vec z, Vec x) const
{
  if (_P)
    MatMult(_P->mat(), z, x);
  else
    VecCopy(z, x);
}

void Linearisation::restrict_to(Vec x, Vec z) const
{
  if (_P)
    MatMultTranspose(_P->mat(), x, z);
  else
    VecCopy(x, z);
}
} // namespace piezocontact
