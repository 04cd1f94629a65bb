#pragma once
// Extension point for generalised forces that depend on time, coordinates and velocities
// (springs, dampers, actuators). Gravity and point loads are built into fsi::mbd::Model.

#include <Eigen/Dense>

#include <string>

#include "fsi/mbd/matrix_sink.hpp"

namespace fsi::mbd {

class ForceElement {
 public:
  virtual ~ForceElement() = default;

  // Adds this element's generalised force Q(t, q, v) to `force` (size n = coordinate count).
  virtual void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                         Eigen::VectorXd& force) const = 0;

  // Dense form (the model calls add_jacobian_entries below, which forwards to this one unless
  // overridden): adds dQ/dq to `force_by_position` and dQ/dv to `force_by_velocity` (both n x n)
  // and returns true. The default returns false and adds nothing: the model then differentiates
  // add_force by central differences. Analytic derivatives only make Newton cheaper, never more
  // accurate: the converged solution depends on add_force alone.
  virtual bool add_jacobians(double /*time*/, const Eigen::VectorXd& /*q*/,
                             const Eigen::VectorXd& /*v*/, Eigen::MatrixXd& /*force_by_position*/,
                             Eigen::MatrixXd& /*force_by_velocity*/) const {
    return false;
  }

  // The same derivatives as entries at global (row, column) of the sinks: what the model
  // assembles (dense for small systems, sparse for large ones). The model's own elements write
  // only their non-zeros. The default is a dense fallback for elements that only implement
  // add_jacobians: it calls add_jacobians on n x n scratch matrices and forwards their non-zeros,
  // O(n^2) per element; override it for elements of large models.
  virtual bool add_jacobian_entries(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                    MatrixSink& force_by_position,
                                    MatrixSink& force_by_velocity) const {
    const auto n = q.size();
    Eigen::MatrixXd by_position = Eigen::MatrixXd::Zero(n, n);
    Eigen::MatrixXd by_velocity = Eigen::MatrixXd::Zero(n, n);
    if (!add_jacobians(time, q, v, by_position, by_velocity)) return false;
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index i = 0; i < n; ++i) {
        const int row = static_cast<int>(i), column = static_cast<int>(j);
        if (by_position(i, j) != 0.0) force_by_position.add(row, column, by_position(i, j));
        if (by_velocity(i, j) != 0.0) force_by_velocity.add(row, column, by_velocity(i, j));
      }
    }
    return true;
  }

  // True when the force is a user's function of the coordinates or velocities (a spring law
  // written in a scene): Newton needs it continuous, which only its author can see to; the
  // integrators' messages name such elements where Newton fails.
  virtual bool user_law() const { return false; }
  // Names the element in messages (non-finite forces, sensors).
  virtual std::string description() const { return "force element"; }
  // Why add_force is not finite at this state, when the element knows (a measure it cannot take
  // there); empty otherwise. Messages append it to the description.
  virtual std::string non_finite_reason(double /*time*/, const Eigen::VectorXd& /*q*/,
                                        const Eigen::VectorXd& /*v*/) const {
    return {};
  }
  // The elastic energy stored in the element at q (zero for non-conservative elements); summed
  // into Model::potential_energy.
  virtual double potential_energy(double /*time*/, const Eigen::VectorXd& /*q*/) const {
    return 0.0;
  }
};

}  // namespace fsi::mbd
