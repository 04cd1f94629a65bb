#pragma once
// A muParser expression in named variables that the multibody model evaluates while it runs:
// the tension of a NonlinearSpringDamper in `elongation` and `rate`, a PointForce or Torque in `t`
// (internal to the scene builder). Copies share one parser; not thread-safe, like the model.

#include <memory>
#include <string>
#include <vector>

namespace fsi::scene::detail {

class RuntimeExpression {
 public:
  // Throws fsi::Error (muParser's message, the variables allowed) when the text does not parse or
  // uses other names.
  RuntimeExpression(const std::string& text, const std::vector<std::string>& variables);

  // One value per variable, in the order given to the constructor.
  double operator()(const std::vector<double>& values) const;
  double operator()(double value) const;
  double operator()(double first, double second) const;

 private:
  struct Parser;
  std::shared_ptr<Parser> parser_;
};

}  // namespace fsi::scene::detail
