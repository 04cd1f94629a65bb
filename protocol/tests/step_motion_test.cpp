// The Hermite interpolant of the boundary's stage values (step_motion.hpp): exact at the nodes,
// exact for polynomials up to its degree, and bad nodes refused.

#include "fsi/protocol/step_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "error_text.hpp"
#include "fsi/common/error.hpp"

namespace fsi::protocol {
namespace {

// {0} and the nodes of Radau IIA with 3 stages.
const std::vector<double> kRadau3Nodes = {0.0, (4.0 - std::sqrt(6.0)) / 10.0,
                                          (4.0 + std::sqrt(6.0)) / 10.0, 1.0};

struct Evaluated {
  std::vector<double> positions, velocities;
};

Evaluated evaluate(const std::vector<double>& nodes, double h, double theta,
                   const std::vector<double>& values, const std::vector<double>& rates,
                   std::size_t width) {
  Evaluated out{std::vector<double>(width), std::vector<double>(width)};
  evaluate_step_motion(step_motion_weights(nodes, h, theta), values, rates, width, out.positions,
                       out.velocities);
  return out;
}

TEST(ProtocolStepMotion, TakesTheNodesValuesAndVelocitiesExactlyAtTheNodes) {
  const double h = 3.7e-4;
  const std::size_t width = 2;
  std::vector<double> values, rates;
  for (std::size_t i = 0; i < kRadau3Nodes.size(); ++i) {
    values.insert(values.end(), {0.1 + 0.37 * i, -2.0 / (i + 3.0)});
    rates.insert(rates.end(), {1.3 - 0.61 * i, 7.0 / (i + 1.0)});
  }
  for (std::size_t i = 0; i < kRadau3Nodes.size(); ++i) {
    const Evaluated at = evaluate(kRadau3Nodes, h, kRadau3Nodes[i], values, rates, width);
    for (std::size_t j = 0; j < width; ++j) {
      EXPECT_EQ(at.positions[j], values[i * width + j]) << "node " << i;
      EXPECT_EQ(at.velocities[j], rates[i * width + j]) << "node " << i;
    }
  }
}

// x(t) = sum_k a_k t^k over a step [t0, t0 + h]: exact up to degree 2 n - 1 for n nodes.
double polynomial(const std::vector<double>& a, double t) {
  double x = 0.0;
  for (std::size_t k = a.size(); k-- > 0;)
    x = x * t + a[k];
  return x;
}
double derivative(const std::vector<double>& a, double t) {
  double x = 0.0;
  for (std::size_t k = a.size(); k-- > 1;)
    x = x * t + static_cast<double>(k) * a[k];
  return x;
}

double worst_error(int degree) {
  std::vector<double> a;
  for (int k = 0; k <= degree; ++k)
    a.push_back(std::pow(-1.0, k) * (1.0 + 0.3 * k));
  const double t0 = 0.2, h = 0.5;
  std::vector<double> values, rates;
  for (double node : kRadau3Nodes) {
    values.push_back(polynomial(a, t0 + node * h));
    rates.push_back(derivative(a, t0 + node * h));
  }
  double worst = 0.0;
  for (int j = 0; j <= 20; ++j) {
    const double theta = j / 20.0, t = t0 + theta * h;
    const Evaluated at = evaluate(kRadau3Nodes, h, theta, values, rates, 1);
    worst = std::max({worst, std::abs(at.positions[0] - polynomial(a, t)),
                      std::abs(at.velocities[0] - derivative(a, t))});
  }
  return worst;
}

TEST(ProtocolStepMotion, ReproducesPolynomialsUpToDegreeTwiceTheNodesMinusOne) {
  for (int degree = 0; degree <= 7; ++degree)
    EXPECT_LT(worst_error(degree), 1e-12) << "degree " << degree;
  // One degree more is not reproduced: the test sees interpolation error.
  EXPECT_GT(worst_error(8), 1e-6);
}

TEST(ProtocolStepMotion, RefusesBadNodesThetaAndStepSize) {
  using test::contains;
  using test::error_of;
  EXPECT_TRUE(contains(error_of<Error>([] { step_motion_weights({}, 1.0, 0.5); }), "0 nodes"));
  const std::vector<double> twice = {0.0, 0.5, 0.5, 1.0};
  EXPECT_TRUE(contains(error_of<Error>([&] { step_motion_weights(twice, 1.0, 0.5); }),
                       "node 2 of the step motion is 0.5"));
  const std::vector<double> outside = {0.0, 1.5};
  EXPECT_TRUE(contains(error_of<Error>([&] { step_motion_weights(outside, 1.0, 0.5); }),
                       "distinct, ascending and in [0, 1]"));
  const std::vector<double> nan_node = {0.0, std::nan("")};
  EXPECT_TRUE(
      contains(error_of<Error>([&] { step_motion_weights(nan_node, 1.0, 0.5); }), "node 1"));
  EXPECT_TRUE(contains(error_of<Error>([] { step_motion_weights(kRadau3Nodes, 0.0, 0.5); }),
                       "must be positive"));
  EXPECT_TRUE(contains(error_of<Error>([] { step_motion_weights(kRadau3Nodes, 1.0, 1.01); }),
                       "outside the step"));
}

}  // namespace
}  // namespace fsi::protocol
