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
    : description_(std::move(description)),
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

RelativeAngleConstraint::RelativeAngleConstraint(std::string description, int angle_a, int angle_b,
                                                 double offset)
    : description_(std::move(description)), angle_a_(angle_a), angle_b_(angle_b), offset_(offset) {}

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
