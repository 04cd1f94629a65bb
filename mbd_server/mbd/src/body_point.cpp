#include "body_point.hpp"

namespace fsi::mbd::detail {

Eigen::Vector2d BodyPoint::position(const Eigen::VectorXd& q) const {
  return on_ground() ? local_ : body_->position(block(q), local_);
}

Eigen::Vector2d BodyPoint::velocity(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  return on_ground() ? Eigen::Vector2d::Zero() : body_->velocity(block(q), block(v), local_);
}

void BodyPoint::add_jacobian(const Eigen::VectorXd& q, double sign,
                             Eigen::MatrixXd& jacobian) const {
  if (on_ground()) return;
  Eigen::MatrixXd own(2, body_->coordinate_count());
  body_->position_jacobian(block(q), local_, own);
  jacobian.middleCols(offset_, own.cols()) += sign * own;
}

void BodyPoint::add_velocity_jacobian(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                      double sign, Eigen::MatrixXd& jacobian) const {
  if (on_ground()) return;
  Eigen::MatrixXd own(2, body_->coordinate_count());
  body_->velocity_jacobian(block(q), block(v), local_, own);
  jacobian.middleCols(offset_, own.cols()) += sign * own;
}

Eigen::Vector2d BodyPoint::acceleration_remainder(const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& v) const {
  if (on_ground()) return Eigen::Vector2d::Zero();
  Eigen::MatrixXd own(2, body_->coordinate_count());
  body_->velocity_jacobian(block(q), block(v), local_, own);
  return own * block(v);
}

void BodyPoint::add_load_derivative(const Eigen::VectorXd& q, const Eigen::Vector2d& force,
                                    Eigen::MatrixXd& derivative) const {
  if (on_ground()) return;
  const int nb = body_->coordinate_count();
  body_->add_point_load_derivative(block(q), local_, force,
                                   derivative.block(offset_, offset_, nb, nb));
}

}  // namespace fsi::mbd::detail
