#pragma once
// A rotational spring-damper between two spatial rigid bodies (or a body and the ground) about an
// axis n fixed in body a (internal; built by Model::add_spatial_rotational_spring_damper, the
// spatial counterpart of the planar RotationalSpringDamper in force_elements.hpp).
//
// e1, e2 are unit directions of a normal to n (e1 x e2 = n), u the unit direction of b that
// coincides with e1 initially. With x = u . e1, y = u . e2 (bilinear in the natural coordinates)
//
//     theta = atan2(-y, x)             a's rotation relative to b about n, 0 initially
//     twist = theta - rest_angle       wrapped into (-pi, pi]
//     g     = d theta / dq = (y grad x - x grad y) / rho^2,   rho^2 = x^2 + y^2
//     T     = law(twist, g . v, t)     the torque resisting the twist [N m]
//     Q     = -T g                     on a: -T about n, on b: +T (exact: Q = -dE/dq for E = the
//                                      law's energy, whatever b's tilt)
//
// With a revolute joint about n the twist is the hinge angle; otherwise it is the angle of u's
// projection on the plane normal to n, which loses its meaning where u turns into the axis (a
// non-finite force, with the reason). The twist is measured within half a turn of the rest
// angle: a law that depends on it, or differs at +180 and -180 degrees (a one-sided stop), is
// refused beyond +-170 degrees (at +-180 the torque would jump); a pure damper turns any number
// of times.

#include <memory>
#include <string>
#include <vector>

#include "direction_rows.hpp"
#include "fsi/mbd/force_element.hpp"
#include "measured_force.hpp"
#include "sink_elements.hpp"
#include "tension_law.hpp"

namespace fsi::mbd::detail {

class SpatialRotationalSpringDamper final : public SparseForceElement, public MeasuredForce {
 public:
  // The largest twist [rad] a law that depends on it may reach (170 degrees).
  static constexpr double kTwistLimit = 170.0 / 180.0 * 3.14159265358979323846;

  SpatialRotationalSpringDamper(std::string description, SpatialDirection e1, SpatialDirection e2,
                                SpatialDirection u, double rest_angle,
                                std::shared_ptr<const TensionLaw> law);

  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                 Eigen::VectorXd& force) const override;
  bool add_jacobian_entries(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            MatrixSink& force_by_position,
                            MatrixSink& force_by_velocity) const override;
  double potential_energy(double time, const Eigen::VectorXd& q) const override;
  bool user_law() const override { return law_->user(); }
  std::string non_finite_reason(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;
  // The torque on body a about the axis [N m].
  double measured_force(double time, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& v) const override;

  // The twist [rad] and its rate [rad/s] (tests and sensors).
  double twist(const Eigen::VectorXd& q) const;
  double twist_rate(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;

 private:
  // The twist and its first and second derivatives in the coordinates the directions depend on.
  struct Kinematics {
    std::vector<int> columns;  // global indices of the local coordinates
    double twist = 0.0;
    double rho = 0.0;          // |projection of u on the plane normal to the axis|
    Eigen::VectorXd gradient;  // d theta / dq (local)
    Eigen::MatrixXd hessian;   // d^2 theta / dq^2 (local, symmetric)
    double rate(const Eigen::VectorXd& v) const;
  };
  Kinematics kinematics(const Eigen::VectorXd& q, bool with_hessian) const;
  // Why the force is not finite at this state (empty when it is); `law` at the twist and rate.
  std::string problem(const Kinematics& k, const Tension& law, double rate, double time) const;

  SpatialDirection e1_;
  SpatialDirection e2_;
  SpatialDirection u_;
  double rest_angle_;
  std::shared_ptr<const TensionLaw> law_;
};

}  // namespace fsi::mbd::detail
