#include "spatial_rotational_spring.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "fsi/common/text.hpp"

namespace fsi::mbd::detail {

namespace {

// Below this |projection of u| (u within ~0.06 degrees of the axis) the twist is not defined.
constexpr double kSmallestProjection = 1e-3;

double wrapped(double angle) {
  angle = std::remainder(angle, 2.0 * std::numbers::pi);  // [-pi, pi]
  return angle == -std::numbers::pi ? std::numbers::pi : angle;
}

// A direction's Jacobian as a dense 3 x m block over `columns` (indices added as they come).
Eigen::Matrix3Xd local_jacobian(const SpatialColumns& sparse, std::vector<int>& columns) {
  for (const int index : sparse.index) {
    bool known = false;
    for (const int c : columns)
      known = known || c == index;
    if (!known) columns.push_back(index);
  }
  Eigen::Matrix3Xd dense = Eigen::Matrix3Xd::Zero(3, static_cast<Eigen::Index>(columns.size()));
  for (std::size_t k = 0; k < sparse.index.size(); ++k) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (columns[c] == sparse.index[k])
        dense.col(static_cast<Eigen::Index>(c)) += sparse.column[k];
    }
  }
  return dense;
}

Eigen::Matrix3Xd widened(const Eigen::Matrix3Xd& block, Eigen::Index columns) {
  Eigen::Matrix3Xd wide = Eigen::Matrix3Xd::Zero(3, columns);
  wide.leftCols(block.cols()) = block;
  return wide;
}

}  // namespace

SpatialRotationalSpringDamper::SpatialRotationalSpringDamper(std::string description,
                                                             SpatialDirection e1,
                                                             SpatialDirection e2,
                                                             SpatialDirection u, double rest_angle,
                                                             std::shared_ptr<const TensionLaw> law)
    : SparseForceElement(std::move(description)),
      e1_(e1),
      e2_(e2),
      u_(u),
      rest_angle_(rest_angle),
      law_(std::move(law)) {}

double SpatialRotationalSpringDamper::Kinematics::rate(const Eigen::VectorXd& v) const {
  double sum = 0.0;
  for (std::size_t c = 0; c < columns.size(); ++c)
    sum += gradient(static_cast<Eigen::Index>(c)) * v(columns[c]);
  return sum;
}

SpatialRotationalSpringDamper::Kinematics SpatialRotationalSpringDamper::kinematics(
    const Eigen::VectorXd& q, bool with_hessian) const {
  Kinematics k;
  const Eigen::Vector3d e1 = e1_.value(q), e2 = e2_.value(q), u = u_.value(q);
  // The local blocks; those found first are narrower, so all are widened to the final count.
  Eigen::Matrix3Xd j_e1 = local_jacobian(e1_.jacobian(q), k.columns);
  Eigen::Matrix3Xd j_e2 = local_jacobian(e2_.jacobian(q), k.columns);
  Eigen::Matrix3Xd j_u = local_jacobian(u_.jacobian(q), k.columns);
  const auto m = static_cast<Eigen::Index>(k.columns.size());
  j_e1 = widened(j_e1, m);
  j_e2 = widened(j_e2, m);
  j_u = widened(j_u, m);

  const double x = u.dot(e1), y = u.dot(e2);
  const double rho2 = x * x + y * y;
  k.rho = std::sqrt(rho2);
  k.twist = wrapped(std::atan2(-y, x) - rest_angle_);
  const Eigen::VectorXd grad_x = j_u.transpose() * e1 + j_e1.transpose() * u;
  const Eigen::VectorXd grad_y = j_u.transpose() * e2 + j_e2.transpose() * u;
  k.gradient = (y * grad_x - x * grad_y) / rho2;
  if (with_hessian) {
    // The directions are linear in q (rigid bodies), so x and y are bilinear with constant
    // second derivatives; theta's follow from the quotient rule.
    const Eigen::MatrixXd hess_x = j_u.transpose() * j_e1 + j_e1.transpose() * j_u;
    const Eigen::MatrixXd hess_y = j_u.transpose() * j_e2 + j_e2.transpose() * j_u;
    k.hessian =
        (grad_x * grad_y.transpose() - grad_y * grad_x.transpose() + y * hess_x - x * hess_y) /
            rho2 -
        2.0 * k.gradient * (x * grad_x + y * grad_y).transpose() / rho2;
  }
  return k;
}

