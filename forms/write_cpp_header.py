"""Write the executable's view of the catalogue (terms.py): per dimension and
variant, every term with its piece, role and ffcx kernel, and every Constant
with its shape and config key, so that the C++ side never restates them.
The executable carries the degrees of entry_points.COMPILED_DEGREES, each
pair (degree_u, degree_phi) in .ufl files of its own (suffix `suffix`).
Run by CMake next to ffcx: write_cpp_header.py OUT.h"""

import os
import sys

import entry_points as ep
import piezo_forms as pf
import terms

CELL = {2: "triangle", 3: "tetrahedron"}
# the kernel families: (dimension, axisymmetric) and the name of their files
FAMILIES = {(2, False): "2d", (3, False): "3d", (2, True): "axi"}
# the ffcx file that holds a variant's kernels, by family; "fields": the
# model with the fields of data given by expressions
PREFIX = {None: "piezo_contact_{f}", "fields": "piezo_contact_{f}_fields",
          "manufactured": "manufactured_{f}"}
# the kinds of run: (manufactured, fields); a manufactured run takes no
# expressions (config.cpp)
RUNS = ((False, False), (False, True), (True, False))


def suffix(degrees):
    """The .ufl files' suffix of a pair of degrees: none at (1, 1) (the
    paper's P1), _p2 at (2, 2), _u2phi1 at (2, 1)"""
    ku, kphi = degrees
    return "" if degrees == (1, 1) else f"_p{ku}" if ku == kphi else f"_u{ku}phi{kphi}"


def files(degrees):
    """The ffcx files of a pair of degrees, by variant."""
    return {v: p + suffix(degrees) for v, p in PREFIX.items()}


def roles(d, axisymmetric, manufactured_run, fields, degrees):
    """(term, role, ffcx file, form name) in catalogue order, each Jacobian
    after the residual term it is the derivative of, then the term's
    stiffness (its own kernel, or the Jacobian's where they are the same)
    and damping."""
    jacobians = ep.compiled(CELL[d], degrees=degrees, axisymmetric=axisymmetric)[4]
    prefix = files(degrees)
    model = prefix["fields" if fields else None]
    out = []
    for t in terms.catalogue(d, manufactured_run):
        out.append((t, t.role, model if t.variant is None else prefix[t.variant], t.name))
        if t.role == "F" and terms.jacobian_name(t) in jacobians:
            name = terms.jacobian_name(t)
            out.append((t, jacobians[name], model, name))
            K, C = "K" + t.name[1:], "C" + t.name[1:]
            out.append((t, "K", model, K if K in jacobians else name))
            if C in jacobians:
                out.append((t, "C", model, C))
    return out


def term_table(d, axisymmetric, manufactured_run, fields, degrees):
    rows = []
    for t, role, prefix, name in roles(d, axisymmetric, manufactured_run, fields, degrees):
        p = prefix.format(f=FAMILIES[d, axisymmetric])
        kernel = (f"nullptr, expression_{p}_{name}" if t.expression
                  else f"form_{p}_{name}, nullptr")
        rows.append(f'{{"{name}", Piece::{t.piece}, Role::{role}, "{t.slot or ""}", '
                    f'"{t.where or ""}", Space::{t.space}, {kernel}}}')
    return "{" + ",\n          ".join(rows) + "}"


def data_table(d, axisymmetric, manufactured_run, fields, degrees=None):
    groups = ep.data(d, manufactured_run, axisymmetric)
    rows = []
    for group, data in groups.items():
        for name, datum in data.items():
            shape = ", ".join(map(str, datum.shape))
            field = pf.field_name(name) if datum.spatial and fields else ""
            rows.append(f'{{"{group}", "{name}", {{{shape}}}, "{datum.key or ""}", '
                        f'{"true" if datum.timed else "false"}, "{datum.flag or ""}", '
                        f'"{field}"}}')
    return "{" + ",\n          ".join(rows) + "}"


def by_case(table, per_degree=True):
    cases = []
    for degrees in ep.COMPILED_DEGREES if per_degree else [None]:
        when = f" and degrees == Degrees{{{degrees[0]}, {degrees[1]}}}" if degrees else ""
        for d, axi in FAMILIES:
            for m, fields in RUNS:
                cases.append(f"  if (d == {d} and axisymmetric == {'true' if axi else 'false'}"
                             f" and manufactured == {'true' if m else 'false'}"
                             f" and fields == {'true' if fields else 'false'}"
                             f"{when})\n    return {table(d, axi, m, fields, degrees)};")
    return "\n".join(cases)


