#include "config.h"
#include "expressions.h"
#include "json_input.h"
#include "schema.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace piezocontact
{
using namespace dolfinx;

const json* contact_block(const json& cfg, const json& boundary)
{
  const json contact = boundary.value("contact", json());
  if (contact.is_object())
    return &boundary["contact"];
  return contact == true and cfg.contains("contact") ? &cfg["contact"] : nullptr;
}

bool paper_foundation(const json& cfg, const json& boundary)
{
  if (boundary.value("contact", json()) != true or !cfg.contains("contact"))
    return false;
  const json& block = cfg["contact"];
  return !block.contains("obstacle") and block.value("method", "penalty") == "penalty";
}

namespace
{
std::string fmt(const json& v) { return printable(v); }

std::string fmt_g(double v)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

std::string join(const std::string& path, const std::string& key)
{
  const std::string k = printable(key, 60);
  return path.empty() ? k : path + "." + k;
}

[[noreturn]] void fail(const std::string& source, const std::string& what)
{
  throw ConfigError(printable(source, 200) + ": " + what);
}

// Optimal string alignment distance (swaps of neighbours count 1).
std::size_t edit_distance(const std::string& a, const std::string& b)
{
  std::vector<std::vector<std::size_t>> d(a.size() + 1,
                                          std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i)
    d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j)
    d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1,
                          d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

bool is_utf8(const std::string& s)
{
  try
  {
    (void)json(s).dump();
    return true;
  }
  catch (const json::type_error&)
  {
    return false;
  }
}

bool is_number(const json& v)
{
  return v.is_number() and std::isfinite(v.get<double>());
}

void check_bounds(const json& v, const json& rule, const std::string& path,
                  const std::string& source)
{
  const double x = v.get<double>();
  if (rule.contains("min") and x < rule["min"].get<double>())
    fail(source, path + " = " + fmt(v) + ": must be >= " + fmt(rule["min"]));
  if (rule.contains("exclusive_min")
      and x <= rule["exclusive_min"].get<double>())
    fail(source,
         path + " = " + fmt(v) + ": must be > " + fmt(rule["exclusive_min"]));
  if (rule.contains("max") and x > rule["max"].get<double>())
    fail(source, path + " = " + fmt(v) + ": must be <= " + fmt(rule["max"]));
}

bool is_number_list(const json& v, std::size_t n)
{
  return v.is_array() and v.size() == n
         and std::all_of(v.begin(), v.end(), is_number);
}

/// Numbers as doubles; expressions (strings) and free components (null)
/// as they are
json to_doubles(const json& v)
{
  if (v.is_array())
  {
    json out = json::array();
    for (const auto& item : v)
      out.push_back(item.is_null() or item.is_string() ? item : to_doubles(item));
    return out;
  }
  return v.is_string() ? v : json(v.get<double>());
}

/// An expression of x, y, z, t where the schema allows one ("expression"):
/// parsed now, so that a bad one is refused at start-up with the parser's
/// reason
void check_expression(const json& value, const std::string& path, const std::string& source)
{
  try
  {
    SpaceTimeExpression(value.get<std::string>());
  }
  catch (const std::invalid_argument& e)
  {
    fail(source, path + ": " + fmt(value) + ": not an expression of x, y, z, t: " + e.what());
  }
}

/// The dimensions a value may have: d, or 2 and 3 while d is not known
std::vector<int> dimensions(int d) { return d ? std::vector{d} : std::vector{2, 3}; }

/// A size of the schema in d dimensions: a number, "d", or "voigt" (the
/// length of a Voigt strain: 3 in 2D, 6 in 3D)
std::size_t size_in(const json& size, int d)
{
  if (size == "d")
    return d;
  if (size == "voigt")
    return d == 2 ? 3 : 6;
  return size.get<std::size_t>();
}

/// The lengths a vector may have in d dimensions (0: not known yet):
/// "frame" is a direction of the 3D frame, which a 2D mesh may give in its
/// plane (2 components) or in full (3: z out of the plane, the hoop
/// direction in axisymmetry)
std::vector<std::size_t> lengths_in(const json& length, int d)
{
  std::vector<std::size_t> out;
  for (int dd : dimensions(d))
    for (std::size_t n : length == "frame" ? std::vector<std::size_t>{std::size_t(dd), 3}
                                           : std::vector<std::size_t>{size_in(length, dd)})
      if (std::find(out.begin(), out.end(), n) == out.end())
        out.push_back(n);
  return out;
}

/// The (vector dimension, Voigt length) pairs a material tensor may have
/// in d dimensions: the reduced shapes of the 2D formulations (plane 3,
/// axisymmetric 4 strains) and the 3D shape
std::vector<std::pair<int, std::size_t>> frames(int d)
{
  std::vector<std::pair<int, std::size_t>> out;
  for (int dd : dimensions(d))
  {
    if (dd == 2)
      out.insert(out.end(), {{2, 3}, {2, 4}});
    out.push_back({3, 6});
  }
  return out;
}

std::string either(const std::vector<std::string>& options)
{
  std::string out;
  for (std::size_t i = 0; i < options.size(); ++i)
    out += (i == 0 ? "" : i + 1 == options.size() ? " or " : ", ") + options[i];
  return out;
}

// Validate `value` against `rule` in d dimensions (0: 2 or 3, not known
// yet); return it with defaults filled in.
const json& schema()
{
  static const json parsed = json::parse(config_schema);
  return parsed;
}

json check(const json& value, const json& rule_, const std::string& path,
           const std::string& source, int d);

/// A load history: exactly one kind; a table's times increasing
json check_history(const json& value, const std::string& path, const std::string& source)
{
  json h = check(value, schema()["definitions"]["history"], path, source, 0);
  if (h.size() != 1)
    fail(source, path + " = " + fmt(value) + ": give exactly one of ramp, sine, table");
  if (h.contains("table"))
  {
    const json& rows = h["table"];
    if (rows.empty())
      fail(source, path + ".table: give at least one [t, factor] row");
    for (std::size_t i = 1; i < rows.size(); ++i)
      if (!(rows[i][0].get<double>() > rows[i - 1][0].get<double>()))
        fail(source, path + ".table = " + fmt(rows) + ": times must increase (row "
                         + std::to_string(i) + ")");
  }
  return h;
}

/// One value against one rule of the schema: a function per rule type
struct Check
{
  const json& value;
  const json& rule;
  const std::string& path;
  const std::string& source;
  int d;
  json alternative; ///< a word allowed instead of the value

  [[noreturn]] void wrong(const std::string& expected) const
  {
    fail(source, path + " = " + fmt(value) + ": expected " + expected
                     + (alternative.is_null() ? "" : " or " + fmt(alternative)));
  }

  json operator()() const
  {
    using Method = json (Check::*)() const;
    static const std::map<std::string, Method> by_type
        = {{"one_of", &Check::one_of},   {"integers", &Check::integers},
           {"object", &Check::object},   {"map", &Check::map},
           {"number", &Check::number},   {"integer", &Check::integer},
           {"boolean", &Check::boolean}, {"string", &Check::string},
           {"scalar", &Check::scalar},   {"vector", &Check::vector},
           {"matrix", &Check::matrix},   {"pairs", &Check::pairs},
           {"points", &Check::points},   {"numbers", &Check::numbers}};
    const std::string t = rule["type"];
    const auto method = by_type.find(t);
    if (method == by_type.end())
      throw std::logic_error("schema: unknown type " + t);
    return (this->*(method->second))();
  }

  /// The option of the value's kind (a list, an object, a boolean or a
  /// number) judges it
  json one_of() const
  {
    const auto kind = [](const std::string& type)
    {
      return type == "vector" or type == "integers" or type == "numbers" ? json::value_t::array
             : type == "object" or type == "map"    ? json::value_t::object
             : type == "boolean"                    ? json::value_t::boolean
                                                    : json::value_t::number_float;
    };
    const auto kind_of = [](const json& v)
    { return v.is_number() ? json::value_t::number_float : v.type(); };
    for (const auto& option : rule["options"])
    {
      const json& resolved = option.contains("ref")
                                 ? schema()["keys"][option["ref"].get<std::string>()]
                                 : option;
      if (kind(resolved["type"]) == kind_of(value))
        return check(value, option, path, source, d);
    }
    // else the option of the value's list-ness says what it expected
    for (const auto& option : rule["options"])
      if (option.contains("type") and kind(option["type"]) != json::value_t::object
          and kind(option["type"]) != json::value_t::boolean
          and (kind(option["type"]) == json::value_t::array) == value.is_array())
        return check(value, option, path, source, d);
    wrong(rule["expected"].get<std::string>());
  }

  /// A list of numbers of any length but 0, each within the bounds
  json numbers() const
  {
    if (!(value.is_array() and !value.empty()
          and std::all_of(value.begin(), value.end(), [](const json& v) { return is_number(v); })))
      wrong("a non-empty list of numbers");
    for (std::size_t i = 0; i < value.size(); ++i)
      check_bounds(value[i], rule, path + "[" + std::to_string(i) + "]", source);
    return value;
  }

  json integers() const
  {
    const std::size_t n = rule["length"];
    if (!(value.is_array() and value.size() == n
          and std::all_of(value.begin(), value.end(),
                          [](const json& v) { return v.is_number_integer(); })))
      wrong("a list of " + std::to_string(n) + " integers");
    for (std::size_t i = 0; i < n; ++i)
      check_bounds(value[i], rule, path + "[" + std::to_string(i) + "]", source);
    return value;
  }

  json object() const
  {
    if (!value.is_object())
      wrong("an object");
    const json& keys = rule["keys"];
    std::vector<std::string> names;
    for (const auto& [k, _] : keys.items())
      names.push_back(k);
    for (const auto& [k, _] : value.items())
      if (!keys.contains(k))
      {
        const std::string near = closest_key(k, names);
        const std::string hint
            = near.empty() ? "" : " (did you mean '" + join(path, near) + "'?)";
        fail(source, join(path, k) + ": unknown key" + hint);
      }
    json out = json::object();
    for (const auto& [k, sub] : keys.items())
    {
      if (value.contains(k))
        out[k] = check(value[k], sub, join(path, k), source, d);
      else if (sub.value("default", json()) == "zeros") // a vector of d zeros, once d is known
      {
        if (d)
          out[k] = std::vector<double>(size_in(sub["length"], d), 0.0);
      }
      else if (sub.contains("default"))
        out[k] = check(sub["default"], sub, join(path, k), source, d);
      else if (sub.value("required", false))
        fail(source, join(path, k) + ": missing required key");
    }
    return out;
  }

  json map() const
  {
    if (!value.is_object())
      wrong("an object");
    json out = json::object();
    for (const auto& [k, v] : value.items())
    {
      if (!is_utf8(k))
        fail(source, join(path, k) + ": a name in UTF-8 expected");
      out[k] = check(v, rule["values"], join(path, k), source, d);
    }
    return out;
  }

  json number() const
  {
    if (value.is_string() and rule.value("expression", false))
    {
      check_expression(value, path, source);
      return value;
    }
    if (!is_number(value))
      wrong(rule.value("expression", false) ? "a number or an expression of x, y, z, t (a string)"
                                            : "a number");
    check_bounds(value, rule, path, source);
    return value.get<double>();
  }

  json integer() const
  {
    if (!value.is_number_integer())
      wrong("an integer");
    check_bounds(value, rule, path, source);
    // read as int later: never beyond its range, whatever the schema says
    const double x = value.get<double>();
    if (x > std::numeric_limits<int>::max() or x < std::numeric_limits<int>::min())
      fail(source, path + " = " + fmt(value) + ": beyond the range of a 32-bit integer");
    return value.get<int>();
  }

  json boolean() const
  {
    if (!value.is_boolean())
      wrong("true or false");
    return value;
  }

  json string() const
  {
    if (!value.is_string())
      wrong("a string");
    if (rule.contains("enum"))
    {
      const json& e = rule["enum"];
      if (std::find(e.begin(), e.end(), value) == e.end())
      {
        std::string options;
        for (const auto& o : e)
          options += (options.empty() ? "" : ", ") + o.get<std::string>();
        wrong("one of " + options);
      }
    }
    return value;
  }

  json scalar() const
  {
    if (!(value.is_string() or value.is_boolean() or is_number(value)))
      wrong("a string, number or boolean");
    return value;
  }

  /// "nullable": a component may be null (left free), not all of them
  json vector() const
  {
    const bool nullable = rule.value("nullable", false);
    const bool expressions = rule.value("expression", false);
    auto fits = [&](std::size_t n)
    {
      if (!value.is_array() or value.size() != n)
        return false;
      std::size_t given = 0;
      for (const auto& v : value)
      {
        if (!(is_number(v) or (nullable and v.is_null()) or (expressions and v.is_string())))
          return false;
        given += !v.is_null();
      }
      return given > 0;
    };
    std::vector<std::string> options;
    for (std::size_t n : lengths_in(rule["length"], d))
    {
      if (fits(n))
      {
        for (std::size_t i = 0; i < n; ++i)
        {
          const std::string at = path + "[" + std::to_string(i) + "]";
          if (value[i].is_string())
            check_expression(value[i], at, source);
          else if (!value[i].is_null())
            check_bounds(value[i], rule, at, source);
        }
        return to_doubles(value);
      }
      options.push_back(std::to_string(n));
    }
    wrong("a list of " + either(options) + " numbers"
          + (expressions ? " or expressions of x, y, z, t (strings)" : "")
          + (nullable ? ", null for a free component" : "")
          + (rule["length"] == "d" ? d ? " (the mesh is " + std::to_string(d) + "D)" : " (2D or 3D)" : ""));
  }

  /// In 2D a material tensor has a reduced shape (plane: 3 strains,
  /// axisymmetric: 4) or its 3D shape, which the formulation reduces
  /// (check_formulation narrows it down once the formulation is known)
  json matrix() const
  {
    std::vector<std::string> options;
    for (const auto& [dd, strains] : frames(d))
    {
      const auto size = [&](const json& s) { return s == "voigt" ? strains : size_in(s, dd); };
      const std::size_t r = size(rule["shape"][0]), c = size(rule["shape"][1]);
      if (std::find(options.begin(), options.end(),
                    std::to_string(r) + "x" + std::to_string(c)) != options.end())
        continue;
      if (value.is_array() and value.size() == r
          and std::all_of(value.begin(), value.end(),
                          [c](const json& row) { return is_number_list(row, c); }))
        return to_doubles(value);
      options.push_back(std::to_string(r) + "x" + std::to_string(c));
    }
    wrong("a " + either(options) + " matrix (a list of rows of numbers"
          + (d ? ", the mesh is " + std::to_string(d) + "D)" : ", 2D or 3D)"));
  }

  json pairs() const
  {
    if (!(value.is_array() and std::all_of(value.begin(), value.end(),
                                           [](const json& p) { return is_number_list(p, 2); })))
      wrong("a list of [t, value] pairs");
    return to_doubles(value);
  }

  json points() const
  {
    for (int dd : dimensions(d))
      if (value.is_array()
          and std::all_of(value.begin(), value.end(),
                          [dd](const json& p) { return is_number_list(p, dd); }))
        return to_doubles(value);
    wrong(d == 2 ? "a list of [x, y] points" : d == 3 ? "a list of [x, y, z] points"
                                                      : "a list of [x, y] or of [x, y, z] points");
  }
};

/// A timed datum: the value, or {"value": the value, "history": ...}
json check_timed(const json& value, const json& rule, const std::string& path,
                 const std::string& source, int d)
{
  for (const auto& [k, _] : value.items())
    if (k != "value" and k != "history")
      fail(source, join(path, k) + ": unknown key (a timed datum has value and history)");
  for (const char* k : {"value", "history"})
    if (!value.contains(k))
      fail(source, join(path, k) + ": missing required key (a timed datum has value and history)");
  json plain = rule;
  plain.erase("timed");
  return {{"value", check(value["value"], plain, join(path, "value"), source, d)},
          {"history", check_history(value["history"], join(path, "history"), source)}};
}

json check(const json& value, const json& rule_, const std::string& path,
           const std::string& source, int d)
{
  // {"ref": KEY}: the rule of definitions.KEY or of the top-level key KEY
  const json& rule = !rule_.contains("ref") ? rule_
                     : schema()["definitions"].contains(rule_["ref"].get<std::string>())
                         ? schema()["definitions"][rule_["ref"].get<std::string>()]
                         : schema()["keys"][rule_["ref"].get<std::string>()];
  if (rule.value("timed", false) and value.is_object())
    return check_timed(value, rule, path, source, d);
  const Check c{value, rule, path, source, d, rule.value("alternative", json())};
  if (!c.alternative.is_null() and value == c.alternative)
    return value;
  if (value.is_string() and !is_utf8(value.get<std::string>()))
    c.wrong("text in UTF-8");
  return c();
}

using Matrix = std::vector<std::vector<double>>;

void check_symmetric(const Matrix& m, const std::string& path,
                     const std::string& source)
{
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = i + 1; j < m.size(); ++j)
    {
      const double scale
          = std::max({std::abs(m[i][j]), std::abs(m[j][i]), 1e-300});
      if (std::abs(m[i][j] - m[j][i]) > 1e-12 * scale)
      {
        fail(source, path + " = " + fmt(json(m)) + ": must be symmetric (entry ["
                         + std::to_string(i) + "][" + std::to_string(j)
                         + "] = " + fmt_g(m[i][j]) + " but ["
                         + std::to_string(j) + "][" + std::to_string(i)
                         + "] = " + fmt_g(m[j][i]) + ")");
      }
    }
}

/// Cholesky factorisation of m scaled to entries of order 1 (those of
/// 1e-170 I would underflow): every pivot positive
bool positive_definite(Matrix m)
{
  double largest = 0.0;
  for (const auto& row : m)
    for (double v : row)
      largest = std::max(largest, std::abs(v));
  if (largest == 0.0)
    return false;
  for (auto& row : m)
    for (double& v : row)
      v /= largest;
  const std::size_t n = m.size();
  for (std::size_t j = 0; j < n; ++j)
  {
    for (std::size_t k = 0; k < j; ++k)
      m[j][j] -= m[j][k] * m[j][k];
    if (!(m[j][j] > 1e-14)) // a pivot at round-off of the largest entry: singular
      return false;
    m[j][j] = std::sqrt(m[j][j]);
    for (std::size_t i = j + 1; i < n; ++i)
    {
      for (std::size_t k = 0; k < j; ++k)
        m[i][j] -= m[i][k] * m[j][k];
      m[i][j] /= m[j][j];
    }
  }
  return true;
}

void check_spd(const Matrix& m, const std::string& path,
               const std::string& source, const std::string& why)
{
  check_symmetric(m, path, source);
  if (!positive_definite(m))
    fail(source, path + " = " + fmt(json(m)) + ": not positive definite: " + why);
}

// A manufactured solution brings its own loads and Dirichlet data; "exact"
// boundary values need one.
void check_manufactured(const json& cfg, const std::string& source)
{
  const bool mms = cfg.contains("manufactured");
  const std::string unused
      = "not used with a manufactured solution (its loads come from the exact solution)";
  if (mms and cfg.contains("regions"))
    fail(source, "regions: a manufactured solution has one material (give material)");
  if (mms)
  {
    for (const char* key : {"body_force", "charge_density"})
    {
      if (!cfg["loads"].contains(key))
        continue;
      const json& v = cfg["loads"][key];
      const bool zero = v.is_array() ? std::all_of(v.begin(), v.end(),
                                                   [](const json& c) { return c == 0.0; })
                                     : v == 0.0;
      if (!zero)
        fail(source, std::string("loads.") + key + " = " + fmt(v) + ": " + unused);
    }
  }
  for (const auto& [name, bc] : cfg["boundaries"].items())
  {
    for (const char* key : {"displacement", "potential"})
    {
      if (!bc.contains(key))
        continue;
      const std::string where
          = "boundaries." + name + "." + key + " = " + fmt(bc[key]);
      if (bc[key] == "exact" and !mms)
        fail(source, where + ": needs the key manufactured (the exact solution "
                             "to take it from)");
      if (bc[key] != "exact" and mms)
        fail(source, where + ": with a manufactured solution the Dirichlet data "
                             "are the exact solution's: use \"exact\"");
    }
    for (const char* key : {"traction", "surface_charge", "spring"})
      if (mms and bc.contains(key))
        fail(source, "boundaries." + name + "." + key + ": " + unused);
  }
  if (mms)
    for (const auto& [name, bc] : cfg["boundaries"].items())
      if (const json* block = contact_block(cfg, bc); block and !paper_foundation(cfg, bc))
        fail(source, (bc["contact"].is_object() ? "boundaries." + name + ".contact" : "contact")
                         + ": a manufactured solution's contact is the paper's foundation "
                           "(\"contact\": true, the top-level block with c_p and gap, penalty)");
  if (mms and cfg.contains("contact") and cfg["contact"].value("gap", json()).is_string())
    fail(source, "contact.gap = " + fmt(cfg["contact"]["gap"])
                     + ": a manufactured solution's gap is a number (its forms have no "
                       "fields of data given by expressions)");
}

/// The Voigt length of a material's tensors (elastic's; 3D 6, plane 3,
/// axisymmetric 4) and their vector dimension, each tensor checked against
/// it: one material, one shape
std::pair<std::size_t, std::size_t> material_shape(const json& mat, const std::string& path,
                                                   const std::string& source)
{
  const std::size_t strains = mat["elastic"].size(), dim = strains == 6 ? 3 : 2;
  const auto shape = [](const json& m)
  { return std::to_string(m.size()) + "x" + std::to_string(m[0].size()); };
  const std::map<std::string, std::pair<std::size_t, std::size_t>> expected = {
      {"viscosity", {strains, strains}},
      {"piezoelectric", {dim, strains}},
      {"permittivity", {dim, dim}}};
  for (const auto& [key, rc] : expected)
    if (mat.contains(key) and (mat[key].size() != rc.first or mat[key][0].size() != rc.second))
      fail(source, join(path, key) + ": a " + shape(mat[key]) + " matrix with a "
                       + shape(mat["elastic"]) + " elastic tensor: one material's tensors "
                       + "have one shape (" + std::to_string(rc.first) + "x"
                       + std::to_string(rc.second) + " here)");
  return {strains, dim};
}

// A material: a preset with one orientation, or explicit tensors with a
// viscosity or a relaxation time
void check_material(const json& spec, const std::string& path, const std::string& source)
{
  const std::vector<std::string> tensors = {"elastic", "viscosity", "piezoelectric", "permittivity"};
  if (spec.contains("preset"))
  {
    for (const auto& k : tensors)
      if (spec.contains(k))
        fail(source, join(path, k) + ": not used with a preset (its tensors come from "
                                     "config/materials.json; the viscosity from relaxation_time)");
    if (spec.contains("poling") == spec.contains("euler"))
      fail(source, path + ".preset = " + fmt(spec["preset"]) + ": give its orientation, "
                   + "either poling (the direction of its axis 3) or euler (angles), not both");
    if (spec.contains("poling"))
    {
      const auto p = spec["poling"].get<std::vector<double>>();
      double n2 = 0.0, largest = 0.0;
      for (double x : p)
        largest = std::max(largest, std::abs(x));
      for (double x : p)
        n2 += (x / largest) * (x / largest);
      if (largest == 0.0 or !std::isfinite(n2))
        fail(source, path + ".poling = " + fmt(spec["poling"]) + ": must be a nonzero direction");
    }
    return;
  }
  for (const char* k : {"poling", "euler"})
    if (spec.contains(k))
      fail(source, join(path, k) + ": only with a preset (explicit tensors are in the mesh frame)");
  for (const char* k : {"elastic", "piezoelectric", "permittivity"})
    if (!spec.contains(k))
      fail(source, join(path, k) + ": missing required key (or give a preset)");
  if (spec.contains("viscosity") == spec.contains("relaxation_time"))
    fail(source, join(path, "viscosity") + (spec.contains("viscosity")
                                               ? ": give viscosity or relaxation_time, not both"
                                               : ": missing required key (or relaxation_time)"));
  check_spd(spec["permittivity"].get<Matrix>(), join(path, "permittivity"), source,
            "permittivity must be positive definite (2.14c); the paper's Table "
            "2 prints -beta, use +8.3 eps0 and +8.8 eps0");
  if (spec.contains("viscosity"))
    check_spd(spec["viscosity"].get<Matrix>(), join(path, "viscosity"), source,
              "viscosity must be positive definite (2.11c)");
  check_symmetric(spec["elastic"].get<Matrix>(), join(path, "elastic"), source);
  // one shape for all of a material's tensors (the formulation's fit is
  // checked once the mesh's dimension is known: check_dimension)
  material_shape(spec, path, source);
}

// The potential is known only up to a constant unless some boundary holds
// it: the electric block of the Jacobian would be singular (a floating
// electrode's capacitance too)
void check_electrodes(const json& cfg, const std::string& source)
{
  std::string floating;
  bool grounded = false;
  for (const auto& [name, bc] : cfg["boundaries"].items())
  {
    grounded = grounded or bc.contains("potential");
    if (bc.contains("floating") and floating.empty())
      floating = name;
  }
  if (!floating.empty() and cfg.contains("manufactured"))
    fail(source, join("boundaries", floating) + ".floating: not with a manufactured solution "
                                                "(its Dirichlet data are the exact solution's)");
  if (grounded)
    return;
  if (floating.empty())
    fail(source, "boundaries: none has a potential, so phi is known only up to a constant "
                 "(ground an electrode: potential 0)");
  fail(source, join("boundaries", floating) + ".floating: no boundary has a prescribed "
               "potential, so the floating one is known only up to a constant (ground an "
               "electrode: potential 0)");
}

/// The mesh keys its type needs, and none it does not use
void check_mesh_keys(const json& mesh, const std::string& source)
{
  const std::string type = mesh["type"];
  const std::map<std::string, std::vector<std::string>> needed_by_type
      = {{"unit_square", {"n"}}, {"box", {"n", "size"}}, {"gmsh", {"geometry", "size"}},
         {"xdmf", {"path"}}, {"msh", {"path"}}, {"dolfinx", {}}};
  const auto& needed = needed_by_type.at(type);
  for (const auto& k : needed)
    if (!mesh.contains(k))
      fail(source, "mesh." + k + ": missing required key for mesh.type \""
                       + type + "\"");
  for (const auto& [k, _] : mesh.items())
    if (k != "type" and (k != "diagonal" or type != "unit_square")
        and std::find(needed.begin(), needed.end(), k) == needed.end())
      fail(source, "mesh." + k + ": not used with mesh.type \"" + type + "\"");
}

/// One material for the body, or one per region
void check_materials(const json& cfg, const std::string& source)
{
  if (cfg.contains("material") == cfg.contains("regions"))
    fail(source, cfg.contains("material")
                     ? "regions: give either material (one for the whole body) or regions, not both"
                     : "material: missing (or regions: one material per named cell group)");
  if (cfg.contains("material"))
    check_material(cfg["material"], "material", source);
  else
    for (const auto& [name, spec] : cfg["regions"].items())
      check_material(spec, join("regions", name), source);
}

/// The conditions one boundary combines
/// A contact block's own rules (path: where it is), the dimension aside
void check_contact_block(const json& block, const std::string& path, const std::string& source)
{
  const bool obstacle = block.contains("obstacle");
  const bool nitsche = block.value("method", "penalty") == "nitsche";
  if (obstacle)
  {
    const json& o = block["obstacle"];
    const int kinds = o.contains("plane") + o.contains("sphere") + o.contains("cylinder");
    if (kinds != 1)
      fail(source, join(path, "obstacle") + " = " + fmt(o)
                       + ": give exactly one of plane, sphere, cylinder");
    for (const auto& [kind, key] : {std::pair{"plane", "normal"}, {"cylinder", "axis"}})
      if (o.contains(kind))
      {
        const json& v = o[kind][key];
        if (std::all_of(v.begin(), v.end(), [](const json& c) { return c == 0.0; }))
          fail(source, join(path, std::string("obstacle.") + kind + "." + key) + " = " + fmt(v)
                           + ": a direction cannot be zero");
      }
    if (block.contains("gap"))
      fail(source, join(path, "gap") + ": the obstacle's geometry gives the gap (gap is the "
                                       "paper's foundation's, without an obstacle)");
  }
  else if (!block.contains("gap"))
    fail(source, join(path, "gap") + ": missing required key (without an obstacle the "
                                     "foundation is the paper's: the boundary offset by gap)");
  if (!nitsche and !block.contains("c_p"))
    fail(source, join(path, "c_p") + ": missing required key (the penalty method's stiffness; "
                                     "or \"method\": \"nitsche\")");
  if (nitsche and block.contains("c_p"))
    fail(source, join(path, "c_p") + ": the penalty method's (the method is nitsche: its "
                                     "parameter is gamma)");
  for (const char* key : {"gamma", "theta"})
    if (!nitsche and block.contains(key))
      fail(source, join(path, key) + ": Nitsche's method's (give \"method\": \"nitsche\")");
}

void check_boundary(const json& cfg, const std::string& name, const json& bc,
                    const std::string& source)
{
  const std::string where = join("boundaries", name);
  const bool contact = contact_block(cfg, bc) != nullptr;
  if (bc.value("contact", json()) == true and !cfg.contains("contact"))
    fail(source, "contact: missing: " + where + " has \"contact\": true, which needs the "
                 "top-level contact block (c_p and gap, or an obstacle)");
  if (bc.contains("contact") and bc["contact"].is_object())
    check_contact_block(bc["contact"], join(where, "contact"), source);
  if (bc.contains("displacement") and (bc.contains("traction") or contact))
    fail(source, where + ": a clamped boundary (displacement) cannot also "
                         "carry traction or contact");
  if (bc.contains("traction") and contact)
    fail(source, where + ": traction and contact are exclusive");
  if (bc.contains("potential") and bc.contains("surface_charge"))
    fail(source, where + ": potential and surface_charge are exclusive");
  for (const char* other : {"potential", "surface_charge"})
    if (bc.contains("floating") and bc.contains(other))
      fail(source, where + ": floating and " + other + " are exclusive (a floating "
                           "electrode's potential is an unknown, its charge is floating.charge)");
}

/// Frictionless contact pushes only along the normal: without a clamped
/// boundary or a bed that resists both along and across its normal, the body
/// can slide and the Jacobian is singular
void check_held(const json& boundaries, const std::string& source)
{
  for (const auto& [name, bc] : boundaries.items())
  {
    const json* bed = bc.contains("spring") ? &bc["spring"] : nullptr;
    if (bc.contains("displacement")
        or (bed and (*bed)["normal"].get<double>() > 0
            and (*bed)["tangential"].get<double>() > 0))
      return;
  }
  fail(source, "boundaries: none has a displacement condition (or a spring bed with both "
               "stiffnesses): with frictionless contact nothing holds the body against sliding");
}

bool analysis_at_end(const json& cfg)
{
  for (const auto& [_, block] : cfg["analysis"].items())
    return block.value("at", "start") == "end";
  return false;
}

/// Where a datum has a history (or an expression of t), the first found
std::string timed_datum(const json& v, const std::string& path)
{
  if (v.is_object())
  {
    if (v.contains("history"))
      return join(path, "history");
    for (const auto& [k, sub] : v.items())
      if (auto p = timed_datum(sub, join(path, k)); !p.empty())
        return p;
  }
  if (v.is_array())
    for (std::size_t i = 0; i < v.size(); ++i)
      if (auto p = timed_datum(v[i], path + "[" + std::to_string(i) + "]"); !p.empty())
        return p;
  if (v.is_string())
    try
    {
      if (SpaceTimeExpression(v.get<std::string>()).uses_time())
        return path;
    }
    catch (const std::invalid_argument&) // a word ("nitsche"), not an expression
    {
    }
  return "";
}

/// A dynamic analysis: one kind; every material has a density; harmonic
/// data are amplitudes (no history), over a band that holds frequencies
void check_analysis(const json& cfg, const std::string& source)
{
  if (!cfg.contains("analysis"))
    return;
  const json& a = cfg["analysis"];
  if (a.contains("modal") == a.contains("harmonic"))
    fail(source, std::string("analysis: ") + (a.empty() ? "give modal or harmonic"
                                                         : "give modal or harmonic, not both"));
  if (cfg.contains("manufactured"))
    fail(source, "analysis: not with a manufactured solution (its loads are the exact "
                 "solution's, not a device's)");
  const auto has_density = [&](const json& m, const std::string& path)
  {
    if (!m.contains("density") and !m.contains("preset"))
      fail(source, join(path, "density") + ": missing: a dynamic analysis needs the mass "
                                           "density of each material (kg/m^3)");
  };
  if (cfg.contains("material"))
    has_density(cfg["material"], "material");
  else
    for (const auto& [name, m] : cfg["regions"].items())
      has_density(m, join("regions", name));
  if (!a.contains("harmonic"))
    return;
  const json& f = a["harmonic"]["frequencies"];
  if (f.is_object())
  {
    const double start = f["start"], stop = f["stop"];
    if (stop < start or (stop == start and f["points"].get<int>() > 1))
      fail(source, "analysis.harmonic.frequencies: the band " + fmt_g(start) + " to " + fmt_g(stop)
                       + " Hz is empty (stop > start, or one point)");
    if (f["spacing"] == "log" and start <= 0.0)
      fail(source, "analysis.harmonic.frequencies.start = " + fmt_g(start)
                       + ": a log spacing starts above 0 Hz");
  }
  for (const char* group : {"boundaries", "loads", "contact"})
    if (cfg.contains(group))
      if (auto p = timed_datum(cfg[group], group); !p.empty())
        fail(source, p + ": a harmonic analysis takes each datum's value as its complex "
                         "amplitude (phase 0): no history, no expression of t");
}

/// The rules across keys, once each key passed its own (Check)
void check_semantics(const json& cfg, const std::string& source)
{
  check_mesh_keys(cfg["mesh"], source);
  check_materials(cfg, source);
  if (cfg.contains("contact"))
    check_contact_block(cfg["contact"], "contact", source);
  for (const auto& [name, bc] : cfg["boundaries"].items())
    check_boundary(cfg, name, bc, source);
  if (!cfg.contains("analysis") or analysis_at_end(cfg))
    check_held(cfg["boundaries"], source); // a free body's modes: rigid ones at 0 Hz
  check_electrodes(cfg, source);
  check_manufactured(cfg, source);
  check_analysis(cfg, source);
}

/// A component of a validated datum: a number, or an expression (parsed
/// again: the config was checked, so it parses)
Value value_from(const json& v)
{
  Value out;
  if (v.is_string())
    out.expression = std::make_shared<const SpaceTimeExpression>(v.get<std::string>());
  else
    out.number = v.get<double>();
  return out;
}

/// Whether a datum's value holds an expression (it varies in space)
bool varies(const json& v)
{
  if (v.is_array())
    return std::any_of(v.begin(), v.end(), [](const json& c) { return varies(c); });
  return v.is_string();
}

/// The value of a datum that may be timed ({"value": ..., "history": ...})
const json& value_of(const json& datum)
{
  return datum.is_object() and datum.contains("value") ? datum["value"] : datum;
}

History history_of(const json& datum)
{
  History h;
  if (!(datum.is_object() and datum.contains("history")))
    return h;
  const json& j = datum["history"];
  if (j.contains("ramp"))
  {
    h.kind = History::Kind::ramp;
    h.ramp_time = j["ramp"].get<double>();
  }
  else if (j.contains("sine"))
  {
    h.kind = History::Kind::sine;
    h.frequency = j["sine"]["frequency"].get<double>();
    h.phase = j["sine"]["phase"].get<double>();
  }
  else
  {
    h.kind = History::Kind::table;
    for (const auto& row : j["table"])
      h.table.emplace_back(row[0].get<double>(), row[1].get<double>());
  }
  return h;
}

bool is_index(const std::string& s, const json& node)
{
  return node.is_array() and !s.empty() and s.size() < 10
         and std::all_of(s.begin(), s.end(), ::isdigit) and std::stoul(s) < node.size();
}

/// The value of `--set KEY=RAW`: JSON if it is JSON (within the limits of
/// all JSON input), else the bare word as a string (`mumps`)
json override_value(const std::string& key, const std::string& raw, const std::string& source)
{
  const json value = json::parse(raw, nullptr, false);
  const bool looks_like_json
      = !raw.empty() and std::string("[{\"-0123456789").find(raw[0]) != std::string::npos;
  if (value.is_discarded() and !looks_like_json)
    return raw;
  return parse_json(raw, printable(source, 200) + ": --set " + key, max_config_bytes);
}

void apply_override(json& cfg, const std::string& text,
                    const std::string& source)
{
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    fail(source, "--set '" + printable(text) + "': expected key.path=value");
  std::string key = text.substr(0, eq);
  key.erase(0, key.find_first_not_of(" \t"));
  key.erase(key.find_last_not_of(" \t") + 1);
  if (key.empty() or key.front() == '.' or key.back() == '.'
      or key.find("..") != std::string::npos)
    fail(source, "--set '" + printable(text) + "': expected key.path=value");
  const json value = override_value(printable(key), text.substr(eq + 1), source);

  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string p; std::getline(ss, p, '.');)
    parts.push_back(p);
  json* node = &cfg;
  std::string where;
  for (std::size_t d = 0; d + 1 < parts.size(); ++d)
  {
    where = join(where, parts[d]);
    if (is_index(parts[d], *node))
      node = &(*node)[std::stoul(parts[d])];
    else if (node->is_object())
    {
      if (!node->contains(parts[d]))
        (*node)[parts[d]] = json::object();
      node = &(*node)[parts[d]];
    }
    else
      fail(source, "--set " + printable(key) + ": '" + where + "' is not an object");
  }
  const std::string& last = parts.back();
  if (is_index(last, *node))
    (*node)[std::stoul(last)] = value;
  else if (node->is_object())
    (*node)[last] = value;
  else
    fail(source, "--set " + printable(key) + ": cannot set '" + printable(last) + "' here");
}
} // namespace

