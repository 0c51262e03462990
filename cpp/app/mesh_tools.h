// The mesh tools of the executable: a gmsh script of meshes/ or the .msh
// converter of the Python package (python3 -m piezocontact.msh), run as a
// child process on one rank.
#pragma once

#include <piezocontact/mesh.h>

namespace piezocontact::app
{
/// Run the tool of `job`; its exit status (0: done)
int convert_mesh(const MeshConversion& job);
} // namespace piezocontact::app
