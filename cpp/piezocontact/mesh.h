// Meshes and named boundaries: the built-in unit square, a gmsh script of meshes/ run at mesh.size, or an
// XDMF mesh with facet tags and a NAME.boundaries.json sidecar. The facet
// tag of a named boundary becomes 1 + its index in sorted name order.
#pragma once

#include "config.h"
#include "model.h"

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>

namespace piezocontact
{

/// A mesh made by a tool outside the library: a gmsh script of meshes/ run
/// at `size` (type "gmsh"), or a .msh file converted (type "msh"). The tool
/// writes `target` (NAME.xdmf and its NAME.boundaries.json) and its output
/// to `log`.
struct MeshConversion
{
  std::string type;
  std::filesystem::path input, target, log;
  double size = 0.0;
};

/// Runs the tool of a MeshConversion; returns its exit status (0: done).
/// The front ends give it (they can run an interpreter; the library
/// does not).
using MeshConverter = std::function<int(const MeshConversion&)>;

/// The XDMF file to read (empty for the built-in meshes); for "gmsh" and
/// "msh", `convert` makes it on rank 0 (refused without one). Errors are
/// thrown on every rank.
std::optional<std::filesystem::path>
prepare_mesh(const json& cfg, const std::string& source, const std::filesystem::path& out_dir,
             MPI_Comm comm, const MeshConverter& convert);

/// Every boundary of the config is one of the mesh's named boundaries
/// (facet groups), and with "regions" the config names exactly the mesh's
/// regions (named cell groups). Throws ConfigError.
void check_names(const json& cfg, const NamedMesh& mesh, const std::string& source);

NamedMesh build_mesh(const json& cfg, MPI_Comm comm,
                     const std::optional<std::filesystem::path>& mesh_file,
                     const std::string& source);

/// A mesh given as dolfinx objects (the Python API): its facet tags and
/// cell tags (either may be null) named by `boundaries` and `regions`
/// ({name: tag value}), renumbered as a file's are, so that the same mesh
/// read from XDMF and given in memory is the same NamedMesh. No regions:
/// one region "body". Throws ConfigError naming `source` and the key
/// (boundary_names, region_names, facet_tags, cell_tags, mesh). Collective.
NamedMesh name_mesh(std::shared_ptr<compat::Mesh> mesh,
                    std::shared_ptr<const compat::MeshTags> facet_tags,
                    std::shared_ptr<const compat::MeshTags> cell_tags,
                    const std::map<std::string, int>& boundaries,
                    const std::map<std::string, int>& regions, const std::string& source);
} // namespace piezocontact