double History::factor(double t) const
{
  switch (kind)
  {
  case Kind::ramp:
    return std::min(t / ramp_time, 1.0);
  case Kind::sine:
    return std::sin(2.0 * M_PI * frequency * t + phase);
  case Kind::table:
  {
    if (t <= table.front().first)
      return table.front().second;
    if (t >= table.back().first)
      return table.back().second;
    const auto hi = std::upper_bound(table.begin(), table.end(), t,
                                     [](double x, const auto& row) { return x < row.first; });
    const auto lo = hi - 1;
    const double w = (t - lo->first) / (hi->first - lo->first);
    return (1 - w) * lo->second + w * hi->second;
  }
  default:
    return 1.0;
  }
}

std::string closest_key(const std::string& key,
                        const std::vector<std::string>& candidates)
{
  std::string best;
  std::size_t best_d = 0;
  for (const auto& c : candidates)
  {
    const std::size_t d = edit_distance(key, c);
    if (best.empty() or d < best_d or (d == best_d and c < best))
    {
      best = c;
      best_d = d;
    }
  }
  if (!best.empty() and best_d <= std::max<std::size_t>(1, key.size() / 3))
    return best;
  return "";
}

json load_config(const std::string& path,
                 const std::vector<std::string>& overrides)
{
  return configure(read_json_file(path), overrides, path);
}

