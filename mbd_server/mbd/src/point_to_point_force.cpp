#include "point_to_point_force.hpp"

#include <utility>

#include "spatial_body.hpp"

namespace fsi::mbd::detail {

template <typename Point, int D>
BasicPointToPointForce<Point, D>::BasicPointToPointForce(std::string description, Point a, Point b,
                                                         double rest_length,
                                                         std::shared_ptr<const TensionLaw> law)
    : SparseForceElement(std::move(description)),
      a_(a),
      b_(b),
      rest_length_(rest_length),
      law_(std::move(law)) {}

template <typename Point, int D>
double BasicPointToPointForce<Point, D>::measured_force(double time, const Eigen::VectorXd& q,
                                                        const Eigen::VectorXd& v) const {
  const Vector d = b_.position(q) - a_.position(q);
  const double length = d.norm();
  const double rate = d.dot(b_.velocity(q, v) - a_.velocity(q, v)) / length;
  return law_->at(length - rest_length_, rate, time).value;
}

template <typename Point, int D>
double BasicPointToPointForce<Point, D>::potential_energy(double time,
                                                          const Eigen::VectorXd& q) const {
  return law_->energy((b_.position(q) - a_.position(q)).norm() - rest_length_, time);
}

template <typename Point, int D>
void BasicPointToPointForce<Point, D>::add_force(double time, const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& v,
                                                 Eigen::VectorXd& force) const {
  const Vector d = b_.position(q) - a_.position(q);
  const Vector on_a = measured_force(time, q, v) / d.norm() * d;
  a_.add_load(q, on_a, force);
  b_.add_load(q, -on_a, force);
}

template <typename Point, int D>
bool BasicPointToPointForce<Point, D>::add_jacobian_entries(double time, const Eigen::VectorXd& q,
                                                            const Eigen::VectorXd& v,
                                                            MatrixSink& force_by_position,
                                                            MatrixSink& force_by_velocity) const {
  const Vector d = b_.position(q) - a_.position(q);
  const double length = d.norm();
  const Vector e = d / length;
  const Vector relative_velocity = b_.velocity(q, v) - a_.velocity(q, v);
  const Matrix transverse = (Matrix::Identity() - e * e.transpose()) / length;
  const Tension tension = law_->at(length - rest_length_, e.dot(relative_velocity), time);

  // D = dd/dq, W = d(dd/dt)/dq at fixed v; de/dq = transverse D. All D x n by their non-zero
  // columns.
  PointColumns<D> separation, rate_by_position;
  b_.add_jacobian(q, 1.0, separation);
  a_.add_jacobian(q, -1.0, separation);
  b_.add_velocity_jacobian(q, v, 1.0, rate_by_position);
  a_.add_velocity_jacobian(q, v, -1.0, rate_by_position);

  // With T_l, T_r the law's partials: dT/dq = T_l e^T D + T_r (u^T de/dq + e^T W),
  // dT/dv = T_r e^T D. The force on a, f = T e: df/dq = e dT/dq + T transverse D, df/dv = e dT/dv.
  const Vector transverse_velocity = transverse * relative_velocity;
  PointColumns<D> force_on_a_by_position, force_on_a_by_velocity;
  for (std::size_t k = 0; k < separation.index.size(); ++k) {
    const Vector& column = separation.column[k];
    const double tension_by_position =
        tension.by_elongation * e.dot(column) + tension.by_rate * transverse_velocity.dot(column);
    force_on_a_by_position.add(separation.index[k],
                               e * tension_by_position + tension.value * transverse * column);
    force_on_a_by_velocity.add(separation.index[k], e * (tension.by_rate * e.dot(column)));
  }
  for (std::size_t k = 0; k < rate_by_position.index.size(); ++k) {
    force_on_a_by_position.add(rate_by_position.index[k],
                               e * (tension.by_rate * e.dot(rate_by_position.column[k])));
  }

  // Q = J_a^T f - J_b^T f = -D^T f; the product rule adds the derivative of J^T at fixed f.
  separation.add_transpose_product(force_by_position, Matrix::Identity(), force_on_a_by_position,
                                   -1.0);
  separation.add_transpose_product(force_by_velocity, Matrix::Identity(), force_on_a_by_velocity,
                                   -1.0);
  const Vector on_a = tension.value * e;
  a_.add_load_derivative(q, on_a, force_by_position);
  b_.add_load_derivative(q, -on_a, force_by_position);
  return true;
}

template class BasicPointToPointForce<BodyPoint, 2>;
template class BasicPointToPointForce<SpatialPoint, 3>;

}  // namespace fsi::mbd::detail
