#include "materials.h"
#include "json_input.h"
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

namespace
{
/// The rows and columns `strains` (Voigt) and `fields` of 3D tensors
MaterialTensors restricted(const MaterialTensors& m, const std::vector<int>& strains,
                           const std::vector<int>& fields)
{
  const std::size_t ns = strains.size(), nf = fields.size();
  MaterialTensors out{zeros(ns, ns), zeros(ns, ns), zeros(nf, ns), zeros(nf, nf)};
  for (std::size_t I = 0; I < ns; ++I)
    for (std::size_t J = 0; J < ns; ++J)
    {
      out.elastic[I][J] = m.elastic[strains[I]][strains[J]];
      out.viscosity[I][J] = m.viscosity[strains[I]][strains[J]];
    }
  for (std::size_t i = 0; i < nf; ++i)
  {
    for (std::size_t J = 0; J < ns; ++J)
      out.piezoelectric[i][J] = m.piezoelectric[fields[i]][strains[J]];
    for (std::size_t j = 0; j < nf; ++j)
      out.permittivity[i][j] = m.permittivity[fields[i]][fields[j]];
  }
  return out;
}

/// The inverse of a small symmetric positive definite matrix (Gauss-Jordan);
/// throws std::invalid_argument if it is singular
Matrix inverse(Matrix a)
{
  const std::size_t n = a.size();
  Matrix inv = zeros(n, n);
  for (std::size_t i = 0; i < n; ++i)
    inv[i][i] = 1.0;
  double largest = 0.0;
  for (const auto& row : a)
    for (double x : row)
      largest = std::max(largest, std::abs(x));
  for (std::size_t c = 0; c < n; ++c)
  {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c]))
        pivot = r;
    if (!(std::abs(a[pivot][c]) > 1e-12 * largest))
      throw std::invalid_argument("singular");
    std::swap(a[c], a[pivot]);
    std::swap(inv[c], inv[pivot]);
    const double p = a[c][c];
    for (std::size_t j = 0; j < n; ++j)
    {
      a[c][j] /= p;
      inv[c][j] /= p;
    }
    for (std::size_t r = 0; r < n; ++r)
      if (r != c and a[r][c] != 0.0)
      {
        const double f = a[r][c];
        for (std::size_t j = 0; j < n; ++j)
        {
          a[r][j] -= f * a[c][j];
          inv[r][j] -= f * inv[c][j];
        }
      }
  }
  return inv;
}

/// Rows `rows` and columns `cols` of a matrix
Matrix block(const Matrix& m, const std::vector<int>& rows, const std::vector<int>& cols)
{
  Matrix out = zeros(rows.size(), cols.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < cols.size(); ++j)
      out[i][j] = m[rows[i]][cols[j]];
  return out;
}

/// a - b c d (the Schur complement's shape)
Matrix minus_product(const Matrix& a, const Matrix& b, const Matrix& c, const Matrix& d)
{
  Matrix out = a;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < a[i].size(); ++j)
      for (std::size_t k = 0; k < c.size(); ++k)
        for (std::size_t l = 0; l < c[k].size(); ++l)
          out[i][j] -= b[i][k] * c[k][l] * d[l][j];
  return out;
}

Matrix transposed(const Matrix& m)
{
  Matrix out = zeros(m.empty() ? 0 : m[0].size(), m.size());
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = 0; j < m[i].size(); ++j)
      out[j][i] = m[i][j];
  return out;
}

/// The largest |entry| of a tensor's rows `rows` and columns `cols`,
/// relative to its largest entry
double coupling(const Matrix& m, const std::vector<int>& rows, const std::vector<int>& cols)
{
  double largest = 0.0, out = 0.0;
  for (const auto& row : m)
    for (double x : row)
      largest = std::max(largest, std::abs(x));
  for (int i : rows)
    for (int j : cols)
      out = std::max(out, std::abs(m[i][j]));
  return largest > 0.0 ? out / largest : 0.0;
}

constexpr int xx = 0, yy = 1, zz = 2, yz = 3, xz = 4, xy = 5;
} // namespace

MaterialTensors plane_strain(const MaterialTensors& m)
{
  return restricted(m, {xx, yy, xy}, {0, 1});
}

MaterialTensors plane_stress(const MaterialTensors& m)
{
  // sigma_Z = 0 solved for eps_Z with E_z = 0: eps_Z = B_ZZ^-1 (e_Z^T E - B_ZI eps_I)
  const std::vector<int> I = {xx, yy, xy}, Z = {zz, yz, xz}, k = {0, 1};
  Matrix B_ZZ_inv;
  try
  {
    B_ZZ_inv = inverse(block(m.elastic, Z, Z));
  }
  catch (const std::invalid_argument&)
  {
    throw std::invalid_argument("its out-of-plane elastic block (zz, yz, xz) is singular: "
                                "no plane stress state");
  }
  const Matrix B_ZI = block(m.elastic, Z, I), e_kZ = block(m.piezoelectric, k, Z);
  MaterialTensors out;
  out.elastic = minus_product(block(m.elastic, I, I), block(m.elastic, I, Z), B_ZZ_inv, B_ZI);
  out.piezoelectric = minus_product(block(m.piezoelectric, k, I), e_kZ, B_ZZ_inv, B_ZI);
  // beta + e_kZ B_ZZ^-1 e_lZ: the condensed strain adds to the permittivity
  const Matrix coupled = minus_product(zeros(2, 2), e_kZ, B_ZZ_inv, transposed(e_kZ));
  out.permittivity = block(m.permittivity, k, k);
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = 0; j < 2; ++j)
      out.permittivity[i][j] -= coupled[i][j];
  // the viscosity by the same condensation: exact when it is proportional
  // to the elasticity (presets, relaxation_time), see docs/formulations.md
  const Matrix A_ZZ = block(m.viscosity, Z, Z);
  if (coupling(m.viscosity, Z, Z) == 0.0)
    out.viscosity = block(m.viscosity, I, I); // no viscosity out of the plane
  else
    out.viscosity = minus_product(block(m.viscosity, I, I), block(m.viscosity, I, Z),
                                  inverse(A_ZZ), block(m.viscosity, Z, I));
  return out;
}

