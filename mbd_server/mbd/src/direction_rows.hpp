#pragma once
// Constraint rows on body directions (internal; the row interface is
// fsi/mbd/constraint_element.hpp, the common part ConstraintRow in sink_elements.hpp):
//
//   perpendicularity   d_a . d_b = 0 with the spatial body directions d = r(p + u) - r(p), exact
//                      for rigid bodies; two of them keep a revolute joint's axis, three a fixed
//                      joint's orientation; a prismatic joint adds two whose first "direction"
//                      is the offset between points of its two bodies
//   drive              a revolute joint's relative rotation about its axis held at rate * t
//   slope on a body    a beam node's slope held in the frame of a planar rigid body
//
// (The orthonormality rows of a spatial rigid body's own axes are with the body,
// rigid_body_3d.hpp.)

#include <Eigen/Dense>

#include <string>

#include "fsi/mbd/constraint_element.hpp"
#include "sink_elements.hpp"
#include "spatial_body.hpp"

namespace fsi::mbd::detail {

// A body direction as the difference of two of its material points (tip - base); the two points
// may be on different bodies (the offset a prismatic joint holds normal to its axis).
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

// The drive of a spatial revolute joint: body a turns relative to body b about the hinge axis n
// at a prescribed angle phi(t) = rate t. e1, e2 are directions of a normal to n (e1 x e2 = n), u
// the direction of b that coincides with e1 initially; the row
//
//     C = u . (sin(phi) e1 + cos(phi) e2) = sin(phi - theta)
//
// (theta: a's rotation relative to b, the other joint rows holding u normal to n) is smooth, zero
// at theta = phi with dC/dtheta = -1 there: lambda is the torque about n that the drive exerts on
// body a (-lambda on b), N m. Its time dependence: C_t = rate u . (cos(phi) e1 - sin(phi) e2), and
// G, through phi, a function of time.
class RotationDriveConstraint final : public ConstraintRow {
 public:
  RotationDriveConstraint(std::string description, SpatialDirection e1, SpatialDirection e2,
                          SpatialDirection u, double rate);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;
  double explicit_time_derivative(double time, const Eigen::VectorXd& q) const override;
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;
  void add_force_derivative_entries(double time, const Eigen::VectorXd& q, double multiplier,
                                    MatrixSink& derivative) const override;

 private:
  // w = sin(phi) e1 + cos(phi) e2 and its partial time derivative at fixed q.
  Eigen::Vector3d turned(double time, const Eigen::VectorXd& q) const;
  Eigen::Vector3d turned_time_rate(double time, const Eigen::VectorXd& q) const;

  SpatialDirection e1_;
  SpatialDirection e2_;
  SpatialDirection u_;
  double rate_;
};

// A beam node's slope s = r' held in the frame of a planar rigid body with angle phi (a beam
// clamped to a body): the direction row C = (R(phi) m) . s (m the initial normal of the slope in
// the body frame; the stretch stays free), or a component row C = s_k - (R(phi) u)_k (u the
// initial slope in the body frame; two of them hold the slope entirely).
class SlopeOnBodyConstraint final : public ConstraintRow {
 public:
  // component < 0: the direction row with m = `vector`; 0 or 1: the component row with u.
  SlopeOnBodyConstraint(std::string description, int slope_x, int slope_y, int angle,
                        const Eigen::Vector2d& vector, int component);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;
  void add_force_derivative_entries(double time, const Eigen::VectorXd& q, double multiplier,
                                    MatrixSink& derivative) const override;

 private:
  int slope_x_;
  int slope_y_;
  int angle_;
  Eigen::Vector2d vector_;
  int component_;
};

}  // namespace fsi::mbd::detail
