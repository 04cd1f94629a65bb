#include "body_point.hpp"

namespace fsi::mbd::detail {
namespace {

// The non-zero columns of a body's 2 x n_b point matrix, shifted to the body's offset. A column
// that is zero here may be non-zero at another q; the sparse Newton driver re-analyses a
// changed pattern.
void add_columns(const Eigen::MatrixXd& own, int offset, double sign, SparseColumns& out) {
  for (Eigen::Index j = 0; j < own.cols(); ++j) {
    if (own(0, j) != 0.0 || own(1, j) != 0.0)
      out.add(offset + static_cast<int>(j), sign * own.col(j));
  }
}

}  // namespace

Eigen::Vector2d BodyPoint::position(const Eigen::VectorXd& q) const {
  return on_ground() ? local_ : body_->position(block(q), local_);
}

Eigen::Vector2d BodyPoint::velocity(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  return on_ground() ? Eigen::Vector2d::Zero() : body_->velocity(block(q), block(v), local_);
}

void BodyPoint::add_jacobian(const Eigen::VectorXd& q, double sign, SparseColumns& jacobian) const {
  if (on_ground()) return;
  Eigen::MatrixXd own(2, body_->coordinate_count());
  body_->position_jacobian(block(q), local_, own);
  add_columns(own, offset_, sign, jacobian);
}

void BodyPoint::add_velocity_jacobian(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                      double sign, SparseColumns& jacobian) const {
  if (on_ground()) return;
  Eigen::MatrixXd own(2, body_->coordinate_count());
  body_->velocity_jacobian(block(q), block(v), local_, own);
  add_columns(own, offset_, sign, jacobian);
}

Eigen::Vector2d BodyPoint::acceleration_remainder(const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& v) const {
  if (on_ground()) return Eigen::Vector2d::Zero();
  Eigen::MatrixXd own(2, body_->coordinate_count());
  body_->velocity_jacobian(block(q), block(v), local_, own);
  return own * block(v);
}

void BodyPoint::add_load_derivative(const Eigen::VectorXd& q, const Eigen::Vector2d& force,
                                    MatrixSink& derivative) const {
  if (on_ground()) return;
  OffsetSink own(derivative, offset_, offset_);
  body_->add_point_load_derivative(block(q), local_, force, own);
}

void BodyPoint::add_load(const Eigen::VectorXd& q, const Eigen::Vector2d& force,
                         Eigen::VectorXd& generalised_force) const {
  if (on_ground()) return;
  body_->add_point_load(block(q), local_, force,
                        generalised_force.segment(offset_, body_->coordinate_count()));
}

}  // namespace fsi::mbd::detail
