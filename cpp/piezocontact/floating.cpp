#include "floating.h"

#include <cmath>
#include <stdexcept>

namespace piezocontact
{
using namespace dolfinx;
namespace
{
la::petsc::Vector make_vector(const Problem& p)
{
  return la::petsc::Vector(
      la::petsc::create_vector(*p.W->dofmap()->index_map, p.W->dofmap()->index_map_bs()),
      false);
}

/// Set `value` at the owned entries among local `dofs`
void set_owned(Vec v, const std::vector<std::int32_t>& dofs, double value)
{
  PetscInt n;
  VecGetLocalSize(v, &n);
  PetscScalar* a;
  VecGetArray(v, &a);
  for (auto d : dofs)
    if (d < n)
      a[d] = value;
  VecRestoreArray(v, &a);
}

/// Solve the small dense system M y = b (Gaussian elimination, partial
/// pivoting); every rank holds the same M and b
std::vector<double> solve_dense(std::vector<double> M, std::vector<double> b)
{
  const std::size_t n = b.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    std::size_t pivot = k;
    for (std::size_t i = k + 1; i < n; ++i)
      if (std::abs(M[i * n + k]) > std::abs(M[pivot * n + k]))
        pivot = i;
    double largest = 0.0;
    for (double m : M)
      largest = std::max(largest, std::abs(m));
    if (!(std::abs(M[pivot * n + k]) > 1e-13 * largest))
      throw std::runtime_error(
          "the floating electrodes' capacitances are singular: is an electrode, or a part of "
          "the body, insulated from every prescribed potential?");
    for (std::size_t j = 0; j < n; ++j)
      std::swap(M[k * n + j], M[pivot * n + j]);
    std::swap(b[k], b[pivot]);
    for (std::size_t i = k + 1; i < n; ++i)
    {
      const double f = M[i * n + k] / M[k * n + k];
      for (std::size_t j = k; j < n; ++j)
        M[i * n + j] -= f * M[k * n + j];
      b[i] -= f * b[k];
    }
  }
  std::vector<double> y(n);
  for (std::size_t k = n; k-- > 0;)
  {
    double s = b[k];
    for (std::size_t j = k + 1; j < n; ++j)
      s -= M[k * n + j] * y[j];
    y[k] = s / M[k * n + k];
  }
  return y;
}
} // namespace

FloatingPotentials::FloatingPotentials(Problem& p,
                                       const std::optional<la::petsc::Matrix>& matrix)
    : _p(p)
{
  for (std::size_t e = 0; e < p.electrodes.size(); ++e)
    if (p.electrodes[e].floating)
      _index.push_back(e);
  if (_index.empty())
    return;
  const Mat J = matrix->mat();
  la::petsc::Vector ones = make_vector(p);
  for (std::size_t e : _index)
  {
    VecSet(ones.vec(), 0.0);
    set_owned(ones.vec(), p.electrodes[e].dofs, 1.0);
    // c_e = J^T 1_e: the change of the electrode's charge with x
    _c.push_back(make_vector(p));
    MatMultTranspose(J, ones.vec(), _c.back().vec());
    _abs_c.push_back(make_vector(p));
    VecCopy(_c.back().vec(), _abs_c.back().vec());
    VecAbs(_abs_c.back().vec());
    // l_e: -J 1_e off the Dirichlet dofs (lifting of a unit potential), 1 on e
    _l.push_back(make_vector(p));
    Vec l = _l.back().vec();
    MatMult(J, ones.vec(), l);
    VecScale(l, -1.0);
    set_owned(l, p.bc_dofs(), 0.0);
    set_owned(l, p.electrodes[e].dofs, 1.0);
    _z.push_back(make_vector(p));
  }
  _rho.assign(_index.size(), 0.0);
  _scale.assign(_index.size(), 0.0);
  _M.assign(_index.size() * _index.size(), 0.0);
}

void FloatingPotentials::factorised(KSP ksp, const std::function<void()>& check)
{
  if (empty())
    return;
  ScopedTimer timer(stats, "floating electrodes");
  const std::size_t n = _index.size();
  for (std::size_t f = 0; f < n; ++f)
  {
    KSPSolve(ksp, _l[f].vec(), _z[f].vec());
    check();
  }
  for (std::size_t e = 0; e < n; ++e)
    for (std::size_t f = 0; f < n; ++f)
      VecDot(_c[e].vec(), _z[f].vec(), &_M[e * n + f]);
}

void FloatingPotentials::residual(std::span<const double> r, std::span<const double> x)
{
  if (empty())
    return;
  ScopedTimer timer(stats, "floating electrodes");
  const auto charges = _p.reaction_charges(r);
  const auto target = _p.target_charges();
  std::vector<double> size(_index.size(), 0.0); // |c_e| . |x|
  for (std::size_t k = 0; k < _index.size(); ++k)
  {
    const PetscScalar* c;
    VecGetArrayRead(_abs_c[k].vec(), &c);
    for (std::size_t i = 0; i < x.size(); ++i)
      size[k] += c[i] * std::abs(x[i]);
    VecRestoreArrayRead(_abs_c[k].vec(), &c);
  }
  MPI_Allreduce(MPI_IN_PLACE, size.data(), size.size(), MPI_DOUBLE, MPI_SUM, _p.comm);
  for (std::size_t k = 0; k < _index.size(); ++k)
  {
    const std::size_t e = _index[k];
    _rho[k] = charges[e] - target[e];
    _scale[k] = size[k] + std::abs(target[e]);
  }
}

void FloatingPotentials::update(Vec dx0, Vec x)
{
  VecAXPY(x, -1.0, dx0);
  if (empty())
    return;
  ScopedTimer timer(stats, "floating electrodes");
  const std::size_t n = _index.size();
  std::vector<double> rhs(n);
  for (std::size_t e = 0; e < n; ++e)
  {
    double c_dx0;
    VecDot(_c[e].vec(), dx0, &c_dx0);
    rhs[e] = _rho[e] + c_dx0;
  }
  const std::vector<double> dV = solve_dense(_M, rhs);
  for (std::size_t f = 0; f < n; ++f)
  {
    VecAXPY(x, dV[f], _z[f].vec());
    // exactly uniform, whatever the round-off of the solve
    Electrode& el = _p.electrodes[_index[f]];
    _p.hold(el, el.held + dV[f]);
    set_owned(x, el.dofs, el.held);
  }
}

double FloatingPotentials::relative_residual() const
{
  double out = 0.0;
  for (std::size_t k = 0; k < _rho.size(); ++k)
    out = std::max(out, _scale[k] > 0.0 ? std::abs(_rho[k]) / _scale[k]
                                        : (_rho[k] == 0.0 ? 0.0 : INFINITY));
  return out;
}

double FloatingPotentials::residual_norm() const
{
  double out = 0.0;
  for (double r : _rho)
    out = std::max(out, std::abs(r));
  return out;
}
} // namespace piezocontact
