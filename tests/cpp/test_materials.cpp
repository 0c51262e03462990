// Material rotation and reduction, against what the transversely isotropic
// constants of a preset must become (the tensors in config/materials.json,
// read independently here).
#include <piezocontact/materials.h>

#include <cmath>
#include <fstream>
#include <gtest/gtest.h>

namespace
{
using namespace piezocontact;

json pzt5h()
{
  std::ifstream in(PIEZO_SOURCE_DIR "/config/materials.json");
  return json::parse(in)["presets"]["PZT-5H"];
}

double rel(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

/// Every entry of a and b agrees to 1e-14 of the largest
void expect_same(const Matrix& a, const Matrix& b)
{
  double largest = 0.0;
  for (const auto& row : b)
    for (double x : row)
      largest = std::max(largest, std::abs(x));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < a[i].size(); ++j)
      EXPECT_NEAR(a[i][j], b[i][j], 1e-13 * largest) << "entry " << i << ", " << j;
}
} // namespace

TEST(Materials, PoledAlongZIsTheCrystalFrame)
{
  const auto m = preset_tensors("PZT-5H", 0.0);
  const auto r = rotate(m, poling_rotation({0, 0, 1}));
  expect_same(r.elastic, m.elastic);
  expect_same(r.piezoelectric, m.piezoelectric);
  expect_same(r.permittivity, m.permittivity);
}

// Poled along x: the crystal's axis 3 is x, so C_xxxx = c33, e_x,xx = e33,
// e_x,yy = e_x,zz = e31, e_y,xy = e15 (shear in the plane containing the
// poling axis), eps_xx = eps33
TEST(Materials, PoledAlongXMovesAxisThreeToX)
{
  const json p = pzt5h();
  const auto r = rotate(preset_tensors("PZT-5H", 0.0), poling_rotation({1, 0, 0}));
  EXPECT_LT(rel(r.elastic[0][0], p["c33"].get<double>() * 1e9), 1e-14);
  EXPECT_LT(rel(r.elastic[1][1], p["c11"].get<double>() * 1e9), 1e-14);
  EXPECT_LT(rel(r.elastic[0][1], p["c13"].get<double>() * 1e9), 1e-14);
  EXPECT_LT(rel(r.piezoelectric[0][0], p["e33"].get<double>()), 1e-14);
  EXPECT_LT(rel(r.piezoelectric[0][1], p["e31"].get<double>()), 1e-14);
  EXPECT_LT(rel(r.piezoelectric[0][2], p["e31"].get<double>()), 1e-14);
  EXPECT_LT(rel(r.piezoelectric[1][5], p["e15"].get<double>()), 1e-14);
  EXPECT_LT(rel(r.permittivity[0][0], p["eps33"].get<double>() * p["eps0"].get<double>()),
            1e-14);
  // shears (Voigt yz, xz, xy = 3, 4, 5): those containing x, the poling
  // axis, are c44; yz, the crystal's 12 plane, is c66 = (c11 - c12) / 2
  const double c44 = p["c44"].get<double>() * 1e9,
               c66 = (p["c11"].get<double>() - p["c12"].get<double>()) / 2 * 1e9;
  EXPECT_LT(rel(r.elastic[4][4], c44), 1e-14);
  EXPECT_LT(rel(r.elastic[5][5], c44), 1e-14);
  EXPECT_LT(rel(r.elastic[3][3], c66), 1e-14);
  // e15 couples D_y to the xy shear and D_z to the xz shear
  EXPECT_LT(rel(r.piezoelectric[2][4], p["e15"].get<double>()), 1e-14);
}

// Reversing the poling reverses e (odd order) and leaves C and eps (even)
TEST(Materials, ReversedPolingFlipsOnlyThePiezoelectricTensor)
{
  const auto m = preset_tensors("PZT-5H", 0.0);
  const auto r = rotate(m, poling_rotation({0, 0, -1}));
  expect_same(r.elastic, m.elastic);
  expect_same(r.permittivity, m.permittivity);
  Matrix minus = m.piezoelectric;
  for (auto& row : minus)
    for (double& x : row)
      x = -x;
  expect_same(r.piezoelectric, minus);
}

