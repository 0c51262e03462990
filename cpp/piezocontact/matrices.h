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

/// s <- |diag A|^-1/2 (1 where the diagonal is 0): S A S has entries of
/// order 1 whatever the units of its blocks
void jacobi_scaling(Mat A, Vec s);

/// The largest |a_ij - a_ji| of diag(row_sign) A, Jacobi-scaled (each
/// entry over sqrt|a_ii a_jj|, 1 where a diagonal is 0) so that blocks of
/// any units compare: round-off (1e-16..1e-15) for a symmetric sum of
/// forms. No row_sign: A itself. Collective.
double scaled_asymmetry(Mat A, Vec row_sign = nullptr);

/// A is symmetric to the assembly's round-off when its scaled asymmetry is
/// at most this (measured 2e-16..3e-15 on the demo configs; a skew term at
/// 1e-4 of the stiffness gives 1e-4, Nitsche on a piezoelectric boundary 1)
constexpr double symmetry_tolerance = 1e-12;

/// This rank's entries of a PETSc vector
std::vector<double> owned_entries(Vec x);
} // namespace piezocontact
