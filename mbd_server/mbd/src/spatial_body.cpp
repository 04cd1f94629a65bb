#include "spatial_body.hpp"

#include "fsi/common/error.hpp"

namespace fsi::mbd::detail {

void SpatialBody::planar_call() const {
  ::fsi::assertion_failed(
      "planar point function", __FILE__, __LINE__, __func__,
      "a planar point function was called on the spatial body '" + name() + "'");
}

Eigen::Vector3d SpatialPoint::position(const Eigen::VectorXd& q) const {
  return on_ground() ? local_ : body_->spatial_position(block(q), local_);
}

Eigen::Vector3d SpatialPoint::velocity(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  return on_ground() ? Eigen::Vector3d::Zero()
                     : body_->spatial_velocity(block(q), block(v), local_);
}

void SpatialPoint::add_jacobian(const Eigen::VectorXd& q, double sign,
                                SpatialColumns& jacobian) const {
  if (on_ground()) return;
  Eigen::MatrixXd own(3, body_->coordinate_count());
  body_->spatial_position_jacobian(block(q), local_, own);
  // The non-zero columns; one that is zero here may be non-zero at another q (the sparse Newton
  // driver re-analyses a changed pattern).
  for (Eigen::Index j = 0; j < own.cols(); ++j) {
    if (!own.col(j).isZero(0.0))
      jacobian.add(offset_ + static_cast<int>(j), sign * Eigen::Vector3d(own.col(j)));
  }
}

void SpatialPoint::add_velocity_jacobian(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                         double sign, SpatialColumns& jacobian) const {
  if (on_ground()) return;
  Eigen::MatrixXd own(3, body_->coordinate_count());
  body_->spatial_velocity_jacobian(block(q), block(v), local_, own);
  for (Eigen::Index j = 0; j < own.cols(); ++j) {
    if (!own.col(j).isZero(0.0))
      jacobian.add(offset_ + static_cast<int>(j), sign * Eigen::Vector3d(own.col(j)));
  }
}

Eigen::Vector3d SpatialPoint::acceleration_remainder(const Eigen::VectorXd& q,
                                                     const Eigen::VectorXd& v) const {
  if (on_ground()) return Eigen::Vector3d::Zero();
  Eigen::MatrixXd own(3, body_->coordinate_count());
  body_->spatial_velocity_jacobian(block(q), block(v), local_, own);
  return own * block(v);
}

void SpatialPoint::add_load_derivative(const Eigen::VectorXd& q, const Eigen::Vector3d& force,
                                       MatrixSink& derivative) const {
  if (on_ground()) return;
  OffsetSink own(derivative, offset_, offset_);
  body_->add_spatial_point_load_derivative(block(q), local_, force, own);
}

void SpatialPoint::add_load(const Eigen::VectorXd& q, const Eigen::Vector3d& force,
                            Eigen::VectorXd& generalised_force) const {
  if (on_ground()) return;
  body_->add_spatial_point_load(block(q), local_, force,
                                generalised_force.segment(offset_, body_->coordinate_count()));
}

}  // namespace fsi::mbd::detail
