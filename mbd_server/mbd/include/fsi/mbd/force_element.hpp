#pragma once
// Extension point for generalised forces that depend on time, coordinates and velocities
// (springs, dampers, actuators). Gravity and point loads are built into fsi::mbd::Model.

#include <Eigen/Dense>

#include <string>

namespace fsi::mbd {

class ForceElement {
 public:
  virtual ~ForceElement() = default;

  // Adds this element's generalised force Q(t, q, v) to `force` (size n = coordinate count).
  virtual void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                         Eigen::VectorXd& force) const = 0;

  // Adds dQ/dq to `force_by_position` and dQ/dv to `force_by_velocity` (both n x n) and returns
  // true. The default returns false and adds nothing: the model then differentiates add_force by
  // central differences. Analytic derivatives only make Newton cheaper, never more accurate: the
  // converged solution depends on add_force alone.
  virtual bool add_jacobians(double /*time*/, const Eigen::VectorXd& /*q*/,
                             const Eigen::VectorXd& /*v*/, Eigen::MatrixXd& /*force_by_position*/,
                             Eigen::MatrixXd& /*force_by_velocity*/) const {
    return false;
  }

  // Names the element in messages (non-finite forces, sensors).
  virtual std::string description() const { return "force element"; }
  // The elastic energy stored in the element at q (zero for non-conservative elements); summed
  // into Model::potential_energy.
  virtual double potential_energy(const Eigen::VectorXd& /*q*/) const { return 0.0; }
};

}  // namespace fsi::mbd
