#include "tension_law.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace fsi::mbd::detail {

PiecewiseLinearTension::PiecewiseLinearTension(std::vector<Eigen::Vector2d> points, double damping)
    : points_(std::move(points)), damping_(damping) {}

std::size_t PiecewiseLinearTension::segment(double elongation) const {
  // Segment k joins points k and k + 1; upper_bound finds the first point beyond.
  const auto beyond =
      std::upper_bound(points_.begin(), points_.end(), elongation,
                       [](double x, const Eigen::Vector2d& point) { return x < point.x(); });
  const auto index = static_cast<std::size_t>(beyond - points_.begin());
  return std::clamp<std::size_t>(index, 1, points_.size() - 1) - 1;
}

double PiecewiseLinearTension::spring(double elongation) const {
  const std::size_t k = segment(elongation);
  const Eigen::Vector2d& left = points_[k];
  const Eigen::Vector2d& right = points_[k + 1];
  const double slope = (right.y() - left.y()) / (right.x() - left.x());
  return left.y() + slope * (elongation - left.x());
}

Tension PiecewiseLinearTension::at(double elongation, double rate, double) const {
  const std::size_t k = segment(elongation);
  const double slope =
      (points_[k + 1].y() - points_[k].y()) / (points_[k + 1].x() - points_[k].x());
  return {spring(elongation) + damping_ * rate, slope, damping_};
}

double PiecewiseLinearTension::energy(double elongation, double) const {
  // Exact: the trapezoidal rule between 0, the table points in between, and the elongation.
  std::vector<double> nodes = {0.0};
  const double low = std::min(0.0, elongation);
  const double high = std::max(0.0, elongation);
  for (const Eigen::Vector2d& point : points_) {
    if (point.x() > low && point.x() < high) nodes.push_back(point.x());
  }
  nodes.push_back(elongation);
  std::sort(nodes.begin(), nodes.end());
  double work = 0.0;
  for (std::size_t k = 0; k + 1 < nodes.size(); ++k)
    work += 0.5 * (spring(nodes[k]) + spring(nodes[k + 1])) * (nodes[k + 1] - nodes[k]);
  return elongation >= 0.0 ? work : -work;
}

UserTension::UserTension(std::function<double(double, double, double)> tension)
    : tension_(std::move(tension)) {}

Tension UserTension::at(double elongation, double rate, double time) const {
  // The step balances truncation (~step^2) against cancellation (~eps |T| / step); its floor,
  // 6e-6 m and 6e-6 m/s, keeps the cancellation small where elongation or rate are near zero
  // while the tension is not (a small rate term next to a large spring force). The partials only
  // steer Newton; the solution depends on the law alone.
  const double factor = std::cbrt(std::numeric_limits<double>::epsilon());
  const double de = factor * std::max(std::abs(elongation), 1.0);
  const double dr = factor * std::max(std::abs(rate), 1.0);
  return {
      tension_(elongation, rate, time),
      (tension_(elongation + de, rate, time) - tension_(elongation - de, rate, time)) / (2.0 * de),
      (tension_(elongation, rate + dr, time) - tension_(elongation, rate - dr, time)) / (2.0 * dr)};
}

double UserTension::energy(double elongation, double time) const {
  // Five-point Gauss-Legendre: exact for polynomial laws up to degree 9.
  constexpr std::array<double, 5> nodes = {0.0, -0.5384693101056831, 0.5384693101056831,
                                           -0.9061798459386640, 0.9061798459386640};
  constexpr std::array<double, 5> weights = {0.5688888888888889, 0.4786286704993665,
                                             0.4786286704993665, 0.2369268850561891,
                                             0.2369268850561891};
  const double half = 0.5 * elongation;
  double sum = 0.0;
  for (std::size_t k = 0; k < nodes.size(); ++k)
    sum += weights[k] * tension_(half * (1.0 + nodes[k]), 0.0, time);
  return half * sum;
}

}  // namespace fsi::mbd::detail