json configure(json cfg, const std::vector<std::string>& overrides,
               const std::string& source)
{
  // before the overrides, whose messages would blame their keys
  if (!cfg.is_object())
    fail(source, std::string("the top level is ") + (cfg.is_array() ? "an " : "a ")
                     + cfg.type_name() + ": a config is one JSON object ({\"mesh\": ..., ...})");
  for (const auto& o : overrides)
    apply_override(cfg, o, source);
  const json& mesh = cfg.is_object() ? cfg.value("mesh", json()) : json();
  const json type = mesh.is_object() ? mesh.value("type", json()) : json();
  cfg = check(cfg, schema(), "", source,
              type == "unit_square" ? 2 : type == "box" ? 3 : 0);
  check_semantics(cfg, source);
  return cfg;
}

namespace
{
/// The formulation of a 2D mesh, and the shapes it takes for explicit
/// tensors: its reduced shape or the 3D one (which it reduces)
void check_formulation_of_materials(const json& cfg, const std::string& source)
{
  const std::string f = cfg["formulation"];
  const std::size_t reduced = f == "axisymmetric" ? 4 : 3;
  const auto check_one = [&](const json& mat, const std::string& path)
  {
    if (!mat.contains("elastic"))
      return;
    const auto [strains, _] = material_shape(mat, path, source);
    if (strains != reduced and strains != 6)
      fail(source, join(path, "elastic") + ": a " + std::to_string(strains) + "x"
                       + std::to_string(strains) + " matrix does not fit the " + f + " formulation: it takes "
                       + std::to_string(reduced) + "x" + std::to_string(reduced)
                       + " (reduced) or 6x6 (the 3D tensor, reduced by the formulation)");
  };
  if (cfg.contains("material"))
    check_one(cfg["material"], "material");
  if (cfg.contains("regions"))
    for (const auto& [name, mat] : cfg["regions"].items())
      check_one(mat, "regions." + name);
}
} // namespace

