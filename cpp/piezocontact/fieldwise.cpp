#include "fieldwise.h"

#include <dolfinx/la/petsc.h>

#include <cmath>
#include <limits>
#include <set>

namespace piezocontact
{
namespace
{
/// What double precision can promise of a sum of many terms: 1000 eps
constexpr double roundoff = 1e3 * std::numeric_limits<double>::epsilon();
} // namespace

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

namespace
{
/// Replace the values of an AIJ matrix by their absolute values; false for
/// another type (then no coupling floor: the test is r_f <= rtol s_f + ...)
bool absolute_values(Mat M)
{
  PetscBool mpi, seq;
  PetscObjectTypeCompare((PetscObject)M, MATMPIAIJ, &mpi);
  PetscObjectTypeCompare((PetscObject)M, MATSEQAIJ, &seq);
  std::vector<Mat> blocks;
  if (mpi)
  {
    Mat Ad, Ao;
    const PetscInt* colmap;
    MatMPIAIJGetSeqAIJ(M, &Ad, &Ao, &colmap);
    blocks = {Ad, Ao};
  }
  else if (seq)
    blocks = {M};
  else
    return false;
  for (Mat B : blocks)
  {
    PetscInt rows;
    MatGetLocalSize(B, &rows, nullptr);
    const PetscInt *ia, *ja;
    PetscInt n;
    PetscBool done;
    MatGetRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done);
    PetscScalar* values;
    MatSeqAIJGetArray(B, &values);
    for (PetscInt k = 0; done and k < ia[n]; ++k)
      values[k] = std::abs(values[k]);
    MatSeqAIJRestoreArray(B, &values);
    MatRestoreRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done);
  }
  return true;
}
} // namespace

