// Materials: presets (config/materials.json, crystal frame, poling axis 3)
// rotated into the 3D frame by a poling direction or Euler angles, and in 2D
// reduced by the formulation (plane strain, plane stress, axisymmetric);
// explicit tensors pass through, or are reduced like presets when given in
// their 3D shape on a 2D mesh. What a run solves with is always the
// resolved Voigt tensors in the mesh frame (docs/formulations.md).
#pragma once

#include "config.h"

#include <array>
#include <string>
#include <vector>

namespace piezocontact
{
using Matrix = std::vector<std::vector<double>>;

/// A material's tensors in Voigt form (order [xx, yy, zz, yz, xz, xy] in
/// 3D, [xx, yy, xy] in plane strain and stress, [xx, yy, zz, xy] in
/// axisymmetry; engineering shears in the strain)
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
/// x, y (fields) of 3D tensors (eps_z* = 0, E_z = 0)
MaterialTensors plane_strain(const MaterialTensors& m);

/// The plane-stress reduction: the out-of-plane stresses (zz, yz, xz)
/// condensed out of the 3D law with E_z = 0. Throws std::invalid_argument
/// if the out-of-plane elastic block is singular.
MaterialTensors plane_stress(const MaterialTensors& m);

/// The axisymmetric reduction (x = r, y the axis, z the hoop direction):
/// rows and columns xx, yy, zz, xy and fields x, y. Throws
/// std::invalid_argument if the material couples them to torsion.
MaterialTensors axisymmetric(const MaterialTensors& m);

/// The reduction of a 2D formulation ("plane_strain", "plane_stress",
/// "axisymmetric")
MaterialTensors reduced(const MaterialTensors& m, const std::string& formulation);

/// A validated material spec (preset or explicit) resolved in d dimensions
/// and a formulation: {elastic, viscosity, piezoelectric, permittivity,
/// resolved_from: spec}. Throws std::invalid_argument (a reduction's).
json resolve_material(const json& spec, int d, const std::string& formulation);

/// The config with every material ("material" or each of "regions")
/// resolved in d dimensions and the config's formulation. Throws
/// ConfigError naming the material.
json resolve_materials(json cfg, int d, const std::string& source);
} // namespace piezocontact
