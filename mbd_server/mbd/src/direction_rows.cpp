#include "direction_rows.hpp"

#include <cmath>
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

RotationDriveConstraint::RotationDriveConstraint(std::string description, SpatialDirection e1,
                                                 SpatialDirection e2, SpatialDirection u,
                                                 double rate)
    : ConstraintRow(std::move(description)), e1_(e1), e2_(e2), u_(u), rate_(rate) {}

Eigen::Vector3d RotationDriveConstraint::turned(double time, const Eigen::VectorXd& q) const {
  const double phi = rate_ * time;
  return std::sin(phi) * e1_.value(q) + std::cos(phi) * e2_.value(q);
}

Eigen::Vector3d RotationDriveConstraint::turned_time_rate(double time,
                                                          const Eigen::VectorXd& q) const {
  const double phi = rate_ * time;
  return rate_ * (std::cos(phi) * e1_.value(q) - std::sin(phi) * e2_.value(q));
}

double RotationDriveConstraint::residual(double time, const Eigen::VectorXd& q,
                                         const Eigen::VectorXd&) const {
  return u_.value(q).dot(turned(time, q));
}

void RotationDriveConstraint::add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                                                   MatrixSink& jacobian) const {
  const double phi = rate_ * time;
  const Eigen::Vector3d u = u_.value(q);
  u_.jacobian(q).add_row(jacobian, row, turned(time, q));
  e1_.jacobian(q).add_row(jacobian, row, std::sin(phi) * u);
  e2_.jacobian(q).add_row(jacobian, row, std::cos(phi) * u);
}

double RotationDriveConstraint::explicit_time_derivative(double time,
                                                         const Eigen::VectorXd& q) const {
  return u_.value(q).dot(turned_time_rate(time, q));
}

double RotationDriveConstraint::acceleration_remainder(double time, const Eigen::VectorXd& q,
                                                       const Eigen::VectorXd& v) const {
  // C = u . w with w = sin(phi) e1 + cos(phi) e2: d^2C/dt^2 = u'' . w + 2 u' . w' + u . w'', where
  // w' = sin(phi) e1' + cos(phi) e2' + w_t and w'' = sin(phi) e1'' + cos(phi) e2''
  // + 2 rate (cos(phi) e1' - sin(phi) e2') - rate^2 w; the acceleration-free parts of e1'', e2'',
  // u'' are the points' remainders.
  const double phi = rate_ * time;
  const double s = std::sin(phi);
  const double c = std::cos(phi);
  const Eigen::Vector3d u = u_.value(q);
  const Eigen::Vector3d w = turned(time, q);
  const Eigen::Vector3d e1_rate = e1_.rate(q, v);
  const Eigen::Vector3d e2_rate = e2_.rate(q, v);
  const Eigen::Vector3d w_rate = s * e1_rate + c * e2_rate + turned_time_rate(time, q);
  const Eigen::Vector3d w_remainder = s * e1_.acceleration_remainder(q, v) +
                                      c * e2_.acceleration_remainder(q, v) +
                                      2.0 * rate_ * (c * e1_rate - s * e2_rate) - rate_ * rate_ * w;
  return w.dot(u_.acceleration_remainder(q, v)) + 2.0 * u_.rate(q, v).dot(w_rate) +
         u.dot(w_remainder);
}

void RotationDriveConstraint::add_force_derivative_entries(double time, const Eigen::VectorXd& q,
                                                           double multiplier,
                                                           MatrixSink& derivative) const {
  // G^T mu = mu (U^T w + W^T u), U = du/dq, W = dw/dq = sin(phi) E1 + cos(phi) E2: the product
  // rule gives mu (U^T W + W^T U) plus the load derivatives of mu w on u and mu u on w.
  const double phi = rate_ * time;
  SpatialColumns jw;
  jw.append(e1_.jacobian(q), std::sin(phi));
  jw.append(e2_.jacobian(q), std::cos(phi));
  const SpatialColumns ju = u_.jacobian(q);
  ju.add_transpose_product(derivative, Eigen::Matrix3d::Identity(), jw, multiplier);
  jw.add_transpose_product(derivative, Eigen::Matrix3d::Identity(), ju, multiplier);
  const Eigen::Vector3d u = u_.value(q);
  u_.add_load_derivative(q, multiplier * turned(time, q), derivative);
  e1_.add_load_derivative(q, multiplier * std::sin(phi) * u, derivative);
  e2_.add_load_derivative(q, multiplier * std::cos(phi) * u, derivative);
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

}  // namespace fsi::mbd::detail
