// The rule that accepts a step, written once. A step is accepted when
//  1. every field passed its test: the C++ loop's bounds each field's
//     residual and last update (fieldwise.h); the reference engine keeps a
//     test of its own, on the increments (the independence it checks by);
//  2. the floating electrodes' charge equations hold to Newton's rtol;
//  3. the forces balance: Newton's leftover on the free u dofs is at most
//     balance_tolerance of the forces in play (diagnostics.h). The scaled
//     field test alone can pass with newtons left over where one block
//     dwarfs the rest (a huge contact penalty).
// The C++ loop iterates until the rule holds; Record judges every step by it
// again, whichever engine solved it, and refuses one that breaks it: the
// balance recomputed from the residual at the accepted state, the fields and
// charges as the loop reported them (a loop that reports none breaks it).
#pragma once

#include <optional>
#include <string>

namespace piezocontact
{
class Problem;

/// The largest force_imbalance of an accepted step
constexpr double balance_tolerance = 1e-6;

struct Acceptance
{
  /// Every field passed its loop's test
  bool fields = false;
  /// Relative residual of the floating electrodes' charge equations (none
  /// without floating electrodes)
  std::optional<double> charges;
  /// force_imbalance at the state (diagnostics.h)
  double imbalance = 0.0;

  bool balanced() const { return imbalance <= balance_tolerance; }
  bool charges_hold(double rtol) const { return !charges or *charges <= rtol; }
  bool accepted(double rtol) const { return fields and charges_hold(rtol) and balanced(); }
};

/// ", forces unbalanced by X of the contact and support forces (...)" when
/// the forces do not balance, else "": the clause every failure message of
/// every engine carries; `c_p`: the contact penalty, if there is contact
std::string imbalance_clause(const Acceptance& acceptance, std::optional<double> c_p);

/// The same, with the problem's contact penalty
std::string imbalance_clause(const Acceptance& acceptance, const Problem& problem);

/// What of the rule a step its loop accepted breaks: "" if none
std::string broken_rule(const Acceptance& acceptance, double rtol, const Problem& problem);
} // namespace piezocontact
