#include "rigid_body_3d.hpp"

#include <cmath>
#include <utility>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"

namespace fsi::mbd::detail {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return m;
}

}  // namespace

RigidBody3D::RigidBody3D(const RigidBody3DSpec& spec) : spec_(spec) {
  const std::string where = "rigid body '" + spec.name + "'";
  if (spec.name.empty()) {
    throw Error("a rigid body has no name", "rigid body", "give every body a unique name");
  }
  if (!(std::isfinite(spec.mass) && spec.mass > 0.0)) {
    throw Error("mass must be positive and finite, got " + significant(spec.mass, 9), where,
                "give the body a positive mass [kg]");
  }
  if (!spec.inertia.allFinite() || !spec.position.allFinite() || !spec.orientation.allFinite() ||
      !spec.velocity.allFinite() || !spec.angular_velocity.allFinite()) {
    throw Error("the inertia, initial position, orientation or velocity is not finite", where,
                "check the body's values");
  }
  const double size = spec.inertia.cwiseAbs().maxCoeff();
  if (!((spec.inertia - spec.inertia.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * size)) {
    throw Error("the inertia tensor is not symmetric", where,
                "give J about the centre of mass in body axes, J_ij = J_ji");
  }
  // E = tr(J)/2 I - J must be positive definite: its eigenvalues are (J_b + J_c - J_a) / 2 in
  // principal axes, the triangle inequality of a real body's moments of inertia, strict so that
  // the mass matrix is regular (a body of zero thickness has E_33 = 0).
  second_moment_ = 0.5 * spec.inertia.trace() * Eigen::Matrix3d::Identity() - spec.inertia;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> moments(second_moment_);
  const Eigen::Vector3d principal =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(spec.inertia).eigenvalues();
  if (!(principal.minCoeff() > 0.0) || !(moments.eigenvalues().minCoeff() > 1e-12 * size)) {
    throw Error("the inertia tensor (principal moments " + significant(principal(0), 9) + ", " +
                    significant(principal(1), 9) + ", " + significant(principal(2), 9) +
                    " kg m^2) is not that of a body with volume: every principal moment must be "
                    "positive and less than the sum of the other two",
                where, "check the inertia tensor; give a flat body a small thickness");
  }
  const Eigen::Matrix3d& r = spec.orientation;
  const double defect = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(defect <= 1e-10) || !(r.determinant() > 0.0)) {
    throw Error("the orientation is not a rotation matrix (|R^T R - I| = " +
                    significant(defect, 9) + ", det R = " + significant(r.determinant(), 9) + ")",
                where,
                "give orthonormal body axes as the columns, right-handed (or an axis and angle "
                "in the scene)");
  }
}

void RigidBody3D::initial_state(Eigen::Ref<Eigen::VectorXd> q,
                                Eigen::Ref<Eigen::VectorXd> v) const {
  q.head<3>() = spec_.position;
  v.head<3>() = spec_.velocity;
  const Eigen::Matrix3d spin = skew(spec_.angular_velocity);
  for (int k = 0; k < 3; ++k) {
    q.segment<3>(3 + 3 * k) = spec_.orientation.col(k);
    v.segment<3>(3 + 3 * k) = spin * spec_.orientation.col(k);  // de_k/dt = omega x e_k
  }
}

void RigidBody3D::mass_matrix(MatrixSink& block) const {
  for (int i = 0; i < 3; ++i)
    block.add(i, i, spec_.mass);
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) {
      for (int i = 0; i < 3; ++i)
        block.add(3 + 3 * k + i, 3 + 3 * l + i, second_moment_(k, l));
    }
  }
}

void RigidBody3D::add_spatial_gravity_force(const Eigen::Vector3d& acceleration,
                                            Eigen::Ref<Eigen::VectorXd> force) const {
  force.head<3>() += spec_.mass * acceleration;
}

double RigidBody3D::spatial_gravity_potential(const ConstVector& q,
                                              const Eigen::Vector3d& acceleration) const {
  return -spec_.mass * acceleration.dot(q.head<3>());
}

Eigen::Vector3d RigidBody3D::spatial_position(const ConstVector& q,
                                              const Eigen::Vector3d& local) const {
  return q.head<3>() + local.x() * q.segment<3>(3) + local.y() * q.segment<3>(6) +
         local.z() * q.segment<3>(9);
}

Eigen::Vector3d RigidBody3D::spatial_velocity(const ConstVector&, const ConstVector& v,
                                              const Eigen::Vector3d& local) const {
  return v.head<3>() + local.x() * v.segment<3>(3) + local.y() * v.segment<3>(6) +
         local.z() * v.segment<3>(9);
}

