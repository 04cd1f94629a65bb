#include "fsi/contact/quadrature.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace fsi::contact {
namespace {

TEST(GaussLegendre, IntegratesPolynomialsUpToDegreeTwoNMinusOneExactly) {
  for (int n = 1; n <= 5; ++n) {
    const auto rule = gauss_legendre(n);
    ASSERT_EQ(rule.size(), static_cast<std::size_t>(n));
    for (int degree = 0; degree <= 2 * n - 1; ++degree) {
      double sum = 0.0;
      for (const auto& q : rule)
        sum += q.weight * std::pow(q.position, degree);
      EXPECT_NEAR(sum, 1.0 / (degree + 1), 1e-15) << n << " points, degree " << degree;
    }
    // One degree more is not exact: the rule has exactly the order it claims.
    double sum = 0.0;
    for (const auto& q : rule)
      sum += q.weight * std::pow(q.position, 2 * n);
    EXPECT_GT(std::abs(sum - 1.0 / (2 * n + 1)), 1e-6) << n << " points";
  }
}

TEST(GaussLegendre, ThreePointRuleIsThesisTable41) {
  const auto rule = gauss_legendre(3);
  EXPECT_NEAR(rule[0].position, 0.5 * (1.0 - std::sqrt(3.0 / 5.0)), 1e-16);
  EXPECT_NEAR(rule[1].position, 0.5, 1e-16);
  EXPECT_NEAR(rule[2].position, 0.5 * (1.0 + std::sqrt(3.0 / 5.0)), 1e-16);
  // Table 4.1 weights 5/9, 8/9, 5/9 on [-1, 1] are halved on [0, 1].
  EXPECT_NEAR(rule[0].weight, 5.0 / 18.0, 1e-16);
  EXPECT_NEAR(rule[1].weight, 8.0 / 18.0, 1e-16);
}

TEST(GaussLegendre, RejectsUnavailableRules) {
  EXPECT_THROW(gauss_legendre(0), std::invalid_argument);
  EXPECT_THROW(gauss_legendre(6), std::invalid_argument);
}

}  // namespace
}  // namespace fsi::contact