namespace
{
/// Every contact block of a config with its path: the top-level one and
/// the boundaries' own
std::vector<std::pair<std::string, json*>> contact_blocks(json& cfg)
{
  std::vector<std::pair<std::string, json*>> out;
  if (cfg.contains("contact"))
    out.emplace_back("contact", &cfg["contact"]);
  for (auto& [name, bc] : cfg["boundaries"].items())
    if (bc.contains("contact") and bc["contact"].is_object())
      out.emplace_back("boundaries." + name + ".contact", &bc["contact"]);
  return out;
}

/// The rules of obstacles that need the dimension and the formulation, and
/// Nitsche's defaults
void check_obstacles(json& cfg, int d, const std::string& source)
{
  const bool axisymmetric = cfg.value("formulation", "") == "axisymmetric";
  for (auto& [path, block] : contact_blocks(cfg))
  {
    if (block->value("method", "penalty") == "nitsche")
    {
      if (!block->contains("gamma"))
        (*block)["gamma"] = 10.0;
      if (!block->contains("theta"))
        (*block)["theta"] = 1;
    }
    if (!block->contains("obstacle"))
      continue;
    const json& o = (*block)["obstacle"];
    const std::string at = path + ".obstacle";
    if (o.contains("cylinder") and d != 3)
      fail(source, at + ".cylinder: a 3D obstacle (in 2D, a sphere is a circle: a cylinder "
                        "across the plane)");
    if (!axisymmetric)
      continue;
    if (o.contains("sphere") and o["sphere"]["center"][0] != 0.0)
      fail(source, at + ".sphere.center = " + fmt(o["sphere"]["center"])
                       + ": in axisymmetry a sphere is centred on the axis (r = 0)");
    if (o.contains("plane") and o["plane"]["normal"][0] != 0.0)
      fail(source, at + ".plane.normal = " + fmt(o["plane"]["normal"])
                       + ": in axisymmetry a plane is normal to the axis (other planes are cones)");
    if (o.contains("displacement") and value_of(o["displacement"])[0] != 0.0)
      fail(source, at + ".displacement = " + fmt(o["displacement"])
                       + ": in axisymmetry an obstacle moves along the axis (its r component is 0)");
  }
}
} // namespace