def space_factories():
    """The ufcx function spaces of x and of the contact pressure (dolfinx
    0.5 builds its spaces from them), by dimension and degrees."""
    cases = []
    for degrees in ep.COMPILED_DEGREES:
        for d in (2, 3):  # the spaces of a 2D family are the same in every formulation
            p = files(degrees)[None].format(f=FAMILIES[d, False])
            cases.append(f"  if (d == {d} and degrees == Degrees{{{degrees[0]}, {degrees[1]}}})\n"
                         f"    return {{PIEZO_UFCX_SPACE(functionspace_form_{p}_F_region), "
                         f"PIEZO_UFCX_SPACE(functionspace_form_{p}_contact_pressure_load)}};")
    return "\n".join(cases)


def field_degrees():
    cases = []
    for degrees in ep.COMPILED_DEGREES:
        cases.append(f"  if (degrees == Degrees{{{degrees[0]}, {degrees[1]}}})\n"
                     f"    return {ep.field_degree(degrees)};")
    return "\n".join(cases)


def carried():
    return ", ".join(f"Degrees{{{ku}, {kphi}}}" for ku, kphi in ep.COMPILED_DEGREES)


here = os.path.dirname(os.path.abspath(__file__))
for degrees in ep.COMPILED_DEGREES:
    for p in files(degrees).values():
        for f in FAMILIES.values():
            assert os.path.exists(os.path.join(here, p.format(f=f) + ".ufl")), \
                f"entry_points.COMPILED_DEGREES has {degrees}: {p.format(f=f)}.ufl is missing"
includes = "\n".join(f'#include "{p.format(f=f)}.h"' for degrees in ep.COMPILED_DEGREES
                     for p in files(degrees).values() for f in FAMILIES.values())
header = f"""// Generated from forms/terms.py by forms/write_cpp_header.py: do not edit.
#pragma once
{includes}
#include <array>
#include <cstddef>
#include <piezocontact/compat.h>
#include <stdexcept>
#include <utility>
#include <string>
#include <vector>

namespace piezocontact::forms
{{
/// What one instance of a term is integrated over (forms/terms.py)
enum class Piece {{ region, boundary, contact, electrode, exterior, mesh, obstacle }};
/// Residual, applied loads, Jacobian (constant in a run, or not), the
/// stiffness, damping and mass of a linearisation, output
enum class Role {{ F, L, J, J_state, K, C, M, output }};
/// The space of a form's arguments: x's, or the contact pressure's (P1)
enum class Space {{ W, P }};

/// A term of the catalogue and its kernel (a form, or an expression)
struct Term
{{
  std::string name;
  Piece piece;
  Role role;
  std::string slot;  ///< output: the Model member it fills
  std::string where; ///< boundary: the config key a boundary needs (empty: all)
  Space space;
  ufcx_form* form;
  ufcx_expression* expression;
}};

/// A Constant of the forms: its group ("shared", "material", "load"),
/// name, shape, the config key that sets it (empty: the core), whether
/// that key may carry a history, for a switch the value that makes it 1,
/// and for a datum that may vary in space the name of its field (the
/// coefficient the core interpolates expressions into; empty: none)
struct Datum
{{
  std::string group, name;
  std::vector<std::size_t> shape;
  std::string key;
  bool timed;
  std::string flag;
  std::string field;
}};

/// The degrees of the fields (u, phi)
using Degrees = std::array<int, 2>;

/// The Lagrange degree of the fields of spatial data, at some degrees
inline int field_degree(Degrees degrees)
{{
{field_degrees()}
  throw std::invalid_argument("no fields at these degrees");
}}

/// The degrees compiled ahead of time
inline std::vector<Degrees> carried() {{ return {{{carried()}}}; }}

/// The terms of a run in d dimensions (axisymmetric or Cartesian) at some
/// degrees, in the order they are summed; `fields`: the kernels with the
/// fields of data given by expressions
inline std::vector<Term> catalogue(int d, bool axisymmetric, bool manufactured, bool fields,
                                   Degrees degrees)
{{
{by_case(term_table)}
  throw std::invalid_argument("no kernels for d = " + std::to_string(d) + " at degrees "
                              + std::to_string(degrees[0]) + ", " + std::to_string(degrees[1]));
}}

/// The function spaces of x and of the contact pressure (dolfinx 0.5 makes
/// its spaces from ffcx's; null on dolfinx 0.9, which makes them from basix)
inline std::pair<compat::UfcxSpaceFactory, compat::UfcxSpaceFactory>
space_factories(int d, Degrees degrees)
{{
{space_factories()}
  throw std::invalid_argument("no spaces for d = " + std::to_string(d));
}}

/// The Constants of the forms (the same at every degree)
inline std::vector<Datum> data(int d, bool axisymmetric, bool manufactured, bool fields)
{{
{by_case(data_table, per_degree=False)}
  throw std::invalid_argument("no kernels for d = " + std::to_string(d));
}}
}} // namespace piezocontact::forms
"""
with open(sys.argv[1], "w") as out:
    out.write(header)