MaterialTensors axisymmetric(const MaterialTensors& m)
{
  // x = r, y the axis, z the hoop direction: without torsion the shears yz
  // (axis-hoop) and xz (r-hoop) vanish, and must not be driven by the rest
  const std::vector<int> strains = {xx, yy, zz, xy}, torsion = {yz, xz};
  const double c = std::max({coupling(m.elastic, strains, torsion),
                             coupling(m.viscosity, strains, torsion),
                             coupling(m.piezoelectric, {0, 1}, torsion)});
  if (c > 1e-12)
    throw std::invalid_argument(
        "it couples the axisymmetric strains or fields to torsion (shears yz, xz: relative "
        "size " + std::to_string(c) + "); axisymmetry needs its poling along x (r) or y (the "
        "axis)");
  return restricted(m, strains, {0, 1});
}

MaterialTensors reduced(const MaterialTensors& m, const std::string& formulation)
{
  if (formulation == "plane_stress")
    return plane_stress(m);
  if (formulation == "axisymmetric")
    return axisymmetric(m);
  return plane_strain(m);
}

namespace
{
/// Round-off of a rotation or a condensation below 1e-14 of a tensor's
/// largest entry is cleaned: exact zeros stay zeros, and the solved
/// tensors read as the data
void clean(MaterialTensors& m)
{
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
}

/// The resolved material: its tensors, its density if it has one (given,
/// or its preset's), and what it was resolved from
json tensors_json(const MaterialTensors& m, const json& from, const json& density)
{
  json out = {{"elastic", m.elastic},
              {"viscosity", m.viscosity},
              {"piezoelectric", m.piezoelectric},
              {"permittivity", m.permittivity}};
  if (!density.is_null())
    out["density"] = density;
  if (!from.is_null())
    out["resolved_from"] = from;
  return out;
}

/// The viscosity an explicit material means: given, or relaxation_time x elastic
Matrix explicit_viscosity(const json& spec)
{
  if (spec.contains("viscosity"))
    return spec["viscosity"].get<Matrix>();
  Matrix A = spec["elastic"].get<Matrix>();
  for (auto& row : A)
    for (double& x : row)
      x = decimal(x * spec["relaxation_time"].get<double>());
  return A;
}
} // namespace

json resolve_material(const json& spec, int d, const std::string& formulation)
{
  if (spec.contains("elastic")) // explicit, in the mesh frame
  {
    const json from = spec.contains("viscosity")
                          ? json(nullptr)
                          : json{{"relaxation_time", spec["relaxation_time"]}};
    if (d == 2 and spec["elastic"].size() == 6) // the 3D tensors: reduced like a preset's
    {
      MaterialTensors m{spec["elastic"].get<Matrix>(), explicit_viscosity(spec),
                        spec["piezoelectric"].get<Matrix>(), spec["permittivity"].get<Matrix>()};
      m = reduced(m, formulation);
      clean(m);
      return tensors_json(m, from, spec.value("density", json()));
    }
    // already in the formulation's shape: as given (a resolved material
    // validates as it is: a resumed run reads it back)
    json out = spec;
    if (!spec.contains("viscosity"))
    {
      out["viscosity"] = explicit_viscosity(spec);
      out.erase("relaxation_time");
      out["resolved_from"] = from;
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
    m = reduced(m, formulation);
  clean(m);
  json from = spec;
  from["relaxation_time"] = tau;
  from.erase("density");
  const json& preset = presets()["presets"][spec["preset"].get<std::string>()];
  return tensors_json(m, from, spec.value("density", preset["density"]));
}

json resolve_materials(json cfg, int d, const std::string& source)
{
  const std::string formulation = d == 2 ? cfg["formulation"].get<std::string>() : "";
  const auto resolve = [&](json& spec, const std::string& path)
  {
    try
    {
      spec = resolve_material(spec, d, formulation);
    }
    catch (const std::invalid_argument& e)
    {
      throw ConfigError(printable(source, 200) + ": " + path + ": " + formulation + ": "
                        + e.what());
    }
  };
  if (cfg.contains("material"))
    resolve(cfg["material"], "material");
  if (cfg.contains("regions"))
    for (auto& [name, spec] : cfg["regions"].items())
      resolve(spec, "regions." + name);
  return cfg;
}
} // namespace piezocontact
