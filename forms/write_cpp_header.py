"""Write the C++ view of the forms' metadata (the name and shape of every
Constant of piezo_forms.py and manufactured.py, in 2D and 3D), so that the
C++ solver never restates them. Run by CMake next to ffcx:
write_cpp_header.py OUT.h"""

import sys

import manufactured as mms
import piezo_forms as pf


def cpp_map(shapes):
    return "{" + ", ".join(f'{{"{name}", {{{", ".join(map(str, shape))}}}}}'
                           for name, shape in shapes.items()) + "}"


def by_dimension(function):
    return f"d == 2 ? Shapes{cpp_map(function(2))}\n                : Shapes{cpp_map(function(3))}"


header = f"""// Generated from forms/piezo_forms.py by forms/write_cpp_header.py: do not edit.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace piezocontact::forms
{{
using Shapes = std::map<std::string, std::vector<std::size_t>>;

/// The Constants shared by every term, in d dimensions
inline Shapes constant_shapes(int d)
{{
  return {by_dimension(pf.constant_shapes)};
}}

/// The Constants of one region's material
inline Shapes material_shapes(int d)
{{
  return {by_dimension(pf.material_shapes)};
}}

/// The Constants of one named boundary's loads
inline Shapes load_shapes(int d)
{{
  return {by_dimension(pf.load_shapes)};
}}

/// The Constants that a manufactured-solution run adds
inline const Shapes manufactured_constant_shapes = {cpp_map(mms.constant_shapes())};
}} // namespace piezocontact::forms
"""
with open(sys.argv[1], "w") as out:
    out.write(header)
