// Meshes and named boundaries: the built-in unit square, a gmsh script of meshes/ run at mesh.size, or an
// XDMF mesh with facet tags and a NAME.boundaries.json sidecar. The facet
// tag of a named boundary becomes 1 + its index in sorted name order.
#pragma once

#include "config.h"
#include "model.h"

#include <filesystem>
#include <map>
#include <memory>
#include <optional>

namespace piezocontact
{

/// The XDMF file to read (empty for the built-in square); for gmsh, run the
/// geometry script on rank 0. Errors are thrown on every rank.
std::optional<std::filesystem::path>
prepare_mesh(const json& cfg, const std::string& source,
             const std::filesystem::path& out_dir, MPI_Comm comm);

/// Every boundary of the config is one of the mesh's named boundaries
/// (facet groups), and with "regions" the config names exactly the mesh's
/// regions (named cell groups). Throws ConfigError.
void check_names(const json& cfg, const NamedMesh& mesh, const std::string& source);

NamedMesh build_mesh(const json& cfg, MPI_Comm comm,
                     const std::optional<std::filesystem::path>& mesh_file,
                     const std::string& source);
} // namespace piezocontact
