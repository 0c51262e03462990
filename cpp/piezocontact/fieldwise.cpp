#include "fieldwise.h"

#include <dolfinx/la/petsc.h>

#include <cmath>
#include <limits>
#include <set>

namespace piezocontact
{
FieldwiseConvergence::FieldwiseConvergence(
    const std::map<std::string, std::vector<std::int32_t>>& field_dofs,
    const std::vector<std::int32_t>& bc_dofs, std::int32_t num_owned,
    double rtol, double atol, MPI_Comm comm)
    : _rtol(rtol), _atol(atol), _comm(comm)
{
  const std::set<std::int32_t> constrained(bc_dofs.begin(), bc_dofs.end());
  for (const auto& [name, dofs] : field_dofs)
  {
    _dofs[name] = {}; // every rank holds every field, owned dofs or not
    for (auto d : dofs)
      if (d < num_owned and !constrained.contains(d))
        _dofs[name].push_back(d);
  }
}

void FieldwiseConvergence::set_scaling(Mat A)
{
  Vec v;
  MatCreateVecs(A, nullptr, &v);
  const dolfinx::la::petsc::Vector diagonal(v, false); // destroys v
  const Vec d = diagonal.vec();
  MatGetDiagonal(A, d);
  PetscInt n;
  VecGetLocalSize(d, &n);
  const PetscScalar* a;
  VecGetArrayRead(d, &a);
  _sqrt_d.resize(n);
  for (PetscInt i = 0; i < n; ++i)
    _sqrt_d[i] = a[i] != 0.0 ? std::sqrt(std::abs(a[i])) : 1.0;
  VecRestoreArrayRead(d, &a);
}

bool FieldwiseConvergence::check(std::span<const double> x,
                                 std::span<const double> b)
{
  // per field: ||F||^2, ||D^-1/2 F||^2, ||D^1/2 x||^2; fields in name order
  // ("phi", "u"), the sums are order-independent
  std::vector<double> sums;
  const bool first = history.empty();
  for (const auto& [name, dofs] : _dofs)
  {
    double si = 0, r = 0, s = 0;
    for (auto i : dofs)
    {
      si += b[i] * b[i];
      r += (b[i] / _sqrt_d[i]) * (b[i] / _sqrt_d[i]);
      s += (x[i] * _sqrt_d[i]) * (x[i] * _sqrt_d[i]);
    }
    sums.insert(sums.end(), {si, r, s});
  }
  std::vector<double> global(sums.size());
  MPI_Allreduce(sums.data(), global.data(), sums.size(), MPI_DOUBLE, MPI_SUM, _comm);

  std::map<std::string, FieldNorms> entry;
  bool ok = true;
  std::size_t f = 0;
  for (const auto& [name, _] : _dofs)
  {
    const double si = std::sqrt(global[3 * f]), r = std::sqrt(global[3 * f + 1]),
                 s = std::sqrt(global[3 * f + 2]);
    const double rel = s > 0 ? r / s
                             : (r == 0 ? 0.0 : std::numeric_limits<double>::quiet_NaN());
    entry[name] = {si, r, rel};
    // The floor is this field's own scale at the solve's first iterate
    if (first)
      _s_start[name] = s;
    ok = ok and r <= _rtol * s + _atol * _s_start[name];
    ++f;
  }
  history.push_back(entry);
  return ok;
}
} // namespace piezocontact
