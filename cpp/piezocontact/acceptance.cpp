#include "acceptance.h"
#include "problem.h"

#include <cstdio>

namespace piezocontact
{
namespace
{
std::string sci(double v)
{
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3e", v);
  return buf;
}
} // namespace

std::string imbalance_clause(const Acceptance& acceptance, std::optional<double> c_p)
{
  if (acceptance.balanced())
    return "";
  return ", forces unbalanced by " + sci(acceptance.imbalance)
         + " of the contact and support forces (too ill-conditioned for double precision?"
         + (c_p ? " contact.c_p = " + sci(*c_p) : std::string()) + ")";
}

std::string imbalance_clause(const Acceptance& acceptance, const Problem& problem)
{
  // with a contact boundary, the penalty is the usual culprit
  return imbalance_clause(acceptance,
                          problem.contact_pressure
                              ? std::optional(problem.model.constants.at("c_p")->value[0])
                              : std::nullopt);
}

std::string broken_rule(const Acceptance& acceptance, double rtol, const Problem& problem)
{
  std::string what;
  if (!acceptance.fields)
    what += ", its loop reported no field test passed";
  if (!acceptance.charges_hold(rtol))
    what += ", floating charges = " + sci(*acceptance.charges);
  what += imbalance_clause(acceptance, problem);
  return what.empty() ? what : what.substr(2);
}
} // namespace piezocontact
