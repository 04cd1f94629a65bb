#pragma once
// Constraint rows between points of spatial bodies (internal; built in model_spatial.cpp), beyond
// the point and distance rows the planar ones share (constraint.hpp: SpatialPointConstraint,
// SpatialDistanceConstraint):
//
//   perpendicularity   d_a . d_b = 0 with the body directions d = r(p + u) - r(p), exact for
//                      rigid bodies; two of them keep a revolute joint's axis

#include <Eigen/Dense>

#include <functional>
#include <string>

#include "constraint.hpp"
#include "fsi/mbd/constraint_element.hpp"
#include "fsi/mbd/force_element.hpp"
#include "sink_elements.hpp"
#include "spatial_body.hpp"

namespace fsi::mbd::detail {

// A body direction as the difference of two of its material points (tip - base).
struct SpatialDirection {
  SpatialPoint base;
  SpatialPoint tip;
  Eigen::Vector3d value(const Eigen::VectorXd& q) const {
    return tip.position(q) - base.position(q);
  }
  Eigen::Vector3d rate(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
    return tip.velocity(q, v) - base.velocity(q, v);
  }
  SpatialColumns jacobian(const Eigen::VectorXd& q) const;
  Eigen::Vector3d acceleration_remainder(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
    return tip.acceleration_remainder(q, v) - base.acceleration_remainder(q, v);
  }
  void add_load_derivative(const Eigen::VectorXd& q, const Eigen::Vector3d& force,
                           MatrixSink& derivative) const {
    tip.add_load_derivative(q, force, derivative);
    base.add_load_derivative(q, -force, derivative);
  }
};

class PerpendicularityConstraint final : public ConstraintRow {
 public:
  PerpendicularityConstraint(std::string description, SpatialDirection a, SpatialDirection b);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;
  void add_force_derivative_entries(double time, const Eigen::VectorXd& q, double multiplier,
                                    MatrixSink& derivative) const override;

 private:
  SpatialDirection a_;
  SpatialDirection b_;
};

// A time-dependent torque on a spatial rigid body (the point force is force_elements.hpp's
// SpatialPointForce).
// On a RigidBody3D whose axes e_1..e_3 start at q(axes_offset): Q_(e_k) = 1/2 tau x e_k.
class SpatialTorque final : public SparseForceElement {
 public:
  SpatialTorque(std::string description, int axes_offset,
                std::function<Eigen::Vector3d(double)> torque);
  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                 Eigen::VectorXd& force) const override;
  bool add_jacobian_entries(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            MatrixSink& force_by_position,
                            MatrixSink& force_by_velocity) const override;

 private:
  int axes_offset_;
  std::function<Eigen::Vector3d(double)> torque_;
};

}  // namespace fsi::mbd::detail
