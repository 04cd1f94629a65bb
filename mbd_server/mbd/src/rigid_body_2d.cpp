#include <cmath>

#include "body.hpp"
#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"

namespace fsi::mbd::detail {
namespace {

// R(phi) p and its derivatives with respect to phi: R' p, and R'' p = -R p.
Eigen::Vector2d rotate(double angle, const Eigen::Vector2d& p) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

Eigen::Vector2d rotate_derivative(double angle, const Eigen::Vector2d& p) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return {-s * p.x() - c * p.y(), c * p.x() - s * p.y()};
}

// Input values in messages: all 17 digits.
std::string number(double value) {
  return significant(value, 17);
}

}  // namespace

RigidBody2D::RigidBody2D(const RigidBody2DSpec& spec) : spec_(spec) {
  const std::string where = "rigid body '" + spec.name + "'";
  if (spec.name.empty()) {
    throw Error("a rigid body has no name", "rigid body", "give every body a unique name");
  }
  if (!(std::isfinite(spec.mass) && spec.mass > 0.0)) {
    throw Error("mass must be positive and finite, got " + number(spec.mass), where,
                "give the body a positive mass (2D: per unit depth, kg/m)");
  }
  if (!(std::isfinite(spec.inertia) && spec.inertia > 0.0)) {
    throw Error("inertia must be positive and finite, got " + number(spec.inertia), where,
                "give the moment of inertia about the centre of mass (2D: per unit depth)");
  }
  if (!spec.position.allFinite() || !spec.velocity.allFinite() || !std::isfinite(spec.angle) ||
      !std::isfinite(spec.angular_velocity)) {
    throw Error("the initial position, angle or velocity is not finite", where,
                "check the initial values of the body");
  }
}

double RigidBody2D::initial_coordinate(Coordinate coordinate) const {
  switch (coordinate) {
    case Coordinate::X:
      return spec_.position.x();
    case Coordinate::Y:
      return spec_.position.y();
    case Coordinate::Angle:
      return spec_.angle;
  }
  return 0.0;
}

void RigidBody2D::initial_state(Eigen::Ref<Eigen::VectorXd> q,
                                Eigen::Ref<Eigen::VectorXd> v) const {
  q << spec_.position.x(), spec_.position.y(), spec_.angle;
  v << spec_.velocity.x(), spec_.velocity.y(), spec_.angular_velocity;
}

void RigidBody2D::mass_matrix(MatrixSink& block) const {
  block.add(0, 0, spec_.mass);
  block.add(1, 1, spec_.mass);
  block.add(2, 2, spec_.inertia);
}

void RigidBody2D::add_gravity_force(const Eigen::Vector2d& acceleration,
                                    Eigen::Ref<Eigen::VectorXd> force) const {
  force.head<2>() += spec_.mass * acceleration;
}

double RigidBody2D::gravity_potential(const ConstVector& q,
                                      const Eigen::Vector2d& acceleration) const {
  return -spec_.mass * acceleration.dot(q.head<2>());
}

Eigen::Vector2d RigidBody2D::position(const ConstVector& q, const Eigen::Vector2d& local) const {
  return q.head<2>() + rotate(q(2), local);
}

Eigen::Vector2d RigidBody2D::velocity(const ConstVector& q, const ConstVector& v,
                                      const Eigen::Vector2d& local) const {
  return v.head<2>() + v(2) * rotate_derivative(q(2), local);
}

void RigidBody2D::position_jacobian(const ConstVector& q, const Eigen::Vector2d& local,
                                    Eigen::Ref<Eigen::MatrixXd> jacobian) const {
  jacobian.leftCols<2>().setIdentity();
  jacobian.col(2) = rotate_derivative(q(2), local);
}

void RigidBody2D::velocity_jacobian(const ConstVector& q, const ConstVector& v,
                                    const Eigen::Vector2d& local,
                                    Eigen::Ref<Eigen::MatrixXd> jacobian) const {
  // (dr/dq) v = v_xy + omega R' p; only R' p depends on q: d/dphi = omega R'' p = -omega R p.
  jacobian.leftCols<2>().setZero();
  jacobian.col(2) = -v(2) * rotate(q(2), local);
}

void RigidBody2D::add_point_load_derivative(const ConstVector& q, const Eigen::Vector2d& local,
                                            const Eigen::Vector2d& force,
                                            MatrixSink& derivative) const {
  // Only the torque (R' p) . f depends on q, through phi: d/dphi = (R'' p) . f = -(R p) . f.
  derivative.add(2, 2, -rotate(q(2), local).dot(force));
}

Eigen::Vector2d RigidBody2D::reference_point(const ConstVector& q) const {
  return q.head<2>();
}

}  // namespace fsi::mbd::detail
