#include "connectors.hpp"

#include <utility>

namespace fsi::mbd::detail {
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

namespace {

Eigen::Vector2d turned(double angle, const Eigen::Vector2d& p) {
  return Eigen::Rotation2Dd(angle) * p;
}

// d/dphi of R(phi) p: R(phi) (e_z x p).
Eigen::Vector2d turned_rate(double angle, const Eigen::Vector2d& p) {
  return Eigen::Rotation2Dd(angle) * Eigen::Vector2d(-p.y(), p.x());
}

}  // namespace

SlopeOnBodyConstraint::SlopeOnBodyConstraint(std::string description, int slope_x, int slope_y,
                                             int angle, const Eigen::Vector2d& vector,
                                             int component)
    : ConstraintRow(std::move(description)),
      slope_x_(slope_x),
      slope_y_(slope_y),
      angle_(angle),
      vector_(vector),
      component_(component) {}

double SlopeOnBodyConstraint::residual(double, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd&) const {
  const Eigen::Vector2d s(q(slope_x_), q(slope_y_));
  const Eigen::Vector2d w = turned(q(angle_), vector_);
  return component_ < 0 ? w.dot(s) : s(component_) - w(component_);
}

void SlopeOnBodyConstraint::add_jacobian_entries(double, const Eigen::VectorXd& q, int row,
                                                 MatrixSink& jacobian) const {
  const Eigen::Vector2d s(q(slope_x_), q(slope_y_));
  const Eigen::Vector2d w = turned(q(angle_), vector_);
  const Eigen::Vector2d w_rate = turned_rate(q(angle_), vector_);
  if (component_ < 0) {
    jacobian.add(row, slope_x_, w.x());
    jacobian.add(row, slope_y_, w.y());
    jacobian.add(row, angle_, w_rate.dot(s));
  } else {
    jacobian.add(row, component_ == 0 ? slope_x_ : slope_y_, 1.0);
    jacobian.add(row, angle_, -w_rate(component_));
  }
}

double SlopeOnBodyConstraint::acceleration_remainder(double, const Eigen::VectorXd& q,
                                                     const Eigen::VectorXd& v) const {
  // R'' p = -R p.
  const double omega = v(angle_);
  const Eigen::Vector2d w = turned(q(angle_), vector_);
  if (component_ >= 0) return omega * omega * w(component_);
  const Eigen::Vector2d s(q(slope_x_), q(slope_y_));
  const Eigen::Vector2d s_rate(v(slope_x_), v(slope_y_));
  return -omega * omega * w.dot(s) + 2.0 * omega * turned_rate(q(angle_), vector_).dot(s_rate);
}

void SlopeOnBodyConstraint::add_force_derivative_entries(double, const Eigen::VectorXd& q,
                                                         double multiplier,
                                                         MatrixSink& derivative) const {
  const Eigen::Vector2d w = turned(q(angle_), vector_);
  if (component_ >= 0) {
    derivative.add(angle_, angle_, multiplier * w(component_));
    return;
  }
  const Eigen::Vector2d s(q(slope_x_), q(slope_y_));
  const Eigen::Vector2d w_rate = turned_rate(q(angle_), vector_);
  derivative.add(angle_, angle_, -multiplier * w.dot(s));
  derivative.add(angle_, slope_x_, multiplier * w_rate.x());
  derivative.add(angle_, slope_y_, multiplier * w_rate.y());
  derivative.add(slope_x_, angle_, multiplier * w_rate.x());
  derivative.add(slope_y_, angle_, multiplier * w_rate.y());
}

RelativeAngleConstraint::RelativeAngleConstraint(std::string description, int angle_a, int angle_b,
                                                 double offset)
    : LinearConstraintRow(std::move(description)),
      angle_a_(angle_a),
      angle_b_(angle_b),
      offset_(offset) {}

double RelativeAngleConstraint::residual(double, const Eigen::VectorXd& q,
                                         const Eigen::VectorXd&) const {
  const double a = angle_a_ >= 0 ? q(angle_a_) : 0.0;
  const double b = angle_b_ >= 0 ? q(angle_b_) : 0.0;
  return a - b - offset_;
}

void RelativeAngleConstraint::add_jacobian_entries(double, const Eigen::VectorXd&, int row,
                                                   MatrixSink& jacobian) const {
  if (angle_a_ >= 0) jacobian.add(row, angle_a_, 1.0);
  if (angle_b_ >= 0) jacobian.add(row, angle_b_, -1.0);
}

}  // namespace fsi::mbd::detail