json check_dimension(const json& cfg_, int d, const std::string& source)
{
  json cfg = check(cfg_, schema(), "", source, d);
  check_obstacles(cfg, d, source);
  if (d == 3)
  {
    if (cfg.contains("formulation"))
      fail(source, "formulation: " + fmt(cfg["formulation"])
                       + ": a formulation of 2D meshes (the mesh is 3D)");
    return cfg;
  }
  if (!cfg.contains("formulation"))
    cfg["formulation"] = "plane_strain";
  check_formulation_of_materials(cfg, source);
  return cfg;
}

void bcast_error(std::string& error, MPI_Comm comm)
{
  int len = error.size();
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  error.resize(len);
  MPI_Bcast(error.data(), len, MPI_CHAR, 0, comm);
  if (!error.empty())
    throw ConfigError(error);
}

namespace
{
/// The frequencies of a harmonic analysis: a list, or a band
std::vector<double> frequencies_of(const json& f)
{
  if (f.is_array())
    return f.get<std::vector<double>>();
  const double start = f["start"], stop = f["stop"];
  const int n = f["points"];
  const bool log = f["spacing"] == "log";
  std::vector<double> out;
  for (int i = 0; i < n; ++i)
  {
    const double s = n == 1 ? 0.0 : double(i) / (n - 1);
    out.push_back(log ? start * std::pow(stop / start, s) : start + s * (stop - start));
  }
  return out;
}

AnalysisSettings analysis_settings(const json& cfg)
{
  AnalysisSettings a;
  if (!cfg.contains("analysis"))
    return a;
  const json& modal = cfg["analysis"].value("modal", json());
  const json& harmonic = cfg["analysis"].value("harmonic", json());
  const json& block = modal.is_null() ? harmonic : modal;
  a.kind = modal.is_null() ? AnalysisSettings::Kind::harmonic : AnalysisSettings::Kind::modal;
  a.at_end = block["at"] == "end";
  if (!modal.is_null())
  {
    a.modes = modal["modes"];
    if (modal.contains("target"))
      a.target = modal["target"].get<double>();
  }
  else
    a.frequencies = frequencies_of(harmonic["frequencies"]);
  return a;
}
} // namespace

