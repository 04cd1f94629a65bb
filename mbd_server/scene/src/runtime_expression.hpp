#pragma once
// A muParser expression in named variables that the multibody model evaluates while it runs:
// the tension of a NonlinearSpringDamper in `elongation`, `rate` and `t`, a PointForce or Torque
// in `t`
// (internal to the scene builder). Other names are the scene's numbers (`Geometry.T`), fixed
// when the expression is built. Copies share one parser; not thread-safe, like the model.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fsi::scene::detail {

// muParser's built-in functions: what every expression of a scene may call (the scene's own
// values and the expressions a run evaluates), for the messages that name them.
inline constexpr const char* kFunctionList =
    "sin cos tan asin acos atan sinh cosh tanh asinh acosh atanh exp ln log log2 log10 sqrt abs "
    "sign rint (to the nearest integer) min max sum avg";

class RuntimeExpression {
 public:
  // The value of a name that is not a variable (a path such as "Geometry.T"), or nullopt; the
  // second member says why not when the name is known but not a number ("" otherwise).
  struct Found {
    std::optional<double> value;
    std::string why_not;
  };
  using Lookup = std::function<Found(const std::string& name)>;

  // Throws fsi::Error (muParser's message, the variables allowed) when the text does not parse or
  // uses a name that is neither a variable nor found by `constants` (which is asked once per
  // name, while the text is parsed).
  RuntimeExpression(const std::string& text, const std::vector<std::string>& variables,
                    const Lookup& constants = {});

  // One value per variable, in the order given to the constructor.
  double operator()(const std::vector<double>& values) const;
  double operator()(double value) const;
  double operator()(double first, double second) const;
  double operator()(double first, double second, double third) const;

 private:
  struct Parser;
  std::shared_ptr<Parser> parser_;
};

}  // namespace fsi::scene::detail
