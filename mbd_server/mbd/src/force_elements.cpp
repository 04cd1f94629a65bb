#include "force_elements.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace fsi::mbd::detail {

// ---- rotational spring-damper ----

RotationalSpringDamper::RotationalSpringDamper(std::string description, int angle_a, int angle_b,
                                               double rest_angle,
                                               std::shared_ptr<const TensionLaw> law)
    : SparseForceElement(std::move(description)),
      angle_a_(angle_a),
      angle_b_(angle_b),
      rest_angle_(rest_angle),
      law_(std::move(law)) {}

double RotationalSpringDamper::measured_force(double time, const Eigen::VectorXd& q,
                                              const Eigen::VectorXd& v) const {
  return -law_->at(twist(q), twist_rate(v), time).value;
}

void RotationalSpringDamper::add_force(double time, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& v, Eigen::VectorXd& force) const {
  const double torque = measured_force(time, q, v);
  if (angle_a_ >= 0) force(angle_a_) += torque;
  if (angle_b_ >= 0) force(angle_b_) -= torque;
}

bool RotationalSpringDamper::add_jacobian_entries(double time, const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& v,
                                                  MatrixSink& force_by_position,
                                                  MatrixSink& force_by_velocity) const {
  // The torque depends on phi_a - phi_b and its rate only: the pattern [-1 1; 1 -1] times the
  // law's partial derivatives.
  const Tension law = law_->at(twist(q), twist_rate(v), time);
  const std::array<std::pair<int, double>, 2> ends = {{{angle_a_, 1.0}, {angle_b_, -1.0}}};
  for (const auto& [row, row_sign] : ends) {
    for (const auto& [column, column_sign] : ends) {
      if (row < 0 || column < 0) continue;
      force_by_position.add(row, column, -row_sign * column_sign * law.by_elongation);
      force_by_velocity.add(row, column, -row_sign * column_sign * law.by_rate);
    }
  }
  return true;
}

double RotationalSpringDamper::potential_energy(double time, const Eigen::VectorXd& q) const {
  return law_->energy(twist(q), time);
}

// ---- tension laws ----

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

// ---- point-to-point force ----

PointToPointForce::PointToPointForce(std::string description, BodyPoint a, BodyPoint b,
                                     double rest_length, std::shared_ptr<const TensionLaw> law)
    : SparseForceElement(std::move(description)),
      a_(a),
      b_(b),
      rest_length_(rest_length),
      law_(std::move(law)) {}

double PointToPointForce::measured_force(double time, const Eigen::VectorXd& q,
                                         const Eigen::VectorXd& v) const {
  const Eigen::Vector2d d = b_.position(q) - a_.position(q);
  const double length = d.norm();
  const double rate = d.dot(b_.velocity(q, v) - a_.velocity(q, v)) / length;
  return law_->at(length - rest_length_, rate, time).value;
}

void PointToPointForce::add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                  Eigen::VectorXd& force) const {
  // +T e on a, -T e on b: Q = -(dd/dq)^T T e.
  const Eigen::Vector2d d = b_.position(q) - a_.position(q);
  const Eigen::Vector2d pull = measured_force(time, q, v) / d.norm() * d;
  a_.add_load(q, pull, force);
  b_.add_load(q, -pull, force);
}

bool PointToPointForce::add_jacobian_entries(double time, const Eigen::VectorXd& q,
                                             const Eigen::VectorXd& v,
                                             MatrixSink& force_by_position,
                                             MatrixSink& force_by_velocity) const {
  const Eigen::Vector2d d = b_.position(q) - a_.position(q);
  const double length = d.norm();
  const Eigen::Vector2d e = d / length;
  const Eigen::Vector2d u = b_.velocity(q, v) - a_.velocity(q, v);
  const Tension tension = law_->at(length - rest_length_, e.dot(u), time);
  // P = (I - e e^T) / l is de/dd; D = dd/dq; W = d(dd/dt)/dq at fixed v (non-zero columns).
  const Eigen::Matrix2d projector = (Eigen::Matrix2d::Identity() - e * e.transpose()) / length;
  SparseColumns separation, separation_rate;
  b_.add_jacobian(q, 1.0, separation);
  a_.add_jacobian(q, -1.0, separation);
  b_.add_velocity_jacobian(q, v, 1.0, separation_rate);
  a_.add_velocity_jacobian(q, v, -1.0, separation_rate);

  // l_q = e^T D; rate_q = u^T P D + e^T W; rate_v = e^T D; T_q = T_l l_q + T_r rate_q,
  // T_v = T_r rate_v. The pull T e: d/dq = e T_q + T P D, d/dv = e T_v; Q = -D^T (T e) plus
  // D^T differentiated at the fixed pull (point loads +pull on a, -pull on b).
  const Eigen::Vector2d projected_velocity = projector * u;
  SparseColumns pull_by_q, pull_by_v;
  for (std::size_t k = 0; k < separation.index.size(); ++k) {
    const Eigen::Vector2d& column = separation.column[k];
    const double tension_by_q =
        tension.by_elongation * e.dot(column) + tension.by_rate * projected_velocity.dot(column);
    pull_by_q.add(separation.index[k], e * tension_by_q + tension.value * projector * column);
    pull_by_v.add(separation.index[k], e * (tension.by_rate * e.dot(column)));
  }
  for (std::size_t k = 0; k < separation_rate.index.size(); ++k) {
    pull_by_q.add(separation_rate.index[k],
                  e * (tension.by_rate * e.dot(separation_rate.column[k])));
  }
  separation.add_transpose_product(force_by_position, Eigen::Matrix2d::Identity(), pull_by_q, -1.0);
  separation.add_transpose_product(force_by_velocity, Eigen::Matrix2d::Identity(), pull_by_v, -1.0);
  const Eigen::Vector2d pull = tension.value * e;
  a_.add_load_derivative(q, pull, force_by_position);
  b_.add_load_derivative(q, -pull, force_by_position);
  return true;
}

double PointToPointForce::potential_energy(double time, const Eigen::VectorXd& q) const {
  return law_->energy((b_.position(q) - a_.position(q)).norm() - rest_length_, time);
}

// ---- time-dependent loads ----

Torque::Torque(std::string description, int angle, std::function<double(double)> torque)
    : SparseForceElement(std::move(description)), angle_(angle), torque_(std::move(torque)) {}

void Torque::add_force(double time, const Eigen::VectorXd&, const Eigen::VectorXd&,
                       Eigen::VectorXd& force) const {
  force(angle_) += torque_(time);
}

// ---- spatial torque ----

namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return m;
}

}  // namespace

SpatialTorque::SpatialTorque(std::string description, int axes_offset,
                             std::function<Eigen::Vector3d(double)> torque)
    : SparseForceElement(std::move(description)),
      axes_offset_(axes_offset),
      torque_(std::move(torque)) {}

void SpatialTorque::add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                              Eigen::VectorXd& force) const {
  const Eigen::Vector3d tau = torque_(time);
  for (int k = 0; k < 3; ++k) {
    const int e = axes_offset_ + 3 * k;
    force.segment<3>(e) += 0.5 * tau.cross(q.segment<3>(e));
  }
}

bool SpatialTorque::add_jacobian_entries(double time, const Eigen::VectorXd&,
                                         const Eigen::VectorXd&, MatrixSink& force_by_position,
                                         MatrixSink&) const {
  const Eigen::Matrix3d block = 0.5 * cross_matrix(torque_(time));
  for (int k = 0; k < 3; ++k) {
    const int e = axes_offset_ + 3 * k;
    force_by_position.add_block(e, e, block);
  }
  return true;
}

}  // namespace fsi::mbd::detail
