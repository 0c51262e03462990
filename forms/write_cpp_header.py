"""Write the C++ view of the forms' metadata (the number of boundary slots,
the name and shape of every Constant of piezo_forms.py and manufactured.py),
so that the C++ solver never restates them. Run by CMake next to ffcx:
write_cpp_header.py OUT.h"""

import sys

import manufactured as mms
import piezo_forms as pf


def cpp_map(shapes):
    return ",\n".join(f'    {{"{name}", {{{", ".join(map(str, shape))}}}}}'
                      for name, shape in shapes.items())


header = f"""// Generated from forms/piezo_forms.py by forms/write_cpp_header.py: do not edit.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace piezocontact::forms
{{
/// Facet tags 1..max_boundaries carry the named boundaries
inline constexpr int max_boundaries = {pf.MAX_BOUNDARIES};

/// Name and shape of every Constant of the forms
inline const std::map<std::string, std::vector<std::size_t>> constant_shapes = {{
{cpp_map(pf.constant_shapes())}
}};

/// The Constants that manufactured.ufl adds (manufactured-solution runs)
inline const std::map<std::string, std::vector<std::size_t>> manufactured_constant_shapes = {{
{cpp_map(mms.constant_shapes())}
}};
}} // namespace piezocontact::forms
"""
with open(sys.argv[1], "w") as out:
    out.write(header)