RunSettings run_settings(const json& cfg)
{
  RunSettings s;
  s.T = cfg["time"]["T"].get<double>();
  s.steps = cfg["time"]["steps"].get<int>();
  const json& newton = cfg["solver"]["newton"];
  s.newton = {newton["rtol"].get<double>(), newton["atol"].get<double>(),
              newton["max_iterations"].get<int>(), newton["max_step_halvings"].get<int>()};
  s.reuse_factorisation = cfg["solver"]["reuse_factorisation"].get<bool>();
  s.linear = cfg["solver"]["linear"].get<std::string>() == "iterative" ? LinearSolver::iterative
                                                                       : LinearSolver::direct;
  s.symmetric = cfg["solver"]["symmetric"].get<std::string>() == "auto";
  for (const auto& [key, value] : cfg["solver"]["petsc_options"].items())
    s.petsc_options.emplace_back(key, value.is_string() ? value.get<std::string>()
                                                        : value.dump()); // numbers, bools
  for (const auto& p : cfg["probes"])
  {
    std::array<double, 3> x = {0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < p.size(); ++i)
      x[i] = p[i].get<double>();
    s.probes.push_back(x);
  }
  s.output = {cfg["output"]["xdmf"].get<bool>(), cfg["output"]["nodal"].get<std::string>()};
  std::map<std::string, json> sorted;
  for (const auto& [name, bc] : cfg["boundaries"].items())
    sorted[name] = bc;
  for (const auto& [name, bc] : sorted)
  {
    DirichletSettings d;
    d.boundary = name;
    if (bc.contains("displacement"))
    {
      if (bc["displacement"] == "exact")
        d.displacement_exact = true;
      else
      {
        d.displacement.emplace();
        for (const auto& c : value_of(bc["displacement"]))
          d.displacement->push_back(c.is_null() ? std::nullopt : std::optional(value_from(c)));
        d.displacement_history = history_of(bc["displacement"]);
      }
    }
    if (bc.contains("potential"))
    {
      if (bc["potential"] == "exact")
        d.potential_exact = true;
      else
      {
        d.potential = value_from(value_of(bc["potential"]));
        d.potential_history = history_of(bc["potential"]);
      }
    }
    if (bc.contains("floating"))
    {
      d.floating = true;
      d.charge = value_of(bc["floating"]["charge"]).get<double>();
      d.charge_history = history_of(bc["floating"]["charge"]);
    }
    if (d.displacement or d.displacement_exact or d.potential or d.potential_exact or d.floating)
      s.dirichlet.push_back(std::move(d));
  }
  s.analysis = analysis_settings(cfg);
  return s;
}

