#include <utility>

#include "constraint.hpp"

#include <cmath>

#include "spatial_body.hpp"

namespace fsi::mbd::detail {

template <int D>
using Vector = Eigen::Matrix<double, D, 1>;

CoordinateConstraint::CoordinateConstraint(std::string description, int coordinate_index,
                                           double value)
    : LinearConstraintRow(std::move(description)), index_(coordinate_index), value_(value) {}

double CoordinateConstraint::residual(double, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd&) const {
  return q(index_) - value_;
}

void CoordinateConstraint::add_jacobian_entries(double, const Eigen::VectorXd&, int row,
                                                MatrixSink& jacobian) const {
  jacobian.add(row, index_, 1.0);
}

LinearCoordinateConstraint::LinearCoordinateConstraint(std::string description,
                                                       Eigen::VectorXi indices,
                                                       Eigen::VectorXd weights, double value)
    : LinearConstraintRow(std::move(description)),
      indices_(std::move(indices)),
      weights_(std::move(weights)),
      value_(value) {}

double LinearCoordinateConstraint::residual(double, const Eigen::VectorXd& q,
                                            const Eigen::VectorXd&) const {
  double sum = -value_;
  for (Eigen::Index k = 0; k < indices_.size(); ++k)
    sum += weights_(k) * q(indices_(k));
  return sum;
}

void LinearCoordinateConstraint::add_jacobian_entries(double, const Eigen::VectorXd&, int row,
                                                      MatrixSink& jacobian) const {
  for (Eigen::Index k = 0; k < indices_.size(); ++k)
    jacobian.add(row, indices_(k), weights_(k));
}

VelocityConstraint::VelocityConstraint(std::string description, int coordinate_index,
                                       double velocity)
    : LinearConstraintRow(std::move(description), ConstraintLevel::Velocity),
      index_(coordinate_index),
      velocity_(velocity) {}

double VelocityConstraint::residual(double, const Eigen::VectorXd&,
                                    const Eigen::VectorXd& v) const {
  return v(index_) - velocity_;
}

void VelocityConstraint::add_jacobian_entries(double, const Eigen::VectorXd&, int row,
                                              MatrixSink& jacobian) const {
  jacobian.add(row, index_, 1.0);
}

template <typename Point, int D>
BasicPointConstraint<Point, D>::BasicPointConstraint(std::string description, Point a, Point b,
                                                     int axis)
    : ConstraintRow(std::move(description)), a_(a), b_(b), axis_(axis) {}

template <typename Point, int D>
double BasicPointConstraint<Point, D>::residual(double, const Eigen::VectorXd& q,
                                                const Eigen::VectorXd&) const {
  return (a_.position(q) - b_.position(q))(axis_);
}

template <typename Point, int D>
void BasicPointConstraint<Point, D>::add_jacobian_entries(double, const Eigen::VectorXd& q, int row,
                                                          MatrixSink& jacobian) const {
  PointColumns<D> columns;
  a_.add_jacobian(q, 1.0, columns);
  b_.add_jacobian(q, -1.0, columns);
  columns.add_row(jacobian, row, Vector<D>::Unit(axis_));
}

template <typename Point, int D>
double BasicPointConstraint<Point, D>::acceleration_remainder(double, const Eigen::VectorXd& q,
                                                              const Eigen::VectorXd& v) const {
  return (a_.acceleration_remainder(q, v) - b_.acceleration_remainder(q, v))(axis_);
}

template <typename Point, int D>
void BasicPointConstraint<Point, D>::add_force_derivative_entries(double, const Eigen::VectorXd& q,
                                                                  double multiplier,
                                                                  MatrixSink& derivative) const {
  // G^T mu = (dr_a/dq - dr_b/dq)^T (mu e_axis): the derivative of a point load mu e_axis.
  const Vector<D> load = multiplier * Vector<D>::Unit(axis_);
  a_.add_load_derivative(q, load, derivative);
  b_.add_load_derivative(q, -load, derivative);
}

template <typename Point, int D>
BasicDistanceConstraint<Point, D>::BasicDistanceConstraint(std::string description, Point a,
                                                           Point b, double length)
    : ConstraintRow(std::move(description)), a_(a), b_(b), length_(length) {}

template <typename Point, int D>
PointColumns<D> BasicDistanceConstraint<Point, D>::separation_jacobian(
    const Eigen::VectorXd& q) const {
  PointColumns<D> jacobian;
  b_.add_jacobian(q, 1.0, jacobian);
  a_.add_jacobian(q, -1.0, jacobian);
  return jacobian;
}

template <typename Point, int D>
double BasicDistanceConstraint<Point, D>::residual(double, const Eigen::VectorXd& q,
                                                   const Eigen::VectorXd&) const {
  const Vector<D> d = b_.position(q) - a_.position(q);
  return (d.squaredNorm() - length_ * length_) / (2.0 * length_);
}

template <typename Point, int D>
void BasicDistanceConstraint<Point, D>::add_jacobian_entries(double, const Eigen::VectorXd& q,
                                                             int row, MatrixSink& jacobian) const {
  const Vector<D> d = b_.position(q) - a_.position(q);
  separation_jacobian(q).add_row(jacobian, row, d / length_);
}

template <typename Point, int D>
double BasicDistanceConstraint<Point, D>::acceleration_remainder(double, const Eigen::VectorXd& q,
                                                                 const Eigen::VectorXd& v) const {
  // d^2C/dt^2 = (|d'|^2 + d . d'') / length, d'' = (dd/dq) a + (remainder_b - remainder_a).
  const Vector<D> d = b_.position(q) - a_.position(q);
  const Vector<D> rate = b_.velocity(q, v) - a_.velocity(q, v);
  const Vector<D> remainder = b_.acceleration_remainder(q, v) - a_.acceleration_remainder(q, v);
  return (rate.squaredNorm() + d.dot(remainder)) / length_;
}

template <typename Point, int D>
void BasicDistanceConstraint<Point, D>::add_force_derivative_entries(double,
                                                                     const Eigen::VectorXd& q,
                                                                     double multiplier,
                                                                     MatrixSink& derivative) const {
  // G^T mu = (mu / length) (dd/dq)^T d: the product rule gives (mu / length) D^T D plus the
  // derivative of the point loads +-(mu / length) d at fixed d.
  const PointColumns<D> jacobian = separation_jacobian(q);
  const Vector<D> load = multiplier / length_ * (b_.position(q) - a_.position(q));
  jacobian.add_transpose_product(derivative, Eigen::Matrix<double, D, D>::Identity(), jacobian,
                                 multiplier / length_);
  b_.add_load_derivative(q, load, derivative);
  a_.add_load_derivative(q, -load, derivative);
}

namespace {

// d f/dt by a central difference with a step balancing truncation and rounding.
double time_derivative(const std::function<double(double)>& f, double time) {
  const double step = 1e-5 * (1.0 + std::abs(time));
  return (f(time + step) - f(time - step)) / (2.0 * step);
}

}  // namespace

PrescribedCoordinate::PrescribedCoordinate(std::string description, int coordinate_index,
                                           std::function<double(double)> position,
                                           std::function<double(double)> rate)
    : ConstraintRow(std::move(description)),
      index_(coordinate_index),
      position_(std::move(position)),
      rate_(std::move(rate)) {}

double PrescribedCoordinate::residual(double time, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd&) const {
  return q(index_) - position_(time);
}

void PrescribedCoordinate::add_jacobian_entries(double, const Eigen::VectorXd&, int row,
                                                MatrixSink& jacobian) const {
  jacobian.add(row, index_, 1.0);
}

double PrescribedCoordinate::acceleration_remainder(double time, const Eigen::VectorXd&,
                                                    const Eigen::VectorXd&) const {
  return -time_derivative(rate_, time);  // d^2C/dt^2 = a_i - s''(t)
}

TimeVelocityConstraint::TimeVelocityConstraint(std::string description, int coordinate_index,
                                               std::function<double(double)> velocity)
    : ConstraintRow(std::move(description), ConstraintLevel::Velocity),
      index_(coordinate_index),
      velocity_(std::move(velocity)) {}

double TimeVelocityConstraint::residual(double time, const Eigen::VectorXd&,
                                        const Eigen::VectorXd& v) const {
  return v(index_) - velocity_(time);
}

void TimeVelocityConstraint::add_jacobian_entries(double, const Eigen::VectorXd&, int row,
                                                  MatrixSink& jacobian) const {
  jacobian.add(row, index_, 1.0);
}

double TimeVelocityConstraint::acceleration_remainder(double time, const Eigen::VectorXd&,
                                                      const Eigen::VectorXd&) const {
  return -time_derivative(velocity_, time);
}

template class BasicPointConstraint<BodyPoint, 2>;
template class BasicPointConstraint<SpatialPoint, 3>;
template class BasicDistanceConstraint<BodyPoint, 2>;
template class BasicDistanceConstraint<SpatialPoint, 3>;

}  // namespace fsi::mbd::detail
