#include "matrices.h"

#include <cmath>

#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/SparsityPattern.h>
#include <dolfinx/la/petsc.h>

namespace piezocontact
{
using namespace dolfinx;

/// A matrix whose sparsity holds every term of a sum of bilinear forms on
/// V x V (cell and exterior-facet integrals, the kinds the model has)
Mat create_matrix(const FormList& terms, const compat::FunctionSpace& V)
{
  const auto& dofmap = *V.dofmap();
  const int bs = dofmap.index_map_bs();
  la::SparsityPattern pattern(V.mesh()->comm(), {dofmap.index_map, dofmap.index_map},
                              {bs, bs});
  for (const auto& a : terms)
    compat::add_sparsity(pattern, *a, dofmap);
  compat::finalize(pattern);
  return la::petsc::create_matrix(V.mesh()->comm(), pattern);
}

void assemble_into(Mat M, const FormList& terms,
                   const std::vector<std::shared_ptr<const fem::DirichletBC<double>>>& bcs,
                   const compat::FunctionSpace& V)
{
  MatZeroEntries(M);
  for (const auto& a : terms)
    compat::assemble_matrix(la::petsc::Matrix::set_fn(M, ADD_VALUES), *a, bcs);
  MatAssemblyBegin(M, MAT_FLUSH_ASSEMBLY);
  MatAssemblyEnd(M, MAT_FLUSH_ASSEMBLY);
  compat::set_diagonal(la::petsc::Matrix::set_fn(M, INSERT_VALUES), V, bcs);
  MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY);
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
void jacobi_scaling(Mat A, Vec s)
{
  MatGetDiagonal(A, s);
  PetscInt n;
  VecGetLocalSize(s, &n);
  PetscScalar* a;
  VecGetArray(s, &a);
  for (PetscInt i = 0; i < n; ++i)
    a[i] = a[i] != 0.0 ? 1.0 / std::sqrt(std::abs(a[i])) : 1.0;
  VecRestoreArray(s, &a);
}

double scaled_asymmetry(Mat A, Vec row_sign)
{
  Mat B, T;
  MatDuplicate(A, MAT_COPY_VALUES, &B);
  if (row_sign)
    MatDiagonalScale(B, row_sign, nullptr);
  Vec s;
  MatCreateVecs(B, &s, nullptr);
  jacobi_scaling(B, s);
  MatDiagonalScale(B, s, s);
  MatTranspose(B, MAT_INITIAL_MATRIX, &T);
  // the pattern is symmetric (one space for test and trial), but the
  // transpose's storage need not match B's entry for entry
  MatAXPY(T, -1.0, B, DIFFERENT_NONZERO_PATTERN);
  PetscReal defect = 0.0;
  MatNorm(T, NORM_MAX, &defect);
  MatDestroy(&T);
  MatDestroy(&B);
  VecDestroy(&s);
  return defect;
}
} // namespace piezocontact
