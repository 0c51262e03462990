#include "expressions.h"

#include <muParser.h>
#include <numbers>
#include <stdexcept>

namespace piezocontact
{
namespace
{
/// muparser's "=" assigns to a variable: in a datum it is a slip for "=="
/// or nonsense, so it is refused (comparisons <=, >=, ==, != stay)
bool assigns(const std::string& text)
{
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == '=')
    {
      const char before = i > 0 ? text[i - 1] : ' ';
      const char after = i + 1 < text.size() ? text[i + 1] : ' ';
      if (after == '=')
      {
        ++i;
        continue;
      }
      if (before != '<' and before != '>' and before != '!')
        return true;
    }
  return false;
}
} // namespace

SpaceTimeExpression::SpaceTimeExpression(const std::string& text)
    : _text(text), _parser(std::make_unique<mu::Parser>())
{
  if (assigns(text))
    throw std::invalid_argument("\"=\" assigns in muparser: write == for a comparison");
  try
  {
    const char* names[4] = {"x", "y", "z", "t"};
    for (int i = 0; i < 4; ++i)
      _parser->DefineVar(names[i], &_vars[i]);
    _parser->DefineConst("pi", std::numbers::pi);
    _parser->SetExpr(text);
    int results = 0;
    _parser->Eval(results); // parses: syntax and unknown names are found here
    if (results != 1)
      throw std::invalid_argument(std::to_string(results)
                                  + " values separated by commas: a datum takes one");
    _uses_time = _parser->GetUsedVar().count("t") > 0;
  }
  catch (const mu::Parser::exception_type& e)
  {
    throw std::invalid_argument(e.GetMsg());
  }
}

SpaceTimeExpression::~SpaceTimeExpression() = default;

double SpaceTimeExpression::operator()(const std::array<double, 3>& x, double t) const
{
  _vars = {x[0], x[1], x[2], t};
  return _parser->Eval();
}
} // namespace piezocontact
