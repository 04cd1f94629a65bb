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
  a_.add_load(q, on_a, force);
  b_.add_load(q, -on_a, force);
}

bool SpringDamper::add_jacobian_entries(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                        MatrixSink& force_by_position,
                                        MatrixSink& force_by_velocity) const {
  const Eigen::Vector2d d = b_.position(q) - a_.position(q);
  const double length = d.norm();
  const Eigen::Vector2d e = d / length;
  const Eigen::Vector2d relative_velocity = b_.velocity(q, v) - a_.velocity(q, v);
  const Eigen::Matrix2d transverse = (Eigen::Matrix2d::Identity() - e * e.transpose()) / length;
  const double tension_now =
      stiffness_ * (length - rest_length_) + damping_ * e.dot(relative_velocity);

  // D = dd/dq, W = d(dd/dt)/dq at fixed v; de/dq = transverse D. All 2 x n by their non-zero
  // columns.
  SparseColumns separation, rate_by_position;
  b_.add_jacobian(q, 1.0, separation);
  a_.add_jacobian(q, -1.0, separation);
  b_.add_velocity_jacobian(q, v, 1.0, rate_by_position);
  a_.add_velocity_jacobian(q, v, -1.0, rate_by_position);

  // dT/dq = k e^T D + c (u^T de/dq + e^T W), dT/dv = c e^T D.
  // The force on a, f = T e: df/dq = e dT/dq + T transverse D, df/dv = e dT/dv.
  const Eigen::Vector2d transverse_velocity = transverse * relative_velocity;
  SparseColumns force_on_a_by_position, force_on_a_by_velocity;
  for (std::size_t k = 0; k < separation.index.size(); ++k) {
    const Eigen::Vector2d& column = separation.column[k];
    const double tension_by_position =
        stiffness_ * e.dot(column) + damping_ * transverse_velocity.dot(column);
    force_on_a_by_position.add(separation.index[k],
                               e * tension_by_position + tension_now * transverse * column);
    force_on_a_by_velocity.add(separation.index[k], e * (damping_ * e.dot(column)));
  }
  for (std::size_t k = 0; k < rate_by_position.index.size(); ++k) {
    force_on_a_by_position.add(rate_by_position.index[k],
                               e * (damping_ * e.dot(rate_by_position.column[k])));
  }

  // Q = J_a^T f - J_b^T f = -D^T f; the product rule adds the derivative of J^T at fixed f.
  separation.add_transpose_product(force_by_position, Eigen::Matrix2d::Identity(),
                                   force_on_a_by_position, -1.0);
  separation.add_transpose_product(force_by_velocity, Eigen::Matrix2d::Identity(),
                                   force_on_a_by_velocity, -1.0);
  const Eigen::Vector2d on_a = tension_now * e;
  a_.add_load_derivative(q, on_a, force_by_position);
  b_.add_load_derivative(q, -on_a, force_by_position);
  return true;
}

}  // namespace fsi::mbd::detail
