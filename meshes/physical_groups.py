"""Name a gmsh model's entities: the physical groups the solver reads as
regions (cells) and boundaries (facets)."""

import gmsh


def name_groups(dim, groups):
    """Physical groups of dimension `dim` from {name: [entity tags]}, tagged
    1, 2, ... in the order given."""
    for tag, (name, members) in enumerate(groups.items(), start=1):
        gmsh.model.addPhysicalGroup(dim, list(members), tag)
        gmsh.model.setPhysicalName(dim, tag, name)
