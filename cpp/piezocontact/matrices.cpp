#include "matrices.h"

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
    fem::assemble_matrix(la::petsc::Matrix::set_fn(M, ADD_VALUES), *a, bcs);
  MatAssemblyBegin(M, MAT_FLUSH_ASSEMBLY);
  MatAssemblyEnd(M, MAT_FLUSH_ASSEMBLY);
  fem::set_diagonal<double>(la::petsc::Matrix::set_fn(M, INSERT_VALUES), V, bcs);
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
} // namespace piezocontact
