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
  Lookup constants;
  std::deque<double> constant_values;
  std::vector<std::string> problems;  // names neither a variable nor a number of the scene

  // muParser's variable factory: called once for each name the text uses that is not a variable.
  static double* on_name(const char* name, void* self) {
    Parser& parser = *static_cast<Parser*>(self);
    parser.constant_values.push_back(std::numeric_limits<double>::quiet_NaN());
    const Found found = parser.constants ? parser.constants(name) : Found{};
    if (found.value) {
      parser.constant_values.back() = *found.value;
    } else {
      parser.problems.push_back(found.why_not.empty()
                                    ? "'" + std::string(name) +
                                          "' is neither one of its variables nor a number of the "
                                          "scene"
                                    : found.why_not);
    }
    return &parser.constant_values.back();
  }
};

RuntimeExpression::RuntimeExpression(const std::string& text,
                                     const std::vector<std::string>& variables,
                                     const Lookup& constants)
    : parser_(std::make_shared<Parser>()) {
  std::string allowed;
  for (const std::string& name : variables)
    allowed += (allowed.empty() ? "" : ", ") + name;
  const std::string how = "write a muParser expression in " + allowed +
                          " (numbers, + - * / ^, ?: and the functions " + kFunctionList +
                          ") and the scene's numbers by their path from the top of the file (e.g. "
                          "Geometry.T)";
  try {
    // The constants and name characters of the scene language's own expressions.
    parser_->parser.DefineNameChars(
        "0123456789_abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.[]");
    parser_->parser.DefineConst("pi", std::numbers::pi);
    parser_->parser.DefineConst("e", std::numbers::e);
    for (const std::string& name : variables) {
      parser_->values.push_back(0.0);
      parser_->parser.DefineVar(name, &parser_->values.back());
    }
    parser_->constants = constants;
    parser_->parser.SetVarFactory(&Parser::on_name, parser_.get());
    parser_->parser.SetExpr(text);
    (void)parser_->parser.Eval();  // parses now: a mistake is a scene problem, not a step failure
    // The lookup may refer to the scene being built; parsing is over, so it is not kept.
    parser_->constants = nullptr;
  } catch (const mu::Parser::exception_type& error) {
    throw Error("the expression \"" + text + "\" is invalid: " + error.GetMsg(), "", how);
  }
  if (!parser_->problems.empty()) {
    std::string list;
    for (const std::string& problem : parser_->problems)
      list += (list.empty() ? "" : "; ") + problem;
    throw Error("the expression \"" + text + "\" is invalid: " + list, "", how);
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

double RuntimeExpression::operator()(double first, double second, double third) const {
  return (*this)(std::vector<double>{first, second, third});
}

}  // namespace fsi::scene::detail