void FieldwiseConvergence::set_scaling(Mat A, bool scaled_in_place)
{
  _A = A;
  _scaled = scaled_in_place;
  _abs_stale = true; // |J| is made when a zero field needs it
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

// sum_j |J_ij x_j| over the columns j of other fields than row i's: |J|
// times |x| restricted to each field in turn
std::vector<double> FieldwiseConvergence::coupling(std::span<const double> x)
{
  std::vector<double> local(_dofs.size(), 0.0), global(_dofs.size(), 0.0);
  if (_abs_stale)
  {
    _abs_stale = false;
    if (!_abs_A) // one copy, refilled (the sparsity of J is fixed)
    {
      Mat copy;
      MatDuplicate(_A, MAT_COPY_VALUES, &copy);
      _abs_A = std::make_unique<dolfinx::la::petsc::Matrix>(copy, false);
      Vec in, out;
      MatCreateVecs(_A, &in, &out);
      _in = std::make_unique<dolfinx::la::petsc::Vector>(in, false);
      _out = std::make_unique<dolfinx::la::petsc::Vector>(out, false);
    }
    else
      MatCopy(_A, _abs_A->mat(), SAME_NONZERO_PATTERN);
    if (!absolute_values(_abs_A->mat()))
      _abs_A.reset();
  }
  if (!_abs_A)
    return global;
  for (const auto& [from, from_dofs] : _dofs)
  {
    VecSet(_in->vec(), 0.0);
    PetscScalar* a;
    VecGetArray(_in->vec(), &a);
    // D^-1/2 |J| |x| = |D^-1/2 J D^-1/2| (D^1/2 |x|)
    for (auto i : from_dofs)
      a[i] = _scaled ? std::abs(x[i]) * _sqrt_d[i] : std::abs(x[i]);
    VecRestoreArray(_in->vec(), &a);
    MatMult(_abs_A->mat(), _in->vec(), _out->vec());
    const PetscScalar* y;
    VecGetArrayRead(_out->vec(), &y);
    std::size_t f = 0;
    for (const auto& [to, to_dofs] : _dofs)
    {
      if (to != from)
        for (auto i : to_dofs)
        {
          const double yi = _scaled ? y[i] : y[i] / _sqrt_d[i];
          local[f] += yi * yi;
        }
      ++f;
    }
    VecRestoreArrayRead(_out->vec(), &y);
  }
  MPI_Allreduce(local.data(), global.data(), global.size(), MPI_DOUBLE, MPI_SUM, _comm);
  for (double& c : global)
    c = std::sqrt(c);
  return global;
}

bool FieldwiseConvergence::check(std::span<const double> x,
                                 std::span<const double> b)
{
  // per field: ||F||^2, ||D^-1/2 F||^2, ||D^1/2 x||^2; fields in name order
  // ("phi", "u"), the sums are order-independent
  // and ||D^1/2 (x - x_last)||^2, the last Newton update
  std::vector<double> sums;
  const bool first = history.empty();
  if (first)
    _x_last.assign(x.begin(), x.end());
  for (const auto& [name, dofs] : _dofs)
  {
    double si = 0, r = 0, s = 0, u = 0;
    for (auto i : dofs)
    {
      si += b[i] * b[i];
      r += (b[i] / _sqrt_d[i]) * (b[i] / _sqrt_d[i]);
      s += (x[i] * _sqrt_d[i]) * (x[i] * _sqrt_d[i]);
      u += ((x[i] - _x_last[i]) * _sqrt_d[i]) * ((x[i] - _x_last[i]) * _sqrt_d[i]);
    }
    sums.insert(sums.end(), {si, r, s, u});
  }
  std::copy(x.begin(), x.end(), _x_last.begin());
  std::vector<double> global(sums.size());
  MPI_Allreduce(sums.data(), global.data(), sums.size(), MPI_DOUBLE, MPI_SUM, _comm);

  std::map<std::string, FieldNorms> entry;
  bool ok = true, residuals_ok = true;
  double threshold = std::numeric_limits<double>::infinity(), size = 0.0;
  std::vector<double> coupled; // c_f, computed only if a field fails its test
  std::size_t f = 0;
  for (const auto& [name, _] : _dofs)
  {
    const double si = std::sqrt(global[4 * f]), r = std::sqrt(global[4 * f + 1]),
                 s = std::sqrt(global[4 * f + 2]), du = std::sqrt(global[4 * f + 3]);
    // The floor is this field's own scale at the solve's first iterate
    if (first)
      _s_start[name] = s;
    double accept = _rtol * s + _atol * _s_start[name];
    // The update bounds the error of the iterate it corrected: the solution
    // is accepted only after one, so both engines stop on a bound of the
    // error (the residual alone leaves up to cond(J) rtol in x)
    bool converged = !first and r <= accept and du <= accept;
    bool residual_ok = !first and r <= accept;
    double scale = s; // what the test measures r_f against
    // after a Newton step, a field that fails may be zero to the round-off
    // of the terms around it. c_f <= K s_g (the scaled coupling block is
    // O(1), K ~ 1e3 at most): look only where s_f and r_f could be that
    // small (collective: every rank sees the same norms)
    double others = 0.0;
    for (std::size_t g = 0; g < _dofs.size(); ++g)
      others += g == f ? 0.0 : global[4 * g + 2];
    const double bound = 1e3 * std::sqrt(others);
    if (!converged and !first and _A and s <= roundoff * bound and r <= roundoff * bound)
    {
      if (coupled.empty())
        coupled = coupling(x);
      if (s <= roundoff * coupled[f])
      {
        scale = coupled[f];
        accept = roundoff * coupled[f];
        converged = r <= accept and du <= accept;
        residual_ok = r <= accept;
      }
    }
    threshold = std::min(threshold, accept);
    size += s * s;
    const double rel = scale > 0 ? r / scale
                                 : (r == 0 ? 0.0 : std::numeric_limits<double>::quiet_NaN());
    entry[name] = {si, r, rel,
                   first ? std::numeric_limits<double>::quiet_NaN()
                         : (scale > 0 ? du / scale : (du == 0 ? 0.0 : std::numeric_limits<double>::quiet_NaN()))};
    ok = ok and converged;
    residuals_ok = residuals_ok and residual_ok;
    ++f;
  }
  history.push_back(entry);
  _residuals_converged = residuals_ok;
  // a zero field (s_f = 0 at a predictor, or short-circuited) asks for
  // what round-off allows
  _krylov_atol = std::max(0.5 * threshold, 0.1 * roundoff * std::sqrt(size));
  return ok;
}
} // namespace piezocontact
