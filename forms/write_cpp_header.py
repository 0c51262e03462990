"""Write the C++ view of piezo_forms.py's metadata (the number of boundary
slots and the name and shape of every Constant), so that the C++ solver never
restates them. Run by CMake next to ffcx: write_cpp_header.py OUT.h"""

import sys

import piezo_forms as pf

shapes = ",\n".join(f'    {{"{name}", {{{", ".join(map(str, shape))}}}}}'
                    for name, shape in pf.constant_shapes().items())
header = f"""// Generated from forms/piezo_forms.py by forms/write_cpp_header.py: do not edit.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace piezo::forms
{{
/// Facet tags 1..max_boundaries carry the named boundaries
inline constexpr int max_boundaries = {pf.MAX_BOUNDARIES};

/// Name and shape of every Constant of the forms
inline const std::map<std::string, std::vector<std::size_t>> constant_shapes = {{
{shapes}
}};
}} // namespace piezo::forms
"""
with open(sys.argv[1], "w") as out:
    out.write(header)