ModelSpec model_spec(const json& cfg)
{
  ModelSpec spec;
  spec.manufactured = cfg.contains("manufactured");
  spec.axisymmetric = cfg.value("formulation", "") == "axisymmetric";
  spec.linearised = cfg.contains("analysis");
  const auto note_expressions = [&](const json& entry, const std::string& prefix)
  {
    for (const auto& [key, value] : entry.items())
      if (varies(value_of(value))
          and std::find(spec.expression_keys.begin(), spec.expression_keys.end(), prefix + key)
                  == spec.expression_keys.end())
        spec.expression_keys.push_back(prefix + key);
  };
  for (const char* group : {"loads", "contact"})
    if (cfg.contains(group) and cfg[group].is_object())
      note_expressions(cfg[group], std::string(group) + ".");
  for (const auto& [_, bc] : cfg["boundaries"].items())
    note_expressions(bc, "");
  // (nested: an obstacle's displacement, a boundary's own block)
  for (const auto& [_, bc] : cfg["boundaries"].items())
    if (const json* block = contact_block(cfg, bc))
    {
      note_expressions(*block, "contact.");
      if (block->contains("obstacle"))
        note_expressions((*block)["obstacle"], "contact.obstacle.");
    }
  // (a summary written before "elements" existed has none: degree 1)
  const json elements = cfg.contains("elements") ? cfg["elements"] : json::object();
  const int degree = elements.value("degree", 1);
  spec.degrees = {elements.value("u", degree), elements.value("phi", degree)};
  for (const auto& [name, bc] : cfg["boundaries"].items())
  {
    if (paper_foundation(cfg, bc))
      spec.contact.push_back(name);
    else if (const json* block = contact_block(cfg, bc))
    {
      spec.obstacles.push_back(name);
      if (block->contains("obstacle"))
        spec.with_obstacle.push_back(name);
    }
    if (bc.contains("potential") or bc.contains("floating"))
      spec.electrodes.push_back(name);
    auto& keys = spec.boundary_keys[name];
    for (const auto& [key, _] : bc.items())
      keys.push_back(key);
  }
  return spec;
}

