#pragma once
// Force elements of connectors and time-dependent loads (internal; built in
// model_elements.cpp). All give exact dQ/dq and dQ/dv, except where a user function is
// differentiated by central differences (UserTension).
//
//   RotationalSpringDamper   torque on a: T = -f(phi_a - phi_b - phi_0, omega_a - omega_b), -T on
//                            b (an angle index < 0 is the ground), f a TensionLaw: the linear
//                            k twist + c rate, or a user function
//   PointForce, Torque       f(t) at a body point (world frame), tau(t) on a body angle
//   SpatialTorque            tau(t) on a spatial rigid body in natural coordinates

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "body_point.hpp"
#include "fsi/mbd/force_element.hpp"
#include "measured_force.hpp"
#include "sink_elements.hpp"
#include "tension_law.hpp"

namespace fsi::mbd::detail {

class RotationalSpringDamper final : public SparseForceElement, public MeasuredForce {
 public:
  // The law's "elongation" is the twist phi_a - phi_b - rest_angle [rad], its "rate" the twist's
  // rate [rad/s], its value the torque resisting the twist [N m].
  RotationalSpringDamper(std::string description, int angle_a, int angle_b, double rest_angle,
                         std::shared_ptr<const TensionLaw> law);

  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                 Eigen::VectorXd& force) const override;
  bool add_jacobian_entries(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            MatrixSink& force_by_position,
                            MatrixSink& force_by_velocity) const override;
  double potential_energy(double time, const Eigen::VectorXd& q) const override;
  bool user_law() const override { return law_->user(); }
  // The torque on body a [N m].
  double measured_force(double time, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& v) const override;

 private:
  double angle(const Eigen::VectorXd& x, int index) const { return index >= 0 ? x(index) : 0.0; }
  double twist(const Eigen::VectorXd& q) const {
    return angle(q, angle_a_) - angle(q, angle_b_) - rest_angle_;
  }
  double twist_rate(const Eigen::VectorXd& v) const {
    return angle(v, angle_a_) - angle(v, angle_b_);
  }

  int angle_a_;
  int angle_b_;
  double rest_angle_;
  std::shared_ptr<const TensionLaw> law_;
};

// A force that is a function of time at a body point: Q = (dr/dq)^T f(t). Point: BodyPoint (D = 2)
// or SpatialPoint (D = 3).
template <typename Point, int D>
class BasicPointForce final : public SparseForceElement {
 public:
  using Vector = Eigen::Matrix<double, D, 1>;
  BasicPointForce(std::string description, Point point, std::function<Vector(double)> force)
      : SparseForceElement(std::move(description)), point_(point), force_(std::move(force)) {}

  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                 Eigen::VectorXd& force) const override {
    point_.add_load(q, force_(time), force);
  }
  bool add_jacobian_entries(double time, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                            MatrixSink& force_by_position, MatrixSink&) const override {
    point_.add_load_derivative(q, force_(time), force_by_position);
    return true;
  }

 private:
  Point point_;
  std::function<Vector(double)> force_;
};

using PointForce = BasicPointForce<BodyPoint, 2>;
class SpatialPoint;
using SpatialPointForce = BasicPointForce<SpatialPoint, 3>;

class Torque final : public SparseForceElement {
 public:
  Torque(std::string description, int angle, std::function<double(double)> torque);

  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                 Eigen::VectorXd& force) const override;
  bool add_jacobian_entries(double, const Eigen::VectorXd&, const Eigen::VectorXd&, MatrixSink&,
                            MatrixSink&) const override {
    return true;  // independent of q and v
  }

 private:
  int angle_;
  std::function<double(double)> torque_;
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