// Full-index rotation: R then R^T gives the tensors back, for an arbitrary R
TEST(Materials, EulerRotationAndItsInverseComposeToIdentity)
{
  const auto m = preset_tensors("PZT-5H", 0.1);
  const auto R = euler_rotation({30, 50, 70});
  auto Rt = R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      Rt[i][j] = R[j][i];
  const auto back = rotate(rotate(m, R), Rt);
  expect_same(back.elastic, m.elastic);
  expect_same(back.viscosity, m.viscosity);
  expect_same(back.piezoelectric, m.piezoelectric);
  expect_same(back.permittivity, m.permittivity);
}

// Plane strain keeps rows/columns xx, yy, xy (Voigt 0, 1, 5) and x, y
TEST(Materials, PlaneStrainKeepsTheInPlaneEntries)
{
  const auto m = rotate(preset_tensors("PZT-5H", 0.1), euler_rotation({10, 20, 30}));
  const auto p = plane_strain(m);
  const int s[3] = {0, 1, 5};
  ASSERT_EQ(p.elastic.size(), 3u);
  ASSERT_EQ(p.piezoelectric.size(), 2u);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
    {
      EXPECT_EQ(p.elastic[i][j], m.elastic[s[i]][s[j]]);
      EXPECT_EQ(p.viscosity[i][j], m.viscosity[s[i]][s[j]]);
    }
  for (int k = 0; k < 2; ++k)
  {
    for (int j = 0; j < 3; ++j)
      EXPECT_EQ(p.piezoelectric[k][j], m.piezoelectric[k][s[j]]);
    for (int l = 0; l < 2; ++l)
      EXPECT_EQ(p.permittivity[k][l], m.permittivity[k][l]);
  }
}

// The resolved 2D material of a preset poled along y, as a run solves with it
TEST(Materials, ResolvedInTwoDimensionsPoledAlongY)
{
  const json p = pzt5h();
  const json r = resolve_material({{"preset", "PZT-5H"}, {"poling", {0, 1}}}, 2, "plane_strain");
  EXPECT_LT(rel(r["elastic"][1][1].get<double>(), p["c33"].get<double>() * 1e9), 1e-14);
  EXPECT_LT(rel(r["elastic"][0][0].get<double>(), p["c11"].get<double>() * 1e9), 1e-14);
  EXPECT_LT(rel(r["piezoelectric"][1][1].get<double>(), p["e33"].get<double>()), 1e-14);
  EXPECT_LT(rel(r["piezoelectric"][1][0].get<double>(), p["e31"].get<double>()), 1e-14);
  EXPECT_EQ(r["piezoelectric"][0][0].get<double>(), 0.0);
}

// Plane stress of PZT-5H poled along y (crystal 1 = x, 3 = y, 2 out of the
// plane): the classical condensed constants, c11 - c12^2/c11, ...,
// e33 - e31 c13/c11, eps33 + e31^2/c11 (sigma_zz = 0, E_z = 0)
TEST(Materials, PlaneStressCondensesTheOutOfPlaneStress)
{
  const json p = pzt5h();
  const double GPa = 1e9, c11 = p["c11"].get<double>() * GPa, c12 = p["c12"].get<double>() * GPa,
               c13 = p["c13"].get<double>() * GPa, c33 = p["c33"].get<double>() * GPa,
               c44 = p["c44"].get<double>() * GPa, e31 = p["e31"], e33 = p["e33"],
               e15 = p["e15"], eps0 = p["eps0"], eps11 = p["eps11"].get<double>() * eps0,
               eps33 = p["eps33"].get<double>() * eps0;
  const auto m = plane_stress(rotate(preset_tensors("PZT-5H", 0.1), poling_rotation({0, 1})));
  expect_same(m.elastic, {{c11 - c12 * c12 / c11, c13 - c12 * c13 / c11, 0},
                          {c13 - c12 * c13 / c11, c33 - c13 * c13 / c11, 0},
                          {0, 0, c44}});
  expect_same(m.piezoelectric, {{0, 0, e15}, {e31 - e31 * c12 / c11, e33 - e31 * c13 / c11, 0}});
  expect_same(m.permittivity, {{eps11, 0}, {0, eps33 + e31 * e31 / c11}});
  // viscosity = 0.1 elastic condenses to 0.1 x the condensed elasticity
  Matrix tau_B = m.elastic;
  for (auto& row : tau_B)
    for (double& x : row)
      x *= 0.1;
  expect_same(m.viscosity, tau_B);
}

