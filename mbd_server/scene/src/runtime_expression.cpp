#include "runtime_expression.hpp"

#include <muParser.h>

#include <deque>
#include <limits>
#include <numbers>

#include "fsi/common/error.hpp"

namespace fsi::scene::detail {

struct RuntimeExpression::Parser {
  mu::Parser parser;
  std::deque<double> values;  // stable addresses for muParser's variables
};

RuntimeExpression::RuntimeExpression(const std::string& text,
                                     const std::vector<std::string>& variables)
    : parser_(std::make_shared<Parser>()) {
  std::string allowed;
  for (const std::string& name : variables)
    allowed += (allowed.empty() ? "" : ", ") + name;
  try {
    // The constants of the scene language's own expressions.
    parser_->parser.DefineConst("pi", std::numbers::pi);
    parser_->parser.DefineConst("e", std::numbers::e);
    for (const std::string& name : variables) {
      parser_->values.push_back(0.0);
      parser_->parser.DefineVar(name, &parser_->values.back());
    }
    parser_->parser.SetExpr(text);
    (void)parser_->parser.Eval();  // parses now: a mistake is a scene problem, not a step failure
  } catch (const mu::Parser::exception_type& error) {
    throw Error("the expression \"" + text + "\" is invalid: " + error.GetMsg(), "",
                "write a muParser expression in " + allowed +
                    " (numbers, + - * / ^, sin, exp, sqrt, min, max, ...)");
  }
}

double RuntimeExpression::operator()(const std::vector<double>& values) const {
  FSI_ASSERT(values.size() == parser_->values.size(), "wrong number of expression variables");
  for (std::size_t k = 0; k < values.size(); ++k)
    parser_->values[k] = values[k];
  try {
    return parser_->parser.Eval();
  } catch (const mu::Parser::exception_type&) {
    return std::numeric_limits<double>::quiet_NaN();  // reported by the model as non-finite
  }
}

double RuntimeExpression::operator()(double value) const {
  return (*this)(std::vector<double>{value});
}

double RuntimeExpression::operator()(double first, double second) const {
  return (*this)(std::vector<double>{first, second});
}

}  // namespace fsi::scene::detail