namespace
{
/// The value at a dotted key path below `node` (null if a part is missing)
const json* at_path(const json& node, const std::string& path)
{
  const json* at = &node;
  std::size_t begin = 0;
  while (begin <= path.size())
  {
    const std::size_t end = std::min(path.find('.', begin), path.size());
    const std::string part = path.substr(begin, end - begin);
    if (!at->is_object() or !at->contains(part))
      return nullptr;
    at = &(*at)[part];
    begin = end + 1;
  }
  return at;
}

/// The config entry that a group's keys are relative to, for one piece
/// (null: none, the Constants stay zero)
const json* entry_of(const json& cfg, const std::string& group, const std::string& piece)
{
  if (group == "shared")
    return &cfg;
  if (group == "material")
  {
    if (!cfg.contains("regions"))
      return &cfg["material"];
    return cfg["regions"].contains(piece) ? &cfg["regions"][piece] : nullptr;
  }
  return cfg["boundaries"].contains(piece) ? &cfg["boundaries"][piece] : nullptr;
}

/// The value of a datum's key for one piece (null: the config gives none).
/// A contact boundary's contact data ("contact." keys of the load group)
/// are in its own block or in the top-level one; the paper's foundation
/// has them in the shared data instead.
const json* datum_at(const json& cfg, const std::string& group, const std::string& piece,
                     const std::string& key)
{
  const json* entry = entry_of(cfg, group, piece);
  if (!entry or key.empty())
    return nullptr;
  const std::string prefix = "contact.";
  if (group == "load" and key.compare(0, prefix.size(), prefix) == 0)
  {
    const json* block = contact_block(cfg, *entry);
    return block and !paper_foundation(cfg, *entry) ? at_path(*block, key.substr(prefix.size()))
                                                     : nullptr;
  }
  return at_path(*entry, key);
}

/// Every (piece, Constants) of a group: "" for the shared ones
std::vector<std::pair<std::string, const ConstantMap*>> pieces(const Model& model,
                                                                const std::string& group)
{
  if (group == "shared")
    return {{"", &model.constants}};
  if (group != "material" and group != "load")
    throw std::logic_error("a Constant of an unknown group " + group);
  std::vector<std::pair<std::string, const ConstantMap*>> out;
  for (const auto& [piece, constants] : group == "material" ? model.materials : model.loads)
    out.emplace_back(piece, &constants);
  return out;
}

/// Fill a Constant from nested lists (row-major) or a number
void set_value(const ConstantMap& constants, const std::string& name, const json& value)
{
  auto& v = constants.at(name)->value;
  std::size_t i = 0;
  std::function<void(const json&)> walk = [&](const json& node)
  {
    if (node.is_array())
      for (const auto& item : node)
        walk(item);
    else
      v.at(i++) = node.get<double>();
  };
  walk(value);
  if (i != v.size())
    throw std::logic_error(name + ": " + std::to_string(i) + " values for a Constant of "
                           + std::to_string(v.size()));
}

void set_zero(const ConstantMap& constants)
{
  for (const auto& [_, c] : constants)
    std::fill(c->value.begin(), c->value.end(), 0.0);
}

} // namespace

void set_constants(const json& cfg, const Model& model)
{
  // a Constant no declaration names would silently stay zero
  for (const std::string group : {"shared", "material", "load"})
    for (const auto& [piece, constants] : pieces(model, group))
      for (const auto& [name, _] : *constants)
        if (std::none_of(model.sources.begin(), model.sources.end(),
                         [&](const ConstantSource& s) { return s.group == group and s.name == name; }))
          throw std::logic_error("the model's Constant " + name + " (" + group
                                 + ") has no source: the factory must list it in Model::sources");
  set_zero(model.constants);
  for (const auto& [_, m] : model.materials)
    set_zero(m);
  for (const auto& [_, l] : model.loads)
    set_zero(l);
  for (const auto& datum : model.sources)
    for (const auto& [piece, constants] : pieces(model, datum.group))
    {
      if (datum.group == "material" and !entry_of(cfg, datum.group, piece))
        throw std::logic_error("no material for region " + piece + " (check_names)");
      const json* value = datum_at(cfg, datum.group, piece, datum.key);
      if (value and !datum.flag.empty())
        set_value(*constants, datum.name, *value == datum.flag ? 1.0 : 0.0);
      else if (value and !varies(value_of(*value))) // else its field carries it (spatial_loads)
        set_value(*constants, datum.name, value_of(*value));
    }
  set_value(model.constants, "k", cfg["time"]["T"].get<double>() / cfg["time"]["steps"].get<double>());
}

std::vector<SpatialLoad> spatial_loads(const json& cfg, const Model& model)
{
  std::vector<SpatialLoad> out;
  for (const auto& datum : model.sources)
    if (!datum.field.empty())
      for (const auto& [piece, _] : pieces(model, datum.group))
        if (const json* value = datum_at(cfg, datum.group, piece, datum.key);
            value and varies(value_of(*value)))
          {
            SpatialDatum s;
            s.key = (datum.group == "load" ? "boundaries." + piece + "." : "") + datum.key;
            const json& v = value_of(*value);
            for (const auto& c : v.is_array() ? v : json::array({v}))
              s.components.push_back(value_from(c));
            s.history = history_of(*value);
            out.push_back({piece, datum.name, std::move(s)});
          }
  return out;
}

std::vector<TimedConstant> timed_constants(const json& cfg, const Model& model)
{
  std::vector<TimedConstant> out;
  for (const auto& datum : model.sources)
    if (datum.timed and datum.group != "material")
      for (const auto& [piece, _] : pieces(model, datum.group))
        if (const json* value = datum_at(cfg, datum.group, piece, datum.key))
          out.push_back({piece, datum.name, history_of(*value)});
  return out;
}
} // namespace piezocontact
