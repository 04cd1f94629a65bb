#pragma once
// The model's constraint elements: coordinate and velocity constraints, and joints between body
// points (internal; the row interface is fsi/mbd/constraint_element.hpp).

#include <Eigen/Dense>

#include <functional>
#include <string>

#include "body_point.hpp"
#include "fsi/mbd/constraint_element.hpp"
#include "fsi/mbd/model.hpp"
#include "sink_elements.hpp"

namespace fsi::mbd::detail {

// The interface is public (fsi/mbd/constraint_element.hpp); the elements here are the model's own.
using Constraint = ConstraintElement;

// q_i - value = 0.
class CoordinateConstraint final : public LinearConstraintRow {
 public:
  CoordinateConstraint(std::string description, int coordinate_index, double value);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;

 private:
  int index_;
  double value_;
};

// sum_k w_k q_(i_k) - value = 0: a fixed linear combination of coordinates (a clamped beam
// slope's direction).
class LinearCoordinateConstraint final : public LinearConstraintRow {
 public:
  LinearCoordinateConstraint(std::string description, Eigen::VectorXi indices,
                             Eigen::VectorXd weights, double value);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;

 private:
  Eigen::VectorXi indices_;
  Eigen::VectorXd weights_;
  double value_;
};

// dq_i/dt - velocity = 0.
class VelocityConstraint final : public LinearConstraintRow {
 public:
  VelocityConstraint(std::string description, int coordinate_index, double velocity);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;

 private:
  int index_;
  double velocity_;
};

class SpatialPoint;

// q_i - s(t) = 0 with the rate s'(t) given; s'' by central differences of s' (initial lambda).
class PrescribedCoordinate final : public ConstraintRow {
 public:
  PrescribedCoordinate(std::string description, int coordinate_index,
                       std::function<double(double)> position, std::function<double(double)> rate);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;
  double explicit_time_derivative(double time, const Eigen::VectorXd&) const override {
    return -rate_(time);
  }
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;

 private:
  int index_;
  std::function<double(double)> position_;
  std::function<double(double)> rate_;
};

// dq_i/dt - g(t) = 0; dg/dt by central differences (initial lambda only).
class TimeVelocityConstraint final : public ConstraintRow {
 public:
  TimeVelocityConstraint(std::string description, int coordinate_index,
                         std::function<double(double)> velocity);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;

 private:
  int index_;
  std::function<double(double)> velocity_;
};

// One component of r_a - r_b = 0: two of them (x, y) make a revolute joint between two body
// points, or fix a body point to the ground; three (x, y, z) a spherical joint between spatial
// points. Point: BodyPoint (D = 2) or SpatialPoint (D = 3), instantiated for both.
template <typename Point, int D>
class BasicPointConstraint final : public ConstraintRow {
 public:
  BasicPointConstraint(std::string description, Point a, Point b, int axis);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;
  void add_force_derivative_entries(double time, const Eigen::VectorXd& q, double multiplier,
                                    MatrixSink& derivative) const override;

 private:
  Point a_;
  Point b_;
  int axis_;
};

using PointConstraint = BasicPointConstraint<BodyPoint, 2>;
using SpatialPointConstraint = BasicPointConstraint<SpatialPoint, 3>;

// A massless rod between two body points (planar or spatial, as above):
// C = (|d|^2 - length^2) / (2 length), d = r_b - r_a.
// The quadratic form is smooth for every d; dividing by 2 length makes G = d^T (dd/dq) / length
// the unit direction e = d / |d| at consistent states, so lambda is the rod force [N]: -G^T lambda
// pulls point a by +lambda e and point b by -lambda e, lambda > 0 is tension.
template <typename Point, int D>
class BasicDistanceConstraint final : public ConstraintRow {
 public:
  BasicDistanceConstraint(std::string description, Point a, Point b, double length);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;
  void add_force_derivative_entries(double time, const Eigen::VectorXd& q, double multiplier,
                                    MatrixSink& derivative) const override;

 private:
  // dd/dq = dr_b/dq - dr_a/dq (D x n).
  PointColumns<D> separation_jacobian(const Eigen::VectorXd& q) const;

  Point a_;
  Point b_;
  double length_;
};

using DistanceConstraint = BasicDistanceConstraint<BodyPoint, 2>;
using SpatialDistanceConstraint = BasicDistanceConstraint<SpatialPoint, 3>;

}  // namespace fsi::mbd::detail
