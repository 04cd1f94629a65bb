#include <utility>

#include "constraint.hpp"

namespace fsi::mbd::detail {

CoordinateConstraint::CoordinateConstraint(std::string description, int coordinate_index,
                                           double value)
    : description_(std::move(description)), index_(coordinate_index), value_(value) {}

double CoordinateConstraint::residual(double, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd&) const {
  return q(index_) - value_;
}

void CoordinateConstraint::jacobian_row(double, const Eigen::VectorXd&, RowRef row) const {
  row(index_) = 1.0;
}

LinearCoordinateConstraint::LinearCoordinateConstraint(std::string description,
                                                       Eigen::VectorXi indices,
                                                       Eigen::VectorXd weights, double value)
    : description_(std::move(description)),
      indices_(std::move(indices)),
      weights_(std::move(weights)),
      value_(value) {}

double LinearCoordinateConstraint::residual(double, const Eigen::VectorXd& q,
                                            const Eigen::VectorXd&) const {
  double sum = -value_;
  for (Eigen::Index k = 0; k < indices_.size(); ++k)
    sum += weights_(k) * q(indices_(k));
  return sum;
}

void LinearCoordinateConstraint::jacobian_row(double, const Eigen::VectorXd&, RowRef row) const {
  for (Eigen::Index k = 0; k < indices_.size(); ++k)
    row(indices_(k)) += weights_(k);
}

VelocityConstraint::VelocityConstraint(std::string description, int coordinate_index,
                                       double velocity)
    : description_(std::move(description)), index_(coordinate_index), velocity_(velocity) {}

double VelocityConstraint::residual(double, const Eigen::VectorXd&,
                                    const Eigen::VectorXd& v) const {
  return v(index_) - velocity_;
}

void VelocityConstraint::jacobian_row(double, const Eigen::VectorXd&, RowRef row) const {
  row(index_) = 1.0;
}

PointConstraint::PointConstraint(std::string description, BodyPoint a, BodyPoint b, int axis)
    : description_(std::move(description)), a_(a), b_(b), axis_(axis) {}

double PointConstraint::residual(double, const Eigen::VectorXd& q, const Eigen::VectorXd&) const {
  return (a_.position(q) - b_.position(q))(axis_);
}

void PointConstraint::jacobian_row(double, const Eigen::VectorXd& q, RowRef row) const {
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(2, q.size());
  a_.add_jacobian(q, 1.0, jacobian);
  b_.add_jacobian(q, -1.0, jacobian);
  row += jacobian.row(axis_);
}

double PointConstraint::acceleration_remainder(double, const Eigen::VectorXd& q,
                                               const Eigen::VectorXd& v) const {
  return (a_.acceleration_remainder(q, v) - b_.acceleration_remainder(q, v))(axis_);
}

void PointConstraint::add_force_derivative(double, const Eigen::VectorXd& q, double multiplier,
                                           Eigen::MatrixXd& derivative) const {
  // G^T mu = (dr_a/dq - dr_b/dq)^T (mu e_axis): the derivative of a point load mu e_axis.
  const Eigen::Vector2d load = multiplier * Eigen::Vector2d::Unit(axis_);
  a_.add_load_derivative(q, load, derivative);
  b_.add_load_derivative(q, -load, derivative);
}

DistanceConstraint::DistanceConstraint(std::string description, BodyPoint a, BodyPoint b,
                                       double length)
    : description_(std::move(description)), a_(a), b_(b), length_(length) {}

Eigen::MatrixXd DistanceConstraint::separation_jacobian(const Eigen::VectorXd& q) const {
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(2, q.size());
  b_.add_jacobian(q, 1.0, jacobian);
  a_.add_jacobian(q, -1.0, jacobian);
  return jacobian;
}

double DistanceConstraint::residual(double, const Eigen::VectorXd& q,
                                    const Eigen::VectorXd&) const {
  const Eigen::Vector2d d = b_.position(q) - a_.position(q);
  return (d.squaredNorm() - length_ * length_) / (2.0 * length_);
}

void DistanceConstraint::jacobian_row(double, const Eigen::VectorXd& q, RowRef row) const {
  const Eigen::Vector2d d = b_.position(q) - a_.position(q);
  row += d.transpose() * separation_jacobian(q) / length_;
}

double DistanceConstraint::acceleration_remainder(double, const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& v) const {
  // d^2C/dt^2 = (|d'|^2 + d . d'') / length, d'' = (dd/dq) a + (remainder_b - remainder_a).
  const Eigen::Vector2d d = b_.position(q) - a_.position(q);
  const Eigen::Vector2d rate = b_.velocity(q, v) - a_.velocity(q, v);
  const Eigen::Vector2d remainder =
      b_.acceleration_remainder(q, v) - a_.acceleration_remainder(q, v);
  return (rate.squaredNorm() + d.dot(remainder)) / length_;
}

void DistanceConstraint::add_force_derivative(double, const Eigen::VectorXd& q, double multiplier,
                                              Eigen::MatrixXd& derivative) const {
  // G^T mu = (mu / length) (dd/dq)^T d: the product rule gives (mu / length) D^T D plus the
  // derivative of the point loads +-(mu / length) d at fixed d.
  const Eigen::MatrixXd jacobian = separation_jacobian(q);
  const Eigen::Vector2d load = multiplier / length_ * (b_.position(q) - a_.position(q));
  derivative += multiplier / length_ * jacobian.transpose() * jacobian;
  b_.add_load_derivative(q, load, derivative);
  a_.add_load_derivative(q, -load, derivative);
}

}  // namespace fsi::mbd::detail
