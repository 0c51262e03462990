#include "materials.h"
#include "schema.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

namespace piezocontact
{
namespace
{
using Rotation = std::array<std::array<double, 3>, 3>;

// Voigt index of a pair of 3D axes, and back
int voigt(int i, int j)
{
  constexpr int table[3][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}};
  return table[i][j];
}
constexpr int voigt_pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};

Matrix zeros(std::size_t r, std::size_t c) { return Matrix(r, std::vector<double>(c, 0.0)); }

std::array<double, 3> normalized(std::array<double, 3> v)
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (double& x : v)
    x /= n;
  return v;
}

std::array<double, 3> cross(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Rotation columns(const std::array<double, 3>& a1, const std::array<double, 3>& a2,
                 const std::array<double, 3>& a3)
{
  Rotation R;
  for (int i = 0; i < 3; ++i)
    R[i] = {a1[i], a2[i], a3[i]};
  return R;
}

Rotation product(const Rotation& A, const Rotation& B)
{
  Rotation C{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        C[i][j] += A[i][k] * B[k][j];
  return C;
}

/// x to 15 significant digits: a product of decimal data (8.8 * 8.885e-12)
/// is the decimal number a user would write (7.8188e-11), not its
/// binary neighbour
double decimal(double x)
{
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.15g", x);
  return std::strtod(buf, nullptr);
}

const json& presets()
{
  static const json p = json::parse(material_presets);
  return p;
}
} // namespace

Rotation poling_rotation(const std::vector<double>& poling)
{
  const auto a3 = normalized({poling.at(0), poling.at(1), poling.size() > 2 ? poling[2] : 0.0});
  // complete with the mesh axis least aligned with a3 (the first of equals):
  // for a3 along a mesh axis every entry of R is 0 or +-1, and the rotated
  // presets are exact
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(a3[i]) < std::abs(a3[k]))
      k = i;
  std::array<double, 3> e{};
  e[k] = 1.0;
  const auto a2 = normalized(cross(a3, e));
  const auto a1 = cross(a2, a3);
  return columns(a1, a2, a3);
}

Rotation euler_rotation(const std::vector<double>& angles)
{
  const double c = std::numbers::pi / 180.0;
  auto Rz = [](double a) -> Rotation
  { return {{{std::cos(a), -std::sin(a), 0}, {std::sin(a), std::cos(a), 0}, {0, 0, 1}}}; };
  auto Rx = [](double a) -> Rotation
  { return {{{1, 0, 0}, {0, std::cos(a), -std::sin(a)}, {0, std::sin(a), std::cos(a)}}}; };
  return product(product(Rz(c * angles.at(0)), Rx(c * angles.at(1))), Rz(c * angles.at(2)));
}

MaterialTensors preset_tensors(const std::string& name, double tau)
{
  const json& p = presets()["presets"].at(name);
  auto v = [&p](const char* k) { return p.at(k).get<double>(); };
  const double GPa = 1e9, c11 = v("c11") * GPa, c12 = v("c12") * GPa, c13 = v("c13") * GPa,
               c33 = v("c33") * GPa, c44 = v("c44") * GPa, c66 = (c11 - c12) / 2;
  MaterialTensors m;
  m.elastic = {{c11, c12, c13, 0, 0, 0}, {c12, c11, c13, 0, 0, 0}, {c13, c13, c33, 0, 0, 0},
               {0, 0, 0, c44, 0, 0},     {0, 0, 0, 0, c44, 0},     {0, 0, 0, 0, 0, c66}};
  m.viscosity = m.elastic;
  for (auto& row : m.viscosity)
    for (double& x : row)
      x = decimal(x * tau);
  m.piezoelectric = zeros(3, 6);
  m.piezoelectric[0][4] = m.piezoelectric[1][3] = v("e15"); // D1 <- 2 eps13, D2 <- 2 eps23
  m.piezoelectric[2][0] = m.piezoelectric[2][1] = v("e31");
  m.piezoelectric[2][2] = v("e33");
  m.permittivity = zeros(3, 3);
  m.permittivity[0][0] = m.permittivity[1][1] = decimal(v("eps11") * v("eps0"));
  m.permittivity[2][2] = decimal(v("eps33") * v("eps0"));
  return m;
}

