#include "coordinate_rows.hpp"

#include <cmath>
#include <utility>

namespace fsi::mbd::detail {

CoordinateConstraint::CoordinateConstraint(std::string description, int coordinate_index,
                                           double value)
    : SingleCoordinateRow(std::move(description), ConstraintLevel::Position, coordinate_index),
      value_(value) {}

double CoordinateConstraint::residual(double, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd&) const {
  return q(coordinate_index()) - value_;
}

LinearCoordinateConstraint::LinearCoordinateConstraint(std::string description,
                                                       Eigen::VectorXi indices,
                                                       Eigen::VectorXd weights, double value)
    : LinearConstraintRow(std::move(description)),
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

void LinearCoordinateConstraint::add_jacobian_entries(double, const Eigen::VectorXd&, int row,
                                                      MatrixSink& jacobian) const {
  for (Eigen::Index k = 0; k < indices_.size(); ++k)
    jacobian.add(row, indices_(k), weights_(k));
}

VelocityConstraint::VelocityConstraint(std::string description, int coordinate_index,
                                       double velocity)
    : SingleCoordinateRow(std::move(description), ConstraintLevel::Velocity, coordinate_index),
      velocity_(velocity) {}

double VelocityConstraint::residual(double, const Eigen::VectorXd&,
                                    const Eigen::VectorXd& v) const {
  return v(coordinate_index()) - velocity_;
}

namespace {

// d f/dt by a central difference with a step balancing truncation and rounding.
double time_derivative(const std::function<double(double)>& f, double time) {
  const double step = 1e-5 * (1.0 + std::abs(time));
  return (f(time + step) - f(time - step)) / (2.0 * step);
}

}  // namespace

PrescribedCoordinate::PrescribedCoordinate(std::string description, int coordinate_index,
                                           std::function<double(double)> position,
                                           std::function<double(double)> rate)
    : SingleCoordinateRow(std::move(description), ConstraintLevel::Position, coordinate_index),
      position_(std::move(position)),
      rate_(std::move(rate)) {}

double PrescribedCoordinate::residual(double time, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd&) const {
  return q(coordinate_index()) - position_(time);
}

double PrescribedCoordinate::acceleration_remainder(double time, const Eigen::VectorXd&,
                                                    const Eigen::VectorXd&) const {
  return -time_derivative(rate_, time);  // d^2C/dt^2 = a_i - s''(t)
}

TimeVelocityConstraint::TimeVelocityConstraint(std::string description, int coordinate_index,
                                               std::function<double(double)> velocity)
    : SingleCoordinateRow(std::move(description), ConstraintLevel::Velocity, coordinate_index),
      velocity_(std::move(velocity)) {}

double TimeVelocityConstraint::residual(double time, const Eigen::VectorXd&,
                                        const Eigen::VectorXd& v) const {
  return v(coordinate_index()) - velocity_(time);
}

double TimeVelocityConstraint::acceleration_remainder(double time, const Eigen::VectorXd&,
                                                      const Eigen::VectorXd&) const {
  return -time_derivative(velocity_, time);
}

RelativeAngleConstraint::RelativeAngleConstraint(std::string description, int angle_a, int angle_b,
                                                 double offset)
    : LinearConstraintRow(std::move(description)),
      angle_a_(angle_a),
      angle_b_(angle_b),
      offset_(offset) {}

double RelativeAngleConstraint::residual(double, const Eigen::VectorXd& q,
                                         const Eigen::VectorXd&) const {
  const double a = angle_a_ >= 0 ? q(angle_a_) : 0.0;
  const double b = angle_b_ >= 0 ? q(angle_b_) : 0.0;
  return a - b - offset_;
}

void RelativeAngleConstraint::add_jacobian_entries(double, const Eigen::VectorXd&, int row,
                                                   MatrixSink& jacobian) const {
  if (angle_a_ >= 0) jacobian.add(row, angle_a_, 1.0);
  if (angle_b_ >= 0) jacobian.add(row, angle_b_, -1.0);
}

}  // namespace fsi::mbd::detail
