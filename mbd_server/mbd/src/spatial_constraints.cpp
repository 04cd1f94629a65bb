#include "spatial_constraints.hpp"

#include <utility>

namespace fsi::mbd::detail {

SpatialPointConstraint::SpatialPointConstraint(std::string description, SpatialPoint a,
                                               SpatialPoint b, int axis)
    : description_(std::move(description)), a_(a), b_(b), axis_(axis) {}

double SpatialPointConstraint::residual(double, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd&) const {
  return (a_.position(q) - b_.position(q))(axis_);
}

void SpatialPointConstraint::jacobian_row(double, const Eigen::VectorXd& q, RowRef row) const {
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(3, q.size());
  a_.add_jacobian(q, 1.0, jacobian);
  b_.add_jacobian(q, -1.0, jacobian);
  row += jacobian.row(axis_);
}

double SpatialPointConstraint::acceleration_remainder(double, const Eigen::VectorXd& q,
                                                      const Eigen::VectorXd& v) const {
  return (a_.acceleration_remainder(q, v) - b_.acceleration_remainder(q, v))(axis_);
}

void SpatialPointConstraint::add_force_derivative(double, const Eigen::VectorXd& q,
                                                  double multiplier,
                                                  Eigen::MatrixXd& derivative) const {
  const Eigen::Vector3d load = multiplier * Eigen::Vector3d::Unit(axis_);
  a_.add_load_derivative(q, load, derivative);
  b_.add_load_derivative(q, -load, derivative);
}

SpatialDistanceConstraint::SpatialDistanceConstraint(std::string description, SpatialPoint a,
                                                     SpatialPoint b, double length)
    : description_(std::move(description)), a_(a), b_(b), length_(length) {}

Eigen::MatrixXd SpatialDistanceConstraint::separation_jacobian(const Eigen::VectorXd& q) const {
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(3, q.size());
  b_.add_jacobian(q, 1.0, jacobian);
  a_.add_jacobian(q, -1.0, jacobian);
  return jacobian;
}

double SpatialDistanceConstraint::residual(double, const Eigen::VectorXd& q,
                                           const Eigen::VectorXd&) const {
  const Eigen::Vector3d d = b_.position(q) - a_.position(q);
  return (d.squaredNorm() - length_ * length_) / (2.0 * length_);
}

void SpatialDistanceConstraint::jacobian_row(double, const Eigen::VectorXd& q, RowRef row) const {
  const Eigen::Vector3d d = b_.position(q) - a_.position(q);
  row += d.transpose() * separation_jacobian(q) / length_;
}

double SpatialDistanceConstraint::acceleration_remainder(double, const Eigen::VectorXd& q,
                                                         const Eigen::VectorXd& v) const {
  const Eigen::Vector3d d = b_.position(q) - a_.position(q);
  const Eigen::Vector3d rate = b_.velocity(q, v) - a_.velocity(q, v);
  const Eigen::Vector3d remainder =
      b_.acceleration_remainder(q, v) - a_.acceleration_remainder(q, v);
  return (rate.squaredNorm() + d.dot(remainder)) / length_;
}

void SpatialDistanceConstraint::add_force_derivative(double, const Eigen::VectorXd& q,
                                                     double multiplier,
                                                     Eigen::MatrixXd& derivative) const {
  const Eigen::MatrixXd jacobian = separation_jacobian(q);
  const Eigen::Vector3d load = multiplier / length_ * (b_.position(q) - a_.position(q));
  derivative += multiplier / length_ * jacobian.transpose() * jacobian;
  b_.add_load_derivative(q, load, derivative);
  a_.add_load_derivative(q, -load, derivative);
}

Eigen::MatrixXd SpatialDirection::jacobian(const Eigen::VectorXd& q) const {
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(3, q.size());
  tip.add_jacobian(q, 1.0, j);
  base.add_jacobian(q, -1.0, j);
  return j;
}

PerpendicularityConstraint::PerpendicularityConstraint(std::string description, SpatialDirection a,
                                                       SpatialDirection b)
    : description_(std::move(description)), a_(a), b_(b) {}

double PerpendicularityConstraint::residual(double, const Eigen::VectorXd& q,
                                            const Eigen::VectorXd&) const {
  return a_.value(q).dot(b_.value(q));
}

void PerpendicularityConstraint::jacobian_row(double, const Eigen::VectorXd& q, RowRef row) const {
  row += b_.value(q).transpose() * a_.jacobian(q) + a_.value(q).transpose() * b_.jacobian(q);
}

double PerpendicularityConstraint::acceleration_remainder(double, const Eigen::VectorXd& q,
                                                          const Eigen::VectorXd& v) const {
  // d^2(d_a . d_b)/dt^2 = 2 d_a' . d_b' + d_b . d_a'' + d_a . d_b'', of which the acceleration-free
  // parts of d'' are the points' remainders.
  return 2.0 * a_.rate(q, v).dot(b_.rate(q, v)) + b_.value(q).dot(a_.acceleration_remainder(q, v)) +
         a_.value(q).dot(b_.acceleration_remainder(q, v));
}

void PerpendicularityConstraint::add_force_derivative(double, const Eigen::VectorXd& q,
                                                      double multiplier,
                                                      Eigen::MatrixXd& derivative) const {
  // G^T mu = mu (A^T d_b + B^T d_a), A = dd_a/dq, B = dd_b/dq: the product rule gives
  // mu (A^T B + B^T A) plus the load derivatives of mu d_b on a and mu d_a on b.
  const Eigen::MatrixXd ja = a_.jacobian(q);
  const Eigen::MatrixXd jb = b_.jacobian(q);
  derivative += multiplier * (ja.transpose() * jb + jb.transpose() * ja);
  a_.add_load_derivative(q, multiplier * b_.value(q), derivative);
  b_.add_load_derivative(q, multiplier * a_.value(q), derivative);
}

SpatialPointForce::SpatialPointForce(std::string description, SpatialPoint point,
                                     std::function<Eigen::Vector3d(double)> force)
    : description_(std::move(description)), point_(point), force_(std::move(force)) {}

void SpatialPointForce::add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                                  Eigen::VectorXd& force) const {
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(3, q.size());
  point_.add_jacobian(q, 1.0, jacobian);
  force += jacobian.transpose() * force_(time);
}

bool SpatialPointForce::add_jacobians(double time, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                                      Eigen::MatrixXd& force_by_position, Eigen::MatrixXd&) const {
  point_.add_load_derivative(q, force_(time), force_by_position);
  return true;
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
    : description_(std::move(description)), axes_offset_(axes_offset), torque_(std::move(torque)) {}

void SpatialTorque::add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                              Eigen::VectorXd& force) const {
  const Eigen::Vector3d tau = torque_(time);
  for (int k = 0; k < 3; ++k) {
    const int e = axes_offset_ + 3 * k;
    force.segment<3>(e) += 0.5 * tau.cross(q.segment<3>(e));
  }
}

bool SpatialTorque::add_jacobians(double time, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                  Eigen::MatrixXd& force_by_position, Eigen::MatrixXd&) const {
  const Eigen::Matrix3d block = 0.5 * cross_matrix(torque_(time));
  for (int k = 0; k < 3; ++k) {
    const int e = axes_offset_ + 3 * k;
    force_by_position.block<3, 3>(e, e) += block;
  }
  return true;
}

}  // namespace fsi::mbd::detail