MaterialTensors rotate(const MaterialTensors& m, const Rotation& R)
{
  MaterialTensors out{zeros(6, 6), zeros(6, 6), zeros(3, 6), zeros(3, 3)};
  // a 4th-order tensor in Voigt storage: T'_{ijkl} = R_ia R_jb R_kc R_ld T_abcd
  for (const auto& [in, res] : {std::pair{&m.elastic, &out.elastic},
                                std::pair{&m.viscosity, &out.viscosity}})
    for (int I = 0; I < 6; ++I)
      for (int J = 0; J < 6; ++J)
      {
        const auto [i, j] = voigt_pairs[I];
        const auto [k, l] = voigt_pairs[J];
        double s = 0.0;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            for (int c = 0; c < 3; ++c)
              for (int d = 0; d < 3; ++d)
                s += R[i][a] * R[j][b] * R[k][c] * R[l][d] * (*in)[voigt(a, b)][voigt(c, d)];
        (*res)[I][J] = s;
      }
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 6; ++J)
    {
      const auto [j, k] = voigt_pairs[J];
      double s = 0.0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          for (int c = 0; c < 3; ++c)
            s += R[i][a] * R[j][b] * R[k][c] * m.piezoelectric[a][voigt(b, c)];
      out.piezoelectric[i][J] = s;
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          out.permittivity[i][j] += R[i][a] * R[j][b] * m.permittivity[a][b];
  return out;
}

MaterialTensors plane_strain(const MaterialTensors& m)
{
  const int strains[3] = {0, 1, 5}; // xx, yy, xy
  MaterialTensors out{zeros(3, 3), zeros(3, 3), zeros(2, 3), zeros(2, 2)};
  for (int I = 0; I < 3; ++I)
    for (int J = 0; J < 3; ++J)
    {
      out.elastic[I][J] = m.elastic[strains[I]][strains[J]];
      out.viscosity[I][J] = m.viscosity[strains[I]][strains[J]];
    }
  for (int i = 0; i < 2; ++i)
  {
    for (int J = 0; J < 3; ++J)
      out.piezoelectric[i][J] = m.piezoelectric[i][strains[J]];
    for (int j = 0; j < 2; ++j)
      out.permittivity[i][j] = m.permittivity[i][j];
  }
  return out;
}

json resolve_material(const json& spec, int d)
{
  if (spec.contains("elastic")) // explicit, in the mesh frame
  {
    json out = spec;
    if (!spec.contains("viscosity"))
    {
      // the viscosity it means, and where it came from (a resolved
      // material validates as it is: a resumed run reads it back)
      Matrix A = spec["elastic"].get<Matrix>();
      for (auto& row : A)
        for (double& x : row)
          x = decimal(x * spec["relaxation_time"].get<double>());
      out["viscosity"] = A;
      out.erase("relaxation_time");
      out["resolved_from"] = {{"relaxation_time", spec["relaxation_time"]}};
    }
    return out;
  }
  const double tau
      = spec.value("relaxation_time", presets()["relaxation_time"].get<double>());
  MaterialTensors m = rotate(preset_tensors(spec["preset"], tau),
                             spec.contains("euler")
                                 ? euler_rotation(spec["euler"].get<std::vector<double>>())
                                 : poling_rotation(spec["poling"].get<std::vector<double>>()));
  if (d == 2)
    m = plane_strain(m);
  // exact zeros stay zeros: round-off of the rotation below 1e-14 of the
  // largest entry is cleaned, so that the solved tensors read as the data
  for (Matrix* t : {&m.elastic, &m.viscosity, &m.piezoelectric, &m.permittivity})
  {
    double largest = 0.0;
    for (const auto& row : *t)
      for (double x : row)
        largest = std::max(largest, std::abs(x));
    for (auto& row : *t)
      for (double& x : row)
        if (std::abs(x) < 1e-14 * largest)
          x = 0.0;
  }
  json from = spec;
  from["relaxation_time"] = tau;
  return {{"elastic", m.elastic},         {"viscosity", m.viscosity},
          {"piezoelectric", m.piezoelectric}, {"permittivity", m.permittivity},
          {"resolved_from", from}};
}

json resolve_materials(json cfg, int d)
{
  if (cfg.contains("material"))
    cfg["material"] = resolve_material(cfg["material"], d);
  if (cfg.contains("regions"))
    for (auto& [name, spec] : cfg["regions"].items())
      spec = resolve_material(spec, d);
  return cfg;
}
} // namespace piezocontact