// An isotropic solid in plane stress: E / (1 - nu^2) [[1, nu, 0], [nu, 1, 0],
// [0, 0, (1 - nu) / 2]], from its explicit 3D tensor on a 2D mesh
TEST(Materials, PlaneStressOfAnIsotropicSolidIsTheTextbookOne)
{
  const double E = 70e9, nu = 0.3, l = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  Matrix C(6, std::vector<double>(6, 0.0));
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
      C[i][j] = l + (i == j ? 2 * mu : 0.0);
    C[i + 3][i + 3] = mu;
  }
  const json spec = {{"elastic", C},
                     {"relaxation_time", 0.5},
                     {"piezoelectric", Matrix(3, std::vector<double>(6, 0.0))},
                     {"permittivity", {{1e-11, 0, 0}, {0, 1e-11, 0}, {0, 0, 1e-11}}}};
  const json r = resolve_material(spec, 2, "plane_stress");
  const double k = E / (1 - nu * nu);
  expect_same(r["elastic"].get<Matrix>(), {{k, k * nu, 0}, {k * nu, k, 0}, {0, 0, mu}});
  expect_same(r["viscosity"].get<Matrix>(),
              {{0.5 * k, 0.5 * k * nu, 0}, {0.5 * k * nu, 0.5 * k, 0}, {0, 0, 0.5 * mu}});
  EXPECT_EQ(r["permittivity"].size(), 2u);
}

// Axisymmetric PZT-5H poled along the axis y: strains (r, z, hoop, rz) are
// the crystal's (1, 3, 2, 13)
TEST(Materials, AxisymmetricKeepsRadialAxialHoopAndShear)
{
  const json p = pzt5h();
  const double GPa = 1e9, c11 = p["c11"].get<double>() * GPa, c12 = p["c12"].get<double>() * GPa,
               c13 = p["c13"].get<double>() * GPa, c33 = p["c33"].get<double>() * GPa,
               c44 = p["c44"].get<double>() * GPa, e31 = p["e31"], e33 = p["e33"],
               e15 = p["e15"];
  const auto m = axisymmetric(rotate(preset_tensors("PZT-5H", 0.1), poling_rotation({0, 1})));
  expect_same(m.elastic,
              {{c11, c13, c12, 0}, {c13, c33, c13, 0}, {c12, c13, c11, 0}, {0, 0, 0, c44}});
  expect_same(m.piezoelectric, {{0, 0, 0, e15}, {e31, e33, e31, 0}});
}

// A poling that tilts out of the (r, z) plane drives torsion: refused
TEST(Materials, AxisymmetryRefusesATorsionalMaterial)
{
  const auto m = rotate(preset_tensors("PZT-5H", 0.1), euler_rotation({0, 30, 0}));
  EXPECT_THROW(axisymmetric(m), std::invalid_argument);
  const json spec = {{"preset", "PZT-5H"}, {"euler", {0, 30, 0}}};
  EXPECT_THROW(resolve_material(spec, 2, "axisymmetric"), std::invalid_argument);
  EXPECT_NO_THROW(resolve_material(spec, 2, "plane_stress"));
}
