// Points in the straight-sided simplices of a mesh (P1 geometry: a cell's
// geometry nodes are its vertices)
#pragma once

#include "compat.h"

#include <array>
#include <span>
#include <vector>

namespace piezocontact
{
/// The vertices of local cell c, in the cell's order
std::vector<std::array<double, 3>> cell_vertices(const compat::Mesh& mesh, std::int32_t c);

/// The barycentric coordinates of x in the simplex of `vertices` (2D or 3D:
/// tdim + 1 vertices), one per vertex, summing to 1; all >= 0 inside
std::vector<double> barycentric(std::span<const double> x,
                                const std::vector<std::array<double, 3>>& vertices);
} // namespace piezocontact
