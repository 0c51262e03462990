// Sums of bilinear forms as PETSc matrices: the Jacobian of Newton's
// method and the matrices of a linearisation (dynamics.h) are each one sum
// of the catalogue's terms, on the mixed space W.
#pragma once

#include "model.h"

#include <dolfinx/fem/DirichletBC.h>
#include <memory>
#include <petscmat.h>
#include <petscvec.h>
#include <vector>

namespace piezocontact
{
/// A matrix whose sparsity holds every term of a sum of bilinear forms on
/// V x V (cell and exterior-facet integrals, the kinds the model has)
Mat create_matrix(const FormList& terms, const compat::FunctionSpace& V);

/// M <- the sum of the terms, with identity rows and columns at the dofs
/// of bcs (none: the unconstrained sum)
void assemble_into(Mat M, const FormList& terms,
                   const std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>>& bcs,
                   const compat::FunctionSpace& V);

/// This rank's entries of a PETSc vector
std::vector<double> owned_entries(Vec x);
} // namespace piezocontact
