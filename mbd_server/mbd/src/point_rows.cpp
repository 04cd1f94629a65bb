#include "point_rows.hpp"

#include <cmath>
#include <utility>

#include "spatial_body.hpp"

namespace fsi::mbd::detail {

template <int D>
using Vector = Eigen::Matrix<double, D, 1>;

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

// The 2D cross product u x w = u^T S w.
double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& w) {
  return u.x() * w.y() - u.y() * w.x();
}

// S w with u x w = u . (S w): a quarter turn clockwise.
Eigen::Vector2d cross_partner(const Eigen::Vector2d& w) {
  return {w.y(), -w.x()};
}

}  // namespace

PrismaticConstraint::PrismaticConstraint(std::string description, BodyPoint origin, BodyPoint tip,
                                         BodyPoint slider, double axis_length)
    : ConstraintRow(std::move(description)),
      origin_(origin),
      tip_(tip),
      slider_(slider),
      axis_length_(axis_length) {}

PrismaticConstraint::Geometry PrismaticConstraint::geometry(const Eigen::VectorXd& q) const {
  Geometry g{
      tip_.position(q) - origin_.position(q), slider_.position(q) - origin_.position(q), {}, {}};
  tip_.add_jacobian(q, 1.0, g.axis_jacobian);
  origin_.add_jacobian(q, -1.0, g.axis_jacobian);
  slider_.add_jacobian(q, 1.0, g.separation_jacobian);
  origin_.add_jacobian(q, -1.0, g.separation_jacobian);
  return g;
}

double PrismaticConstraint::residual(double, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd&) const {
  const Eigen::Vector2d e = tip_.position(q) - origin_.position(q);
  const Eigen::Vector2d d = slider_.position(q) - origin_.position(q);
  return cross(e, d) / axis_length_;
}

void PrismaticConstraint::add_jacobian_entries(double, const Eigen::VectorXd& q, int row,
                                               MatrixSink& jacobian) const {
  // d(e x d) = (S d) . de - (S e) . dd, since e x d = -(d x e).
  const Geometry g = geometry(q);
  g.axis_jacobian.add_row(jacobian, row, cross_partner(g.separation) / axis_length_);
  g.separation_jacobian.add_row(jacobian, row, -cross_partner(g.axis) / axis_length_);
}

double PrismaticConstraint::acceleration_remainder(double, const Eigen::VectorXd& q,
                                                   const Eigen::VectorXd& v) const {
  // (e x d)'' = e'' x d + 2 e' x d' + e x d''; the acceleration-free parts of e'' and d''.
  const Eigen::Vector2d e = tip_.position(q) - origin_.position(q);
  const Eigen::Vector2d d = slider_.position(q) - origin_.position(q);
  const Eigen::Vector2d e_rate = tip_.velocity(q, v) - origin_.velocity(q, v);
  const Eigen::Vector2d d_rate = slider_.velocity(q, v) - origin_.velocity(q, v);
  const Eigen::Vector2d origin_remainder = origin_.acceleration_remainder(q, v);
  const Eigen::Vector2d e_remainder = tip_.acceleration_remainder(q, v) - origin_remainder;
  const Eigen::Vector2d d_remainder = slider_.acceleration_remainder(q, v) - origin_remainder;
  return (cross(e_remainder, d) + 2.0 * cross(e_rate, d_rate) + cross(e, d_remainder)) /
         axis_length_;
}

void PrismaticConstraint::add_force_derivative_entries(double, const Eigen::VectorXd& q,
                                                       double multiplier,
                                                       MatrixSink& derivative) const {
  // mu G^T = (mu / |axis|) (E^T S d - D^T S e), E = de/dq, D = dd/dq. Its q-derivative: the
  // products E^T S D - D^T S E, plus E^T and D^T differentiated at fixed vectors, which are
  // the point-load derivatives of the loads mu S d / |axis| (tip +, origin -) and
  // -mu S e / |axis| (slider +, origin -).
  const Geometry g = geometry(q);
  const double scale = multiplier / axis_length_;
  Eigen::Matrix2d quarter_turn;
  quarter_turn << 0.0, 1.0, -1.0, 0.0;  // S
  g.axis_jacobian.add_transpose_product(derivative, quarter_turn, g.separation_jacobian, scale);
  g.separation_jacobian.add_transpose_product(derivative, quarter_turn, g.axis_jacobian, -scale);
  const Eigen::Vector2d on_tip = scale * cross_partner(g.separation);
  const Eigen::Vector2d on_slider = -scale * cross_partner(g.axis);
  tip_.add_load_derivative(q, on_tip, derivative);
  slider_.add_load_derivative(q, on_slider, derivative);
  origin_.add_load_derivative(q, -on_tip - on_slider, derivative);
}

template class BasicPointConstraint<BodyPoint, 2>;
template class BasicPointConstraint<SpatialPoint, 3>;
template class BasicDistanceConstraint<BodyPoint, 2>;
template class BasicDistanceConstraint<SpatialPoint, 3>;

}  // namespace fsi::mbd::detail