std::string SpatialRotationalSpringDamper::problem(const Kinematics& k, const Tension& law,
                                                   double rate, double time) const {
  if (!(k.rho >= kSmallestProjection)) {
    return "body b's reference direction has turned into the spring's axis (its projection on "
           "the plane normal to the axis is " +
           significant(k.rho, 3) +
           " of its length), where the twist about the axis is not defined: hold the axis with a "
           "RevoluteJoint3D about it";
  }
  // Beyond the range a law that depends on the twist, or differs on the two sides of the half
  // turn (a one-sided stop), would jump there.
  if (std::abs(k.twist) > kTwistLimit &&
      (law.by_elongation != 0.0 || law_->at(std::numbers::pi, rate, time).value !=
                                       law_->at(-std::numbers::pi, rate, time).value)) {
    return "twisted past the +-170 degrees from its rest angle that it measures (" +
           significant(k.twist * 180.0 / std::numbers::pi, 7) +
           "; at +-180 the torque would jump to the other side of the spring): keep the twist "
           "within half a turn of rest_angle, e.g. by a stiffer spring or a rest_angle nearer "
           "the motion";
  }
  return {};
}

double SpatialRotationalSpringDamper::measured_force(double time, const Eigen::VectorXd& q,
                                                     const Eigen::VectorXd& v) const {
  const Kinematics k = kinematics(q, false);
  const double rate = k.rate(v);
  const Tension law = law_->at(k.twist, rate, time);
  if (!problem(k, law, rate, time).empty()) return std::numeric_limits<double>::quiet_NaN();
  return -law.value;
}

void SpatialRotationalSpringDamper::add_force(double time, const Eigen::VectorXd& q,
                                              const Eigen::VectorXd& v,
                                              Eigen::VectorXd& force) const {
  const Kinematics k = kinematics(q, false);
  const double rate = k.rate(v);
  const Tension law = law_->at(k.twist, rate, time);
  const double torque =
      problem(k, law, rate, time).empty() ? law.value : std::numeric_limits<double>::quiet_NaN();
  for (std::size_t c = 0; c < k.columns.size(); ++c)
    force(k.columns[c]) -= torque * k.gradient(static_cast<Eigen::Index>(c));
}

bool SpatialRotationalSpringDamper::add_jacobian_entries(double time, const Eigen::VectorXd& q,
                                                         const Eigen::VectorXd& v,
                                                         MatrixSink& force_by_position,
                                                         MatrixSink& force_by_velocity) const {
  // Q = -T(theta, g . v, t) g:  dQ/dq = -T_s g g^T - T_r g (H v)^T - T H,  dQ/dv = -T_r g g^T.
  const Kinematics k = kinematics(q, true);
  const auto m = static_cast<Eigen::Index>(k.columns.size());
  Eigen::VectorXd local_v(m);
  for (Eigen::Index c = 0; c < m; ++c)
    local_v(c) = v(k.columns[static_cast<std::size_t>(c)]);
  const Tension law = law_->at(k.twist, k.gradient.dot(local_v), time);
  const Eigen::VectorXd hv = k.hessian * local_v;
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < m; ++j) {
      const int row = k.columns[static_cast<std::size_t>(i)];
      const int column = k.columns[static_cast<std::size_t>(j)];
      const double gg = k.gradient(i) * k.gradient(j);
      force_by_position.add(row, column,
                            -law.by_elongation * gg - law.by_rate * k.gradient(i) * hv(j) -
                                law.value * k.hessian(i, j));
      force_by_velocity.add(row, column, -law.by_rate * gg);
    }
  }
  return true;
}

double SpatialRotationalSpringDamper::potential_energy(double time,
                                                       const Eigen::VectorXd& q) const {
  return law_->energy(twist(q), time);
}

std::string SpatialRotationalSpringDamper::non_finite_reason(double time, const Eigen::VectorXd& q,
                                                             const Eigen::VectorXd& v) const {
  const Kinematics k = kinematics(q, false);
  const double rate = k.rate(v);
  return problem(k, law_->at(k.twist, rate, time), rate, time);
}

double SpatialRotationalSpringDamper::twist(const Eigen::VectorXd& q) const {
  return kinematics(q, false).twist;
}

double SpatialRotationalSpringDamper::twist_rate(const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& v) const {
  return kinematics(q, false).rate(v);
}

}  // namespace fsi::mbd::detail
