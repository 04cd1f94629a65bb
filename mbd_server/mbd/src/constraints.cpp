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

}  // namespace fsi::mbd::detail
