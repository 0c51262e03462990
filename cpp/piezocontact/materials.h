// Materials: presets (config/materials.json, crystal frame, poling axis 3)
// rotated into the mesh frame by a poling direction or Euler angles, and
// reduced to plane strain in 2D; explicit tensors pass through. What a run
// solves with is always the resolved Voigt tensors in the mesh frame.
#pragma once

#include "config.h"

#include <array>
#include <string>
#include <vector>

namespace piezocontact
{
using Matrix = std::vector<std::vector<double>>;

/// A material's tensors in Voigt form (order [xx, yy, zz, yz, xz, xy] in
/// 3D, [xx, yy, xy] in 2D, engineering shears in the strain)
struct MaterialTensors
{
  Matrix elastic, viscosity, piezoelectric, permittivity;
};

/// Rotation whose columns are the crystal axes 1, 2, 3 in the mesh frame:
/// axis 3 along `poling` (2 or 3 components; the others complete a
/// right-handed frame: exact for materials isotropic about axis 3)
std::array<std::array<double, 3>, 3> poling_rotation(const std::vector<double>& poling);

/// Rotation of Bunge Euler angles (degrees): R = Rz(phi1) Rx(Phi) Rz(phi2)
std::array<std::array<double, 3>, 3> euler_rotation(const std::vector<double>& angles);

/// A preset's 3D tensors in the crystal frame, viscosity = tau * elastic
MaterialTensors preset_tensors(const std::string& name, double tau);

/// Tensors in the frame whose axes are R's columns seen from the mesh:
/// T'_{ij..} = R_ia R_jb ... T_{ab..} (full-index rotation, not entry by entry)
MaterialTensors rotate(const MaterialTensors& m, const std::array<std::array<double, 3>, 3>& R);

/// The plane-strain reduction: rows and columns xx, yy, xy (strains) and
/// x, y (fields) of 3D tensors
MaterialTensors plane_strain(const MaterialTensors& m);

/// A validated material spec (preset or explicit) resolved in d dimensions:
/// {elastic, viscosity, piezoelectric, permittivity, resolved_from: spec}
json resolve_material(const json& spec, int d);

/// The config with every material ("material" or each of "regions")
/// resolved in d dimensions
json resolve_materials(json cfg, int d);
} // namespace piezocontact
