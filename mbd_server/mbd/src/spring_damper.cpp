#include "spring_damper.hpp"

namespace fsi::mbd::detail {

SpringDamper::SpringDamper(BodyPoint a, BodyPoint b, double stiffness, double damping,
                           double rest_length)
    : a_(a), b_(b), stiffness_(stiffness), damping_(damping), rest_length_(rest_length) {}

double SpringDamper::tension(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  const Eigen::Vector2d d = b_.position(q) - a_.position(q);
  const double length = d.norm();
  const double rate = d.dot(b_.velocity(q, v) - a_.velocity(q, v)) / length;
  return stiffness_ * (length - rest_length_) + damping_ * rate;
}

double SpringDamper::potential_energy(const Eigen::VectorXd& q) const {
  const double stretch = (b_.position(q) - a_.position(q)).norm() - rest_length_;
  return 0.5 * stiffness_ * stretch * stretch;
}

void SpringDamper::add_force(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                             Eigen::VectorXd& force) const {
  const Eigen::Vector2d d = b_.position(q) - a_.position(q);
  const Eigen::Vector2d on_a = tension(q, v) * d / d.norm();
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(2, q.size());
  a_.add_jacobian(q, 1.0, jacobian);
  force += jacobian.transpose() * on_a;
  jacobian.setZero();
  b_.add_jacobian(q, 1.0, jacobian);
  force -= jacobian.transpose() * on_a;
}

bool SpringDamper::add_jacobians(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                 Eigen::MatrixXd& force_by_position,
                                 Eigen::MatrixXd& force_by_velocity) const {
  const int n = static_cast<int>(q.size());
  const Eigen::Vector2d d = b_.position(q) - a_.position(q);
  const double length = d.norm();
  const Eigen::Vector2d e = d / length;
  const Eigen::Vector2d relative_velocity = b_.velocity(q, v) - a_.velocity(q, v);
  const Eigen::Matrix2d transverse = (Eigen::Matrix2d::Identity() - e * e.transpose()) / length;
  const double tension_now =
      stiffness_ * (length - rest_length_) + damping_ * e.dot(relative_velocity);

  // D = dd/dq, W = d(dd/dt)/dq at fixed v; de/dq = transverse D.
  Eigen::MatrixXd jacobian_a = Eigen::MatrixXd::Zero(2, n), jacobian_b = jacobian_a;
  a_.add_jacobian(q, 1.0, jacobian_a);
  b_.add_jacobian(q, 1.0, jacobian_b);
  const Eigen::MatrixXd separation = jacobian_b - jacobian_a;
  Eigen::MatrixXd rate_by_position = Eigen::MatrixXd::Zero(2, n);
  b_.add_velocity_jacobian(q, v, 1.0, rate_by_position);
  a_.add_velocity_jacobian(q, v, -1.0, rate_by_position);

  // dT/dq = k e^T D + c (u^T de/dq + e^T W), dT/dv = c e^T D.
  const Eigen::RowVectorXd tension_by_position =
      stiffness_ * e.transpose() * separation +
      damping_ * (relative_velocity.transpose() * transverse * separation +
                  e.transpose() * rate_by_position);
  const Eigen::RowVectorXd tension_by_velocity = damping_ * e.transpose() * separation;
  // The force on a, f = T e: df/dq = e dT/dq + T transverse D, df/dv = e dT/dv.
  const Eigen::MatrixXd force_on_a_by_position =
      e * tension_by_position + tension_now * transverse * separation;
  const Eigen::MatrixXd force_on_a_by_velocity = e * tension_by_velocity;

  // Q = J_a^T f - J_b^T f; the product rule adds the derivative of J^T at fixed f.
  force_by_position += (jacobian_a - jacobian_b).transpose() * force_on_a_by_position;
  force_by_velocity += (jacobian_a - jacobian_b).transpose() * force_on_a_by_velocity;
  const Eigen::Vector2d on_a = tension_now * e;
  a_.add_load_derivative(q, on_a, force_by_position);
  b_.add_load_derivative(q, -on_a, force_by_position);
  return true;
}

}  // namespace fsi::mbd::detail
