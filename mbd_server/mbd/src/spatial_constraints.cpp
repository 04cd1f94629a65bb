#include "spatial_constraints.hpp"

#include <utility>

namespace fsi::mbd::detail {

SpatialColumns SpatialDirection::jacobian(const Eigen::VectorXd& q) const {
  SpatialColumns j;
  tip.add_jacobian(q, 1.0, j);
  base.add_jacobian(q, -1.0, j);
  return j;
}

PerpendicularityConstraint::PerpendicularityConstraint(std::string description, SpatialDirection a,
                                                       SpatialDirection b)
    : ConstraintRow(std::move(description)), a_(a), b_(b) {}

double PerpendicularityConstraint::residual(double, const Eigen::VectorXd& q,
                                            const Eigen::VectorXd&) const {
  return a_.value(q).dot(b_.value(q));
}

void PerpendicularityConstraint::add_jacobian_entries(double, const Eigen::VectorXd& q, int row,
                                                      MatrixSink& jacobian) const {
  a_.jacobian(q).add_row(jacobian, row, b_.value(q));
  b_.jacobian(q).add_row(jacobian, row, a_.value(q));
}

double PerpendicularityConstraint::acceleration_remainder(double, const Eigen::VectorXd& q,
                                                          const Eigen::VectorXd& v) const {
  // d^2(d_a . d_b)/dt^2 = 2 d_a' . d_b' + d_b . d_a'' + d_a . d_b'', of which the acceleration-free
  // parts of d'' are the points' remainders.
  return 2.0 * a_.rate(q, v).dot(b_.rate(q, v)) + b_.value(q).dot(a_.acceleration_remainder(q, v)) +
         a_.value(q).dot(b_.acceleration_remainder(q, v));
}

void PerpendicularityConstraint::add_force_derivative_entries(double, const Eigen::VectorXd& q,
                                                              double multiplier,
                                                              MatrixSink& derivative) const {
  // G^T mu = mu (A^T d_b + B^T d_a), A = dd_a/dq, B = dd_b/dq: the product rule gives
  // mu (A^T B + B^T A) plus the load derivatives of mu d_b on a and mu d_a on b.
  const SpatialColumns ja = a_.jacobian(q);
  const SpatialColumns jb = b_.jacobian(q);
  ja.add_transpose_product(derivative, Eigen::Matrix3d::Identity(), jb, multiplier);
  jb.add_transpose_product(derivative, Eigen::Matrix3d::Identity(), ja, multiplier);
  a_.add_load_derivative(q, multiplier * b_.value(q), derivative);
  b_.add_load_derivative(q, multiplier * a_.value(q), derivative);
}

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
