#include "model.h"

#include <algorithm>

namespace piezocontact
{
using namespace dolfinx;
namespace
{
std::vector<std::int32_t> tagged(const mesh::MeshTags<std::int32_t>* tags, int tag)
{
  std::vector<std::int32_t> out;
  if (!tags)
    return out;
  const auto idx = tags->indices();
  const auto val = tags->values();
  for (std::size_t i = 0; i < idx.size(); ++i)
    if (val[i] == tag)
      out.push_back(idx[i]);
  return out;
}
} // namespace

std::vector<std::int32_t> NamedMesh::boundary_facets(const std::string& name) const
{
  return tagged(facet_tags.get(), tag_of.at(name));
}

std::vector<std::int32_t> NamedMesh::region_cells(const std::string& name) const
{
  return tagged(cell_tags.get(), region_of.at(name));
}

// An exterior facet has one cell: the facet is the region's if that cell is
std::vector<std::int32_t> NamedMesh::boundary_facets_of(const std::string& boundary,
                                                        const std::string& region) const
{
  const int tdim = compat::topology(*mesh).dim();
  compat::topology_mutable(*mesh).create_connectivity(tdim - 1, tdim);
  const auto f_to_c = compat::topology(*mesh).connectivity(tdim - 1, tdim);
  std::vector<std::int32_t> cells = region_cells(region);
  std::sort(cells.begin(), cells.end());
  std::vector<std::int32_t> out;
  for (const std::int32_t f : boundary_facets(boundary))
    if (std::binary_search(cells.begin(), cells.end(), f_to_c->links(f)[0]))
      out.push_back(f);
  return out;
}

} // namespace piezocontact
