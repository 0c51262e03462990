"""Write the executable's view of the catalogue (terms.py): per dimension and
variant, every term with its piece, role and ffcx kernel, and every Constant
with its shape and config key, so that the C++ side never restates them.
Run by CMake next to ffcx: write_cpp_header.py OUT.h"""

import sys

import entry_points as ep
import terms

CELL = {2: "triangle", 3: "tetrahedron"}
# the ffcx file that holds a variant's kernels, by dimension
PREFIX = {None: "piezo_contact_{d}d", "manufactured": "manufactured_{d}d"}


def roles(d, manufactured_run):
    """(term, role, ffcx file, form name) in catalogue order, each Jacobian
    after the residual term it is the derivative of."""
    jacobians = ep.compiled(CELL[d])[4]
    out = []
    for t in terms.catalogue(d, manufactured_run):
        out.append((t, t.role, PREFIX[t.variant], t.name))
        if t.role == "F" and terms.jacobian_name(t) in jacobians:
            name = terms.jacobian_name(t)
            out.append((t, jacobians[name], PREFIX[None], name))
    return out


def term_table(d, manufactured_run):
    rows = []
    for t, role, prefix, name in roles(d, manufactured_run):
        p = prefix.format(d=d)
        kernel = (f"nullptr, expression_{p}_{name}" if t.expression
                  else f"form_{p}_{name}, nullptr")
        rows.append(f'{{"{name}", Piece::{t.piece}, Role::{role}, "{t.slot or ""}", '
                    f'"{t.where or ""}", {kernel}}}')
    return "{" + ",\n          ".join(rows) + "}"


def data_table(d, manufactured_run):
    groups = ep.data(d, manufactured_run)
    rows = []
    for group, data in groups.items():
        for name, datum in data.items():
            shape = ", ".join(map(str, datum.shape))
            rows.append(f'{{"{group}", "{name}", {{{shape}}}, "{datum.key or ""}", '
                        f'{"true" if datum.timed else "false"}, "{datum.flag or ""}"}}')
    return "{" + ",\n          ".join(rows) + "}"


def by_case(table):
    cases = []
    for d in (2, 3):
        for m in (False, True):
            cases.append(f"  if (d == {d} and manufactured == {'true' if m else 'false'})\n"
                         f"    return {table(d, m)};")
    return "\n".join(cases)


includes = "\n".join(f'#include "{p.format(d=d)}.h"' for p in PREFIX.values() for d in (2, 3))
header = f"""// Generated from forms/terms.py by forms/write_cpp_header.py: do not edit.
#pragma once
{includes}
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace piezocontact::forms
{{
/// What one instance of a term is integrated over (forms/terms.py)
enum class Piece {{ region, boundary, contact, electrode, exterior, mesh }};
/// Residual, applied loads, Jacobian (constant in a run, or not), output
enum class Role {{ F, L, J, J_state, output }};

/// A term of the catalogue and its kernel (a form, or an expression)
struct Term
{{
  std::string name;
  Piece piece;
  Role role;
  std::string slot;  ///< output: the Model member it fills
  std::string where; ///< boundary: the config key a boundary needs (empty: all)
  ufcx_form* form;
  ufcx_expression* expression;
}};

/// A Constant of the forms: its group ("shared", "material", "load"),
/// name, shape, the config key that sets it (empty: the core), whether
/// that key may carry a history, and for a switch the value that makes it 1
struct Datum
{{
  std::string group, name;
  std::vector<std::size_t> shape;
  std::string key;
  bool timed;
  std::string flag;
}};

/// The terms of a run in d dimensions, in the order they are summed
inline std::vector<Term> catalogue(int d, bool manufactured)
{{
{by_case(term_table)}
  throw std::invalid_argument("no kernels for d = " + std::to_string(d));
}}

/// The Constants of the forms
inline std::vector<Datum> data(int d, bool manufactured)
{{
{by_case(data_table)}
  throw std::invalid_argument("no kernels for d = " + std::to_string(d));
}}
}} // namespace piezocontact::forms
"""
with open(sys.argv[1], "w") as out:
    out.write(header)
