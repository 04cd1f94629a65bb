#pragma once
// Spatial rigid body in natural coordinates and the point mass (internal; specs and equations
// in fsi/mbd/model.hpp and docs/theory.md, "Spatial bodies").
//
// RigidBody3D: q = (r, e1, e2, e3), 12 coordinates; a body point p is r + p1 e1 + p2 e2 + p3 e3,
// so dr/dq = [I, p1 I, p2 I, p3 I] is constant. With r at the centre of mass the kinetic energy
// 1/2 integral rho |dr/dt + sum p_k de_k/dt|^2 dV gives the constant mass matrix
// diag(m I, E (x) I), E_kl = integral rho p_k p_l dV = tr(J)/2 delta_kl - J_kl. The rotation is
// kept orthonormal by six constraint rows (OrthonormalityConstraint).

#include <Eigen/Dense>

#include <string>

#include "fsi/mbd/constraint_element.hpp"
#include "fsi/mbd/model.hpp"
#include "sink_elements.hpp"
#include "spatial_body.hpp"

namespace fsi::mbd::detail {

class RigidBody3D final : public SpatialBody {
 public:
  explicit RigidBody3D(const RigidBody3DSpec& spec);  // throws fsi::Error for invalid values

  const RigidBody3DSpec& spec() const { return spec_; }
  // The second moment E of the mass about the centre of mass in body axes.
  const Eigen::Matrix3d& second_moment() const { return second_moment_; }

  const std::string& name() const override { return spec_.name; }
  int coordinate_count() const override { return 12; }
  void initial_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> v) const override;
  using Body::mass_matrix;
  void mass_matrix(MatrixSink& block) const override;
  void add_spatial_gravity_force(const Eigen::Vector3d& acceleration,
                                 Eigen::Ref<Eigen::VectorXd> force) const override;
  double spatial_gravity_potential(const ConstVector& q,
                                   const Eigen::Vector3d& acceleration) const override;
  void check_spatial_local(const Eigen::Vector3d&, const std::string&) const override {}
  Eigen::Vector3d spatial_position(const ConstVector& q,
                                   const Eigen::Vector3d& local) const override;
  Eigen::Vector3d spatial_velocity(const ConstVector& q, const ConstVector& v,
                                   const Eigen::Vector3d& local) const override;
  void spatial_position_jacobian(const ConstVector& q, const Eigen::Vector3d& local,
                                 Eigen::Ref<Eigen::MatrixXd> jacobian) const override;
  Eigen::Vector3d spatial_reference_point(const ConstVector& q) const override {
    return q.head<3>();
  }

 private:
  RigidBody3DSpec spec_;
  Eigen::Matrix3d second_moment_;
};

class PointMass3D final : public SpatialBody {
 public:
  explicit PointMass3D(const PointMassSpec& spec);  // throws fsi::Error for invalid values

  const PointMassSpec& spec() const { return spec_; }
  const std::string& name() const override { return spec_.name; }
  int coordinate_count() const override { return 3; }
  void initial_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> v) const override;
  using Body::mass_matrix;
  void mass_matrix(MatrixSink& block) const override;
  void add_spatial_gravity_force(const Eigen::Vector3d& acceleration,
                                 Eigen::Ref<Eigen::VectorXd> force) const override;
  double spatial_gravity_potential(const ConstVector& q,
                                   const Eigen::Vector3d& acceleration) const override;
  // Only local = 0 (the mass has no extent).
  void check_spatial_local(const Eigen::Vector3d& local, const std::string& user) const override;
  Eigen::Vector3d spatial_position(const ConstVector& q, const Eigen::Vector3d&) const override {
    return q.head<3>();
  }
  Eigen::Vector3d spatial_velocity(const ConstVector&, const ConstVector& v,
                                   const Eigen::Vector3d&) const override {
    return v.head<3>();
  }
  void spatial_position_jacobian(const ConstVector& q, const Eigen::Vector3d& local,
                                 Eigen::Ref<Eigen::MatrixXd> jacobian) const override;
  Eigen::Vector3d spatial_reference_point(const ConstVector& q) const override {
    return q.head<3>();
  }

 private:
  PointMassSpec spec_;
};

// One of the six rows e_i . e_j = delta_ij of a RigidBody3D whose coordinates start at `offset`
// (e_k at offset + 3 + 3 (k - 1)). Written 1/2 (e_i . e_i - 1) for i = j so that G has unit
// entries at consistent states.
class OrthonormalityConstraint final : public ConstraintRow {
 public:
  OrthonormalityConstraint(std::string description, int offset, int i, int j);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;
  void add_force_derivative_entries(double time, const Eigen::VectorXd& q, double multiplier,
                                    MatrixSink& derivative) const override;

 private:
  int first_index() const { return offset_ + 3 * (i_ + 1); }
  int second_index() const { return offset_ + 3 * (j_ + 1); }

  int offset_;
  int i_;
  int j_;
};

}  // namespace fsi::mbd::detail
