#include "mesh.h"
#include "json_input.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <dolfinx/io/XDMFFile.h>
#include <fstream>
#include <set>
#include <sstream>

namespace piezocontact
{
using namespace dolfinx;
namespace
{
// Built-in meshes: boundary name -> (axis, which end: 0 at 0, 1 at L)
const std::map<std::string, std::pair<int, int>> box_sides
    = {{"left", {0, 0}}, {"right", {0, 1}}, {"bottom", {1, 0}},
       {"top", {1, 1}},  {"back", {2, 0}},  {"front", {2, 1}}};

/// The one region of a mesh without named cell groups
constexpr const char* whole_body = "body";

std::filesystem::path resolve(const std::string& value, const std::string& source)
{
  std::filesystem::path p(value);
  return p.is_absolute() ? p
                         : std::filesystem::absolute(source).parent_path() / p;
}

mesh::DiagonalType diagonal_type(const std::string& name)
{
  const std::map<std::string, mesh::DiagonalType> types
      = {{"right", mesh::DiagonalType::right},
         {"left", mesh::DiagonalType::left},
         {"crossed", mesh::DiagonalType::crossed},
         {"left_right", mesh::DiagonalType::left_right},
         {"right_left", mesh::DiagonalType::right_left}};
  return types.at(name);
}

std::shared_ptr<compat::MeshTags>
make_tags(std::shared_ptr<compat::Mesh> m, int dim,
          std::vector<std::pair<std::int32_t, std::int32_t>> tagged)
{
  std::sort(tagged.begin(), tagged.end()); // MeshTags needs sorted indices
  std::vector<std::int32_t> indices, values;
  for (auto [f, v] : tagged)
  {
    indices.push_back(f);
    values.push_back(v);
  }
  return compat::make_meshtags(m, dim, std::move(indices), std::move(values));
}

/// Every cell (owned and ghost) in one region
void one_region(NamedMesh& out)
{
  const int tdim = compat::topology(*out.mesh).dim();
  const auto cells = compat::topology(*out.mesh).index_map(tdim);
  std::vector<std::pair<std::int32_t, std::int32_t>> all;
  for (std::int32_t c = 0; c < cells->size_local() + cells->num_ghosts(); ++c)
    all.emplace_back(c, 1);
  out.cell_tags = make_tags(out.mesh, tdim, std::move(all));
  out.region_of = {{whole_body, 1}};
}

/// Name the sides of an axis-aligned box [0, L]: facet tags 1, 2, ... in
/// sorted name order
void name_sides(NamedMesh& out, const std::array<double, 3>& L)
{
  const int d = out.mesh->geometry().dim();
  std::map<std::string, std::pair<int, int>> sides;
  for (const auto& [name, side] : box_sides)
    if (side.first < d)
      sides[name] = side;
  std::vector<std::pair<std::int32_t, std::int32_t>> tagged;
  int slot = 0;
  for (const auto& [name, side] : sides) // sorted names
  {
    const int axis = side.first;
    const double c = side.second * L[axis];
    const auto facets = compat::locate_boundary_facets(
        *out.mesh, [axis, c](double x, double y, double z)
        {
          const double xi = axis == 0 ? x : axis == 1 ? y : z;
          return std::abs(xi - c) <= 1e-8 + 1e-5 * std::abs(c); // as numpy.isclose
        });
    out.tag_of[name] = ++slot;
    for (auto f : facets)
      tagged.emplace_back(f, slot);
  }
  out.facet_tags = make_tags(out.mesh, d - 1, std::move(tagged));
  one_region(out);
}

NamedMesh unit_square(const json& cfg, MPI_Comm comm)
{
  NamedMesh out;
  const std::size_t n = cfg["mesh"]["n"].get<std::size_t>();
  out.mesh = std::make_shared<compat::Mesh>(
      compat::create_rectangle(comm, {{{0.0, 0.0}, {1.0, 1.0}}}, {n, n},
                               diagonal_type(cfg["mesh"].value("diagonal", std::string("right")))));
  name_sides(out, {1.0, 1.0, 0.0});
  return out;
}

NamedMesh box(const json& cfg, MPI_Comm comm)
{
  NamedMesh out;
  const auto n = cfg["mesh"]["n"].get<std::array<std::size_t, 3>>();
  const auto L = cfg["mesh"]["size"].get<std::array<double, 3>>();
  out.mesh = std::make_shared<compat::Mesh>(compat::create_box(comm, {{{0.0, 0.0, 0.0}, L}}, n));
  name_sides(out, L);
  return out;
}

/// A file's tags of named groups ({name: file tag}) renumbered 1, 2, ...
/// in sorted name order (slot_of: name -> new tag); untagged groups dropped
std::shared_ptr<compat::MeshTags>
renumbered(std::shared_ptr<compat::Mesh> m, int dim, const json& names,
           const std::vector<std::int32_t>& indices, const std::vector<std::int32_t>& values,
           std::map<std::string, int>& slot_of)
{
  std::map<std::string, int> sorted;
  for (const auto& [name, tag] : names.items())
    sorted[name] = tag.get<int>();
  std::map<int, int> slot_of_file_tag;
  int slot = 0;
  for (const auto& [name, tag] : sorted)
  {
    slot_of[name] = ++slot;
    slot_of_file_tag[tag] = slot;
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> tagged;
  for (std::size_t i = 0; i < indices.size(); ++i)
    if (auto it = slot_of_file_tag.find(values[i]); it != slot_of_file_tag.end())
      tagged.emplace_back(indices[i], it->second);
  return make_tags(m, dim, std::move(tagged));
}

NamedMesh read_xdmf(const std::filesystem::path& file, MPI_Comm comm,
                    const std::string& source)
{
  auto sidecar = file;
  sidecar.replace_extension(".boundaries.json");
  json names, regions;
  try
  {
    const json names_file = read_json_file(sidecar);
    names = names_file.at("boundaries");
    regions = names_file.value("regions", json());
    for (const auto& [key, group] : {std::pair{"boundaries", &names}, std::pair{"regions", &regions}})
    {
      if (group->is_null() and std::string(key) == "regions")
        continue;
      if (!group->is_object())
        throw std::runtime_error(std::string("\"") + key + "\" is not an object");
      for (const auto& [name, tag] : group->items())
        if (!tag.is_number_integer() or tag.get<double>() < 1 or tag.get<double>() > 1e9)
          throw std::runtime_error(std::string(key) + "." + printable(name) + " = "
                                   + printable(tag) + ": expected a positive integer (a tag)");
    }
  }
  catch (const std::exception& e)
  {
    throw ConfigError(source + ": mesh: cannot read the boundary names of "
                      + file.string() + " from " + sidecar.string() + ": " + printable(e.what(), 300));
  }
  NamedMesh out;
  std::vector<std::int32_t> tag_indices, tag_values, cell_indices, cell_values;
  try
  {
    io::XDMFFile f(comm, file, "r");
    const auto [cell, degree] = f.read_cell_type("mesh");
    if ((cell != mesh::CellType::triangle and cell != mesh::CellType::tetrahedron)
        or degree != 1)
      throw std::runtime_error("cells of type " + mesh::to_string(cell) + " and degree "
                               + std::to_string(degree)
                               + ": only affine triangles and tetrahedra are supported");
    out.mesh = std::make_shared<compat::Mesh>(compat::read_mesh(f, cell, "mesh"));
    const int tdim = compat::topology(*out.mesh).dim();
    compat::topology_mutable(*out.mesh).create_connectivity(tdim - 1, tdim);
    std::tie(tag_indices, tag_values) = compat::read_meshtags(f, out.mesh, "facets");
    if (!regions.is_null())
      std::tie(cell_indices, cell_values) = compat::read_meshtags(f, out.mesh, "cells");
  }
  catch (const std::exception& e) // every rank reads the same file
  {
    throw ConfigError(source + ": mesh: cannot read a mesh \"mesh\" with facet "
                      "tags \"facets\" from " + file.string() + ": " + e.what());
  }
  const int tdim = compat::topology(*out.mesh).dim();
  out.facet_tags = renumbered(out.mesh, tdim - 1, names, tag_indices, tag_values, out.tag_of);
  if (regions.is_null())
    one_region(out);
  else
    out.cell_tags = renumbered(out.mesh, tdim, regions, cell_indices, cell_values, out.region_of);
  return out;
}
} // namespace

std::optional<std::filesystem::path>
prepare_mesh(const json& cfg, const std::string& source, const std::filesystem::path& out_dir,
             MPI_Comm comm, const MeshConverter& convert)
{
  const json& m = cfg["mesh"];
  const std::string type = m["type"];
  if (type == "unit_square" or type == "box" or type == "dolfinx")
    return std::nullopt;
  const std::string key = type == "gmsh" ? "geometry" : "path";
  const auto path = resolve(m[key].get<std::string>(), source);
  auto target = path;
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  const std::string where = printable(source, 200) + ": mesh." + key + " = " + printable(m[key]);
  if (rank == 0)
  {
    if (!std::filesystem::is_regular_file(path))
      error = where + ": no such file (" + printable(path.string(), 200) + ")";
    else if (type == "gmsh" or type == "msh")
    {
      // the tool writes NAME.xdmf and its sidecar into the output folder
      target = std::filesystem::absolute(out_dir) / "mesh" / (path.stem().string() + ".xdmf");
      const auto log = std::filesystem::absolute(out_dir) / "mesh" / "generate.log";
      int status = 0;
      try // whatever the tool throws, every rank hears of it (bcast_error below)
      {
        std::filesystem::create_directories(log.parent_path());
        if (!convert)
          error = where + ": this program cannot run the mesh tools (piezo-contact and "
                          "python3 -m piezocontact can)";
        else
          status = convert({type, path, target, log, m.value("size", json(0.0)).get<double>()});
      }
      catch (const std::exception& e)
      {
        error = where + ": the mesh tool failed: " + printable(std::string(e.what()), 200);
      }
      if (status != 0)
      {
        std::ifstream in(log);
        std::string line, last = "(no output)";
        while (std::getline(in, line))
          if (!line.empty())
            last = line;
        error = where
                + (type == "gmsh" ? ": mesh generation failed (exit " : ": cannot read it (exit ")
                + std::to_string(status) + "): " + printable(last, 200);
      }
    }
  }
  bcast_error(error, comm);
  std::string t = target.string();
  int len = t.size();
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  t.resize(len);
  MPI_Bcast(t.data(), len, MPI_CHAR, 0, comm);
  return std::filesystem::path(t);
}

namespace
{
std::string names(const std::map<std::string, int>& named)
{
  std::string out;
  for (const auto& [name, _] : named)
    out += (out.empty() ? "" : ", ") + name;
  return out;
}

void check_boundaries(const json& cfg, const NamedMesh& mesh, const std::string& source)
{
  for (const auto& [name, _] : cfg["boundaries"].items())
    if (!mesh.tag_of.contains(name))
      throw ConfigError(printable(source, 200) + ": boundaries." + printable(name, 60)
                        + ": the mesh has no boundary '" + printable(name, 60)
                        + "' (it has: " + printable(names(mesh.tag_of), 200) + ")");
}
} // namespace

void check_names(const json& cfg, const NamedMesh& mesh, const std::string& source)
{
  check_boundaries(cfg, mesh, source);
  if (cfg.contains("manufactured") and mesh.region_of.size() != 1)
    throw ConfigError(printable(source, 200) + ": manufactured: the mesh has "
                      + std::to_string(mesh.region_of.size()) + " regions ("
                      + printable(names(mesh.region_of), 200)
                      + "); a manufactured solution has one material on one region");
  if (!cfg.contains("regions"))
    return;
  const std::string have = names(mesh.region_of);
  for (const auto& [name, _] : cfg["regions"].items())
    if (!mesh.region_of.contains(name))
      throw ConfigError(printable(source, 200) + ": regions." + printable(name, 60)
                        + ": the mesh has no region '" + printable(name, 60)
                        + "' (it has: " + printable(have, 200) + ")");
  for (const auto& [name, _] : mesh.region_of)
    if (!cfg["regions"].contains(name))
      throw ConfigError(printable(source, 200) + ": regions: no material for the mesh's region '"
                        + printable(name, 60) + "'");
}

NamedMesh build_mesh(const json& cfg, MPI_Comm comm,
                     const std::optional<std::filesystem::path>& mesh_file,
                     const std::string& source)
{
  if (mesh_file)
    return read_xdmf(*mesh_file, comm, source);
  if (cfg["mesh"]["type"] == "dolfinx")
    throw ConfigError(printable(source, 200) + ": mesh.type = \"dolfinx\": a mesh given as dolfinx "
                      "objects, which only the Python API takes (piezocontact.Problem)");
  return cfg["mesh"]["type"] == "box" ? box(cfg, comm) : unit_square(cfg, comm);
}

} // namespace piezocontact

namespace piezocontact
{
namespace
{
/// A MeshTags given by a caller: of the entities it names, every index a
/// local entity. Throws ConfigError naming `key`.
void check_tags(const compat::Mesh& mesh, const compat::MeshTags& tags, int dim,
                const std::string& key, const std::string& where)
{
  if (tags.dim() != dim)
    throw ConfigError(where + key + ": tags of entities of dimension " + std::to_string(tags.dim())
                      + ", expected " + std::to_string(dim));
  const auto map = compat::topology(mesh).index_map(dim);
  const std::int32_t count = map ? map->size_local() + map->num_ghosts() : 0;
  const auto indices = tags.indices();
  if (!indices.empty() and (*std::min_element(indices.begin(), indices.end()) < 0
                            or *std::max_element(indices.begin(), indices.end()) >= count))
    throw ConfigError(where + key + ": an index outside the mesh's " + std::to_string(count)
                      + " local entities of dimension " + std::to_string(dim)
                      + " (tags of another mesh?)");
}

/// Every name's tag is a positive value that some entity carries (on some
/// process): a name of no entity is a mistake, not an empty boundary
void check_names_of_tags(const std::map<std::string, int>& names, const compat::MeshTags* tags,
                         const std::string& key, const std::string& where, MPI_Comm comm)
{
  std::vector<int> carried(names.size(), 0);
  if (tags)
  {
    const auto values = tags->values();
    const std::set<std::int32_t> present(values.begin(), values.end());
    std::size_t i = 0;
    for (const auto& [_, tag] : names)
      carried[i++] = present.contains(tag) ? 1 : 0;
  }
  MPI_Allreduce(MPI_IN_PLACE, carried.data(), int(carried.size()), MPI_INT, MPI_MAX, comm);
  std::size_t i = 0;
  for (const auto& [name, tag] : names)
  {
    const std::string named = where + key + "." + printable(name, 60) + " = " + std::to_string(tag);
    if (tag < 1)
      throw ConfigError(named + ": expected a positive integer (a tag value)");
    if (!carried[i++])
      throw ConfigError(named + ": no entity of the mesh carries this tag");
  }
}
} // namespace

NamedMesh name_mesh(std::shared_ptr<compat::Mesh> mesh,
                    std::shared_ptr<const compat::MeshTags> facet_tags,
                    std::shared_ptr<const compat::MeshTags> cell_tags,
                    const std::map<std::string, int>& boundaries,
                    const std::map<std::string, int>& regions, const std::string& source)
{
  const std::string where = printable(source, 200) + ": ";
  const MPI_Comm comm = mesh->comm();
  const auto& topology = compat::topology(*mesh);
  const int tdim = topology.dim();
  if (topology.cell_type() != dolfinx::mesh::CellType::triangle
      and topology.cell_type() != dolfinx::mesh::CellType::tetrahedron)
    throw ConfigError(where + "mesh: cells of type " + dolfinx::mesh::to_string(topology.cell_type())
                      + ": only triangles and tetrahedra are supported");
  if (compat::coordinate_degree(*mesh) != 1)
    throw ConfigError(where + "mesh: coordinates of degree "
                      + std::to_string(compat::coordinate_degree(*mesh))
                      + ": only affine cells (degree 1) are supported");
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::int64_t ghosts = topology.index_map(tdim)->num_ghosts();
  MPI_Allreduce(MPI_IN_PLACE, &ghosts, 1, MPI_INT64_T, MPI_SUM, comm);
  if (size > 1 and ghosts == 0)
    throw ConfigError(where + "mesh: distributed without ghost cells: create it with "
                      "ghost_mode=dolfinx.mesh.GhostMode.shared_facet (the contact, electrode "
                      "and region integrals need the cells across process boundaries)");
  if (facet_tags)
    check_tags(*mesh, *facet_tags, tdim - 1, "facet_tags", where);
  if (cell_tags)
    check_tags(*mesh, *cell_tags, tdim, "cell_tags", where);
  if (!regions.empty() and !cell_tags)
    throw ConfigError(where + "region_names: regions need cell_tags");
  check_names_of_tags(boundaries, facet_tags.get(), "boundary_names", where, comm);
  check_names_of_tags(regions, cell_tags.get(), "region_names", where, comm);
  compat::topology_mutable(*mesh).create_connectivity(tdim - 1, tdim);

  NamedMesh out;
  out.mesh = mesh;
  auto tagged = [&](const compat::MeshTags* tags, int dim, const std::map<std::string, int>& names,
                    std::map<std::string, int>& slot_of)
  {
    std::vector<std::int32_t> indices, values;
    if (tags)
    {
      const auto i = tags->indices();
      const auto v = tags->values();
      indices.assign(i.begin(), i.end());
      values.assign(v.begin(), v.end());
    }
    return renumbered(mesh, dim, json(names), indices, values, slot_of);
  };
  out.facet_tags = tagged(facet_tags.get(), tdim - 1, boundaries, out.tag_of);
  if (regions.empty())
    one_region(out);
  else
    out.cell_tags = tagged(cell_tags.get(), tdim, regions, out.region_of);
  return out;
}
} // namespace piezocontact
