// Data that vary in space and time: a prescribed number may be replaced by
// an expression in x, y, z (m) and t (s), parsed and evaluated by muparser
// (Debian's libmuparser; no parser of ours). In axisymmetry x is r and y
// the axis; on a 2D mesh z = 0.
#pragma once

#include <array>
#include <memory>
#include <string>

namespace mu
{
class Parser;
}

namespace piezocontact
{
/// One expression of x, y, z and t; not copyable (muparser binds its
/// variables by address), shared as a const pointer
class SpaceTimeExpression
{
public:
  /// Parse `text`; throws std::invalid_argument with muparser's reason (or
  /// ours: one value, no assignment)
  explicit SpaceTimeExpression(const std::string& text);
  ~SpaceTimeExpression();
  SpaceTimeExpression(const SpaceTimeExpression&) = delete;
  SpaceTimeExpression& operator=(const SpaceTimeExpression&) = delete;

  /// The value at a point and a time (not thread-safe: one parser)
  double operator()(const std::array<double, 3>& x, double t) const;
  /// Whether t appears in it (else its values are computed once)
  bool uses_time() const { return _uses_time; }
  const std::string& text() const { return _text; }

private:
  std::string _text;
  std::unique_ptr<mu::Parser> _parser;
  mutable std::array<double, 4> _vars{}; // x, y, z, t: muparser reads them here
  bool _uses_time = false;
};

/// A prescribed value: a number, or an expression
struct Value
{
  double number = 0.0;
  std::shared_ptr<const SpaceTimeExpression> expression;

  bool varies() const { return expression != nullptr; }
  double at(const std::array<double, 3>& x, double t) const
  {
    return expression ? (*expression)(x, t) : number;
  }
};
} // namespace piezocontact
