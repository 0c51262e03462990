#include "cell_geometry.h"

#include <algorithm>

namespace piezocontact
{
std::vector<std::array<double, 3>> cell_vertices(const compat::Mesh& mesh, std::int32_t c)
{
  const auto x = mesh.geometry().x();
  const auto nodes = compat::cell_nodes(mesh, c);
  std::vector<std::array<double, 3>> out(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    std::copy_n(x.data() + 3 * nodes[i], 3, out[i].begin());
  return out;
}

namespace
{
double det(int n, const double m[3][3])
{
  return n == 2 ? m[0][0] * m[1][1] - m[0][1] * m[1][0]
                : m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                      - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                      + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}
} // namespace

// Solve sum_i l_i (v_i - v_0) = x - v_0 by Cramer's rule, l_0 = 1 - sum l_i
std::vector<double> barycentric(std::span<const double> x,
                                const std::vector<std::array<double, 3>>& v)
{
  const int n = v.size() - 1;
  double a[3][3] = {}, b[3] = {};
  for (int r = 0; r < n; ++r)
  {
    for (int c = 0; c < n; ++c)
      a[r][c] = v[c + 1][r] - v[0][r];
    b[r] = x[r] - v[0][r];
  }
  const double D = det(n, a);
  std::vector<double> l(n + 1, 1.0);
  for (int c = 0; c < n; ++c)
  {
    double m[3][3];
    std::copy(&a[0][0], &a[0][0] + 9, &m[0][0]);
    for (int r = 0; r < n; ++r)
      m[r][c] = b[r];
    l[c + 1] = det(n, m) / D;
    l[0] -= l[c + 1];
  }
  return l;
}
} // namespace piezocontact
