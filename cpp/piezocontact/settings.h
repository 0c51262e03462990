// Typed settings of a run: what the JSON config (config.h) turns into at
// the edge. Nothing below the config layer reads JSON input.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace piezocontact
{
/// Dirichlet data on one named boundary; "exact" takes the model's exact
/// field at the current time
struct DirichletSettings
{
  std::string boundary;
  /// one value per component; an empty one is free (rollers, symmetry planes)
  std::optional<std::vector<std::optional<double>>> displacement;
  bool displacement_exact = false;
  std::optional<double> potential;
  bool potential_exact = false;
};

struct NewtonSettings
{
  double rtol = 1e-10, atol = 1e-12;
  int max_iterations = 25;
  int max_step_halvings = 4;
};

struct OutputSettings
{
  bool xdmf = true;
  std::string nodal = "final"; ///< "none", "final" or "all" steps as .npy
};

struct RunSettings
{
  double T = 1.0;
  int steps = 1;
  NewtonSettings newton;
  bool reuse_factorisation = true;
  /// PETSc options of the linear solver, without our prefix
  std::vector<std::pair<std::string, std::string>> petsc_options;
  std::vector<std::array<double, 3>> probes;
  OutputSettings output;
  std::vector<DirichletSettings> dirichlet;
};
} // namespace piezocontact