void RigidBody3D::spatial_position_jacobian(const ConstVector&, const Eigen::Vector3d& local,
                                            Eigen::Ref<Eigen::MatrixXd> jacobian) const {
  jacobian.setZero();
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  jacobian.leftCols<3>() = identity;
  for (int k = 0; k < 3; ++k)
    jacobian.middleCols<3>(3 + 3 * k) = local(k) * identity;
}

PointMass3D::PointMass3D(const PointMassSpec& spec) : spec_(spec) {
  const std::string where = "point mass '" + spec.name + "'";
  if (spec.name.empty()) {
    throw Error("a point mass has no name", "point mass", "give every body a unique name");
  }
  if (!(std::isfinite(spec.mass) && spec.mass > 0.0)) {
    throw Error("mass must be positive and finite, got " + significant(spec.mass, 9), where,
                "give the point mass a positive mass [kg]");
  }
  if (!spec.position.allFinite() || !spec.velocity.allFinite()) {
    throw Error("the initial position or velocity is not finite", where, "check the values");
  }
}

void PointMass3D::initial_state(Eigen::Ref<Eigen::VectorXd> q,
                                Eigen::Ref<Eigen::VectorXd> v) const {
  q = spec_.position;
  v = spec_.velocity;
}

void PointMass3D::mass_matrix(MatrixSink& block) const {
  for (int i = 0; i < 3; ++i)
    block.add(i, i, spec_.mass);
}

void PointMass3D::add_spatial_gravity_force(const Eigen::Vector3d& acceleration,
                                            Eigen::Ref<Eigen::VectorXd> force) const {
  force.head<3>() += spec_.mass * acceleration;
}

double PointMass3D::spatial_gravity_potential(const ConstVector& q,
                                              const Eigen::Vector3d& acceleration) const {
  return -spec_.mass * acceleration.dot(q.head<3>());
}

void PointMass3D::check_spatial_local(const Eigen::Vector3d& local, const std::string& user) const {
  if (!local.isZero(0.0)) {
    throw Error(user + " on point mass '" + spec_.name + "' is at local (" +
                    significant(local.x(), 9) + ", " + significant(local.y(), 9) + ", " +
                    significant(local.z(), 9) +
                    "), but a point mass has only the point local = (0, 0, 0)",
                "point mass '" + spec_.name + "'",
                "attach at (0, 0, 0), or use a RigidBody3D for a body with extent");
  }
}

void PointMass3D::spatial_position_jacobian(const ConstVector&, const Eigen::Vector3d&,
                                            Eigen::Ref<Eigen::MatrixXd> jacobian) const {
  jacobian.setIdentity();
}

OrthonormalityConstraint::OrthonormalityConstraint(std::string description, int offset, int i,
                                                   int j)
    : ConstraintRow(std::move(description)), offset_(offset), i_(i), j_(j) {}

double OrthonormalityConstraint::residual(double, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd&) const {
  const double product = q.segment<3>(first_index()).dot(q.segment<3>(second_index()));
  return i_ == j_ ? 0.5 * (product - 1.0) : product;
}

void OrthonormalityConstraint::add_jacobian_entries(double, const Eigen::VectorXd& q, int row,
                                                    MatrixSink& jacobian) const {
  const int a = first_index();
  const int b = second_index();
  for (int k = 0; k < 3; ++k) {
    if (i_ == j_) {
      jacobian.add(row, a + k, q(a + k));
    } else {
      jacobian.add(row, a + k, q(b + k));
      jacobian.add(row, b + k, q(a + k));
    }
  }
}

double OrthonormalityConstraint::acceleration_remainder(double, const Eigen::VectorXd&,
                                                        const Eigen::VectorXd& v) const {
  const double product = v.segment<3>(first_index()).dot(v.segment<3>(second_index()));
  return i_ == j_ ? product : 2.0 * product;
}

void OrthonormalityConstraint::add_force_derivative_entries(double, const Eigen::VectorXd&,
                                                            double multiplier,
                                                            MatrixSink& derivative) const {
  const int a = first_index();
  const int b = second_index();
  for (int k = 0; k < 3; ++k) {
    if (i_ == j_) {
      derivative.add(a + k, a + k, multiplier);
    } else {
      derivative.add(a + k, b + k, multiplier);
      derivative.add(b + k, a + k, multiplier);
    }
  }
}

}  // namespace fsi::mbd::detail
