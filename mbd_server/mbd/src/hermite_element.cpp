#include "hermite_element.hpp"

#include <cmath>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"

namespace fsi::mbd::detail {

GaussRule gauss_rule(int size) {
  GaussRule rule;
  rule.size = size;
  switch (size) {
    case 3: {
      const double x = std::sqrt(0.6);
      rule.points = {-x, 0.0, x};
      rule.weights = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
      break;
    }
    case 4: {
      const double inner = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(1.2));
      const double outer = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(1.2));
      const double w_inner = (18.0 + std::sqrt(30.0)) / 36.0;
      const double w_outer = (18.0 - std::sqrt(30.0)) / 36.0;
      rule.points = {-outer, -inner, inner, outer};
      rule.weights = {w_outer, w_inner, w_inner, w_outer};
      break;
    }
    case 5: {
      const double inner = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
      const double outer = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
      const double w_inner = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
      const double w_outer = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
      rule.points = {-outer, -inner, 0.0, inner, outer};
      rule.weights = {w_outer, w_inner, 128.0 / 225.0, w_inner, w_outer};
      break;
    }
    default:
      FSI_ASSERT(false, "no Gauss rule with this number of points");
  }
  return rule;
}

std::string elastic_line_problems(int elements, double axial_stiffness, double bending_stiffness,
                                  double mass_per_length, double axial_damping,
                                  double bending_damping) {
  auto number = [](double value) { return significant(value, 17); };
  std::string problems;
  if (elements < 1) problems += " element count " + std::to_string(elements) + " < 1;";
  if (!(std::isfinite(axial_stiffness) && axial_stiffness > 0.0)) {
    problems += " axial stiffness EA = " + number(axial_stiffness) + " is not positive;";
  }
  if (!(std::isfinite(bending_stiffness) && bending_stiffness > 0.0)) {
    problems += " bending stiffness EI = " + number(bending_stiffness) + " is not positive;";
  }
  if (!(std::isfinite(axial_damping) && axial_damping >= 0.0)) {
    problems += " axial damping = " + number(axial_damping) + " is negative;";
  }
  if (!(std::isfinite(bending_damping) && bending_damping >= 0.0)) {
    problems += " bending damping = " + number(bending_damping) + " is negative;";
  }
  if (!(std::isfinite(mass_per_length) && mass_per_length > 0.0)) {
    problems += " mass per length rho A = " + number(mass_per_length) + " is not positive;";
  }
  return problems;
}

HermiteShape hermite_shape(double x, double l) {
  const double u = x / l;
  const double u2 = u * u;
  const double u3 = u2 * u;
  HermiteShape s;
  s.value << 1.0 - 3.0 * u2 + 2.0 * u3, l * (u - 2.0 * u2 + u3), 3.0 * u2 - 2.0 * u3, l * (u3 - u2);
  s.first << 6.0 * (u2 - u) / l, 1.0 - 4.0 * u + 3.0 * u2, 6.0 * (u - u2) / l, 3.0 * u2 - 2.0 * u;
  s.second << (12.0 * u - 6.0) / (l * l), (6.0 * u - 4.0) / l, (6.0 - 12.0 * u) / (l * l),
      (6.0 * u - 2.0) / l;
  return s;
}

}  // namespace fsi::mbd::detail
