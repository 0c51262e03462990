// Unit tests of the C++ config reader: the schema rules, --set overrides and
// the wording of errors (the pytest suite checks the Python side says the same).
#include <piezocontact/config.h>
#include <piezocontact/output.h>

#include <filesystem>
#include <fstream>
#include <cstring>
#include <gtest/gtest.h>

namespace
{
const std::string square = PIEZO_SOURCE_DIR "/demos/square.json";

std::string error_of(const std::vector<std::string>& overrides)
{
  try
  {
    piezocontact::load_config(square, overrides);
  }
  catch (const piezocontact::ConfigError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(Config, DefaultsAreFilledAndNumbersAreDoubles)
{
  const auto cfg = piezocontact::load_config(square, {});
  EXPECT_EQ(cfg["solver"]["newton"]["rtol"].get<double>(), 1e-10);
  EXPECT_EQ(cfg["output"]["nodal"], "final");
  EXPECT_EQ(cfg["loads"]["body_force"], piezocontact::json::array({0.0, 0.0}));
  EXPECT_TRUE(cfg["contact"]["gap"].is_number_float());
}

TEST(Config, OverridesSetNestedValuesAndListItems)
{
  const auto cfg = piezocontact::load_config(
      square, {"mesh.n=64", "time.T=2", "probes.1=[0.25,0.5]",
               "solver.petsc_options.pc_factor_mat_solver_type=superlu_dist"});
  EXPECT_EQ(cfg["mesh"]["n"].get<int>(), 64);
  EXPECT_EQ(cfg["time"]["T"].get<double>(), 2.0);
  EXPECT_EQ(cfg["probes"][1], piezocontact::json::array({0.25, 0.5}));
  EXPECT_EQ(cfg["solver"]["petsc_options"]["pc_factor_mat_solver_type"], "superlu_dist");
}

TEST(Config, ErrorsNameFileKeyAndValue)
{
  EXPECT_EQ(error_of({"time.steps=0"}), square + ": time.steps = 0: must be >= 1");
  EXPECT_EQ(error_of({"time.stpes=1"}),
            square + ": time.stpes: unknown key (did you mean 'time.steps'?)");
  EXPECT_EQ(error_of({"mesh.n=\"four\""}),
            square + ": mesh.n = \"four\": expected an integer");
  EXPECT_EQ(error_of({"output.nodal=some"}),
            square + ": output.nodal = \"some\": expected one of none, final, all");
  EXPECT_EQ(error_of({"boundaries.top={\"traction\": [0, -10], \"contact\": true}"}),
            square + ": boundaries.top: traction and contact are exclusive");
  EXPECT_NE(error_of({"material.viscosity=[[1,0,0],[0,-1,0],[0,0,1]]"})
                .find("viscosity must be positive definite"),
            std::string::npos);
  EXPECT_NE(error_of({"material.elastic=[[1,2,0],[0,1,0],[0,0,1]]"})
                .find("must be symmetric (entry [0][1] = 2 but [1][0] = 0)"),
            std::string::npos);
}

TEST(Config, ClosestKey)
{
  EXPECT_EQ(piezocontact::closest_key("stpes", {"T", "steps"}), "steps");
  EXPECT_EQ(piezocontact::closest_key("materal", {"mesh", "material"}), "material");
  EXPECT_EQ(piezocontact::closest_key("xyz", {"T", "steps"}), "");
}

TEST(Output, NpyHeaderIsAlignedAndDataFollows)
{
  const auto path = std::filesystem::temp_directory_path() / "piezo_test.npy";
  piezocontact::write_npy(path, {1.0, 2.0, 3.0, 4.0, 5.0, 6.0}, 3, 2);
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.substr(0, 6), "\x93NUMPY");
  const std::size_t header = static_cast<unsigned char>(bytes[8])
                             + 256 * static_cast<unsigned char>(bytes[9]);
  EXPECT_EQ((10 + header) % 64, 0u);
  EXPECT_NE(bytes.find("'shape': (3, 2)"), std::string::npos);
  ASSERT_EQ(bytes.size(), 10 + header + 6 * sizeof(double));
  double last;
  std::memcpy(&last, bytes.data() + bytes.size() - sizeof(double), sizeof(double));
  EXPECT_EQ(last, 6.0);
}
