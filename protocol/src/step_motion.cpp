// Hermite interpolation of the boundary's stage values over one structure step
// (step_motion.hpp).

#include "fsi/protocol/step_motion.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "fsi/common/error.hpp"

namespace fsi::protocol {

namespace {

constexpr std::size_t kMaxNodes = 8;

void check(std::span<const double> nodes, double step_size, double theta) {
  const char* where = "multi-rate boundary motion";
  const char* fix =
      "use matching fsi-server and fsi-client releases (the server sends the stage nodes of "
      "its Radau IIA or Lobatto IIIA tableau)";
  if (nodes.empty() || nodes.size() > kMaxNodes) {
    throw Error("the step motion has " + std::to_string(nodes.size()) + " nodes (1 to " +
                    std::to_string(kMaxNodes) + " allowed)",
                where, fix);
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const bool inside = nodes[i] >= 0.0 && nodes[i] <= 1.0;
    const bool ascending = i == 0 || nodes[i] > nodes[i - 1];
    if (!inside || !ascending) {
      char text[160];
      std::snprintf(text, sizeof text,
                    "node %zu of the step motion is %.17g: nodes must be distinct, ascending "
                    "and in [0, 1]",
                    i, nodes[i]);
      throw Error(text, where, fix);
    }
  }
  if (!(step_size > 0.0) || !std::isfinite(step_size)) {
    throw Error(
        "the step motion's step size is " + std::to_string(step_size) + " s; it must be positive",
        where, fix);
  }
  if (!(theta >= 0.0 && theta <= 1.0)) {
    throw Error("the step motion is evaluated at theta = " + std::to_string(theta) +
                    ", outside the step [0, 1]",
                where, "evaluate only within the step");
  }
}

}  // namespace

StepMotionWeights step_motion_weights(std::span<const double> nodes, double step_size,
                                      double theta) {
  check(nodes, step_size, theta);
  const std::size_t n = nodes.size();
  StepMotionWeights w;
  w.position_of_position.resize(n);
  w.position_of_velocity.resize(n);
  w.velocity_of_position.resize(n);
  w.velocity_of_velocity.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    // l_i(theta), l_i'(theta) by the product rule (finite at the nodes), and
    // d_i = l_i'(theta_i) = sum over m != i of 1 / (theta_i - theta_m), summed in the same order
    // as l_i' so that H_i'(theta_i) = 2 (l_i'(theta_i) - d_i) is exactly zero.
    double l = 1.0, dl = 0.0, d = 0.0;
    for (std::size_t m = 0; m < n; ++m) {
      if (m == i) continue;
      const double denominator = nodes[i] - nodes[m];
      d += 1.0 / denominator;
      double product = 1.0;
      for (std::size_t p = 0; p < n; ++p) {
        if (p == i || p == m) continue;
        product *= (theta - nodes[p]) / (nodes[i] - nodes[p]);
      }
      dl += product / denominator;
      l *= (theta - nodes[m]) / denominator;
    }
    const double offset = theta - nodes[i];
    const double l2 = l * l;
    const double h_i = (1.0 - 2.0 * d * offset) * l2;
    const double dh_i = -2.0 * d * l2 + (1.0 - 2.0 * d * offset) * 2.0 * l * dl;
    const double k_i = offset * l2;
    const double dk_i = l2 + offset * 2.0 * l * dl;
    w.position_of_position[i] = h_i;
    w.position_of_velocity[i] = step_size * k_i;
    w.velocity_of_position[i] = dh_i / step_size;
    w.velocity_of_velocity[i] = dk_i;
  }
  return w;
}

void evaluate_step_motion(const StepMotionWeights& weights, std::span<const double> values,
                          std::span<const double> rates, std::size_t width,
                          std::span<double> positions_out, std::span<double> velocities_out) {
  const std::size_t n = weights.position_of_position.size();
  FSI_ASSERT(values.size() == n * width && rates.size() == n * width,
             "node data do not match the weights");
  FSI_ASSERT(positions_out.size() == width && velocities_out.size() == width,
             "output does not match the width");
  for (std::size_t j = 0; j < width; ++j) {
    double x = 0.0, u = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double value = values[i * width + j], rate = rates[i * width + j];
      x += weights.position_of_position[i] * value + weights.position_of_velocity[i] * rate;
      u += weights.velocity_of_position[i] * value + weights.velocity_of_velocity[i] * rate;
    }
    positions_out[j] = x;
    velocities_out[j] = u;
  }
}

}  // namespace fsi::protocol
