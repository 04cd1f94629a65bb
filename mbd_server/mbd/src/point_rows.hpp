#pragma once
// Constraint rows between body points (internal; the row interface is
// fsi/mbd/constraint_element.hpp, the common part ConstraintRow in sink_elements.hpp): the point
// rows of revolute and spherical joints and clamps, the massless rod, planar and spatial
// (templates over the point type), and the planar prismatic row.

#include <Eigen/Dense>

#include <string>

#include "body_point.hpp"
#include "fsi/mbd/constraint_element.hpp"
#include "sink_elements.hpp"

namespace fsi::mbd::detail {

class SpatialPoint;

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

// Prismatic row (2D): C = (e x d) / |axis|, e = r_tip - r_origin, d = r_slider - r_origin (2D
// cross product); origin and tip are two points of body a on the sliding line, so
// e = R(phi_a) axis, and the slider point of body b stays on that line. At consistent states G is
// the unit normal, lambda a force. (A prismatic joint adds a relative-angle row, a clamp two point
// rows and one, coordinate_rows.hpp.)
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

}  // namespace fsi::mbd::detail
