#pragma once
// Constraint rows of the 2D connectors beyond the revolute joint (internal; built by
// Model::add_prismatic_joint and Model::add_clamp in model_elements.cpp):
//
//   prismatic row    C = (e x d) / |axis|,  e = r_tip - r_origin,  d = r_slider - r_origin
//                    (2D cross product); origin and tip are two points of body a on the
//                    sliding line, so e = R(phi_a) axis, and the slider point of body b stays
//                    on that line. At consistent states G is the unit normal, lambda a force.
//   relative angle   C = phi_a - phi_b - offset   (phi of the ground: 0), lambda a torque.
//
// A clamp is two PointConstraint rows (the clamped body's centre of mass, constraint.hpp) and one
// relative angle row.

#include <Eigen/Dense>

#include <string>

#include "body_point.hpp"
#include "fsi/mbd/constraint_element.hpp"
#include "sink_elements.hpp"

namespace fsi::mbd::detail {

class PrismaticConstraint final : public ConstraintRow {
 public:
  // |tip - origin| in body a's frame is the axis length the row is divided by.
  PrismaticConstraint(std::string description, BodyPoint origin, BodyPoint tip, BodyPoint slider,
                      double axis_length);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;
  void add_force_derivative_entries(double time, const Eigen::VectorXd& q, double multiplier,
                                    MatrixSink& derivative) const override;

 private:
  struct Geometry {
    Eigen::Vector2d axis;               // e
    Eigen::Vector2d separation;         // d
    SparseColumns axis_jacobian;        // de/dq (2 x n)
    SparseColumns separation_jacobian;  // dd/dq (2 x n)
  };
  Geometry geometry(const Eigen::VectorXd& q) const;

  BodyPoint origin_;
  BodyPoint tip_;
  BodyPoint slider_;
  double axis_length_;
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

// phi_a - phi_b - offset = 0; an angle index < 0 stands for the ground.
class RelativeAngleConstraint final : public LinearConstraintRow {
 public:
  RelativeAngleConstraint(std::string description, int angle_a, int angle_b, double offset);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;

 private:
  int angle_a_;
  int angle_b_;
  double offset_;
};

}  // namespace fsi::mbd::detail
