#include "spring_damper.hpp"

#include "spatial_body.hpp"

namespace fsi::mbd::detail {

template <typename Point, int D>
BasicSpringDamper<Point, D>::BasicSpringDamper(Point a, Point b, double stiffness, double damping,
                                               double rest_length)
    : SparseForceElement("spring-damper"),
      a_(a),
      b_(b),
      stiffness_(stiffness),
      damping_(damping),
      rest_length_(rest_length) {}

template <typename Point, int D>
double BasicSpringDamper<Point, D>::tension(const Eigen::VectorXd& q,
                                            const Eigen::VectorXd& v) const {
  const Vector d = b_.position(q) - a_.position(q);
  const double length = d.norm();
  const double rate = d.dot(b_.velocity(q, v) - a_.velocity(q, v)) / length;
  return stiffness_ * (length - rest_length_) + damping_ * rate;
}

template <typename Point, int D>
double BasicSpringDamper<Point, D>::potential_energy(double, const Eigen::VectorXd& q) const {
  const double stretch = (b_.position(q) - a_.position(q)).norm() - rest_length_;
  return 0.5 * stiffness_ * stretch * stretch;
}

template <typename Point, int D>
void BasicSpringDamper<Point, D>::add_force(double, const Eigen::VectorXd& q,
                                            const Eigen::VectorXd& v,
                                            Eigen::VectorXd& force) const {
  const Vector d = b_.position(q) - a_.position(q);
  const Vector on_a = tension(q, v) * d / d.norm();
  a_.add_load(q, on_a, force);
  b_.add_load(q, -on_a, force);
}

template <typename Point, int D>
bool BasicSpringDamper<Point, D>::add_jacobian_entries(double, const Eigen::VectorXd& q,
                                                       const Eigen::VectorXd& v,
                                                       MatrixSink& force_by_position,
                                                       MatrixSink& force_by_velocity) const {
  const Vector d = b_.position(q) - a_.position(q);
  const double length = d.norm();
  const Vector e = d / length;
  const Vector relative_velocity = b_.velocity(q, v) - a_.velocity(q, v);
  const Matrix transverse = (Matrix::Identity() - e * e.transpose()) / length;
  const double tension_now =
      stiffness_ * (length - rest_length_) + damping_ * e.dot(relative_velocity);

  // D = dd/dq, W = d(dd/dt)/dq at fixed v; de/dq = transverse D. All 2 x n by their non-zero
  // columns.
  PointColumns<D> separation, rate_by_position;
  b_.add_jacobian(q, 1.0, separation);
  a_.add_jacobian(q, -1.0, separation);
  b_.add_velocity_jacobian(q, v, 1.0, rate_by_position);
  a_.add_velocity_jacobian(q, v, -1.0, rate_by_position);

  // dT/dq = k e^T D + c (u^T de/dq + e^T W), dT/dv = c e^T D.
  // The force on a, f = T e: df/dq = e dT/dq + T transverse D, df/dv = e dT/dv.
  const Vector transverse_velocity = transverse * relative_velocity;
  PointColumns<D> force_on_a_by_position, force_on_a_by_velocity;
  for (std::size_t k = 0; k < separation.index.size(); ++k) {
    const Vector& column = separation.column[k];
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
  separation.add_transpose_product(force_by_position, Matrix::Identity(), force_on_a_by_position,
                                   -1.0);
  separation.add_transpose_product(force_by_velocity, Matrix::Identity(), force_on_a_by_velocity,
                                   -1.0);
  const Vector on_a = tension_now * e;
  a_.add_load_derivative(q, on_a, force_by_position);
  b_.add_load_derivative(q, -on_a, force_by_position);
  return true;
}

template class BasicSpringDamper<BodyPoint, 2>;
template class BasicSpringDamper<SpatialPoint, 3>;

}  // namespace fsi::mbd::detail
