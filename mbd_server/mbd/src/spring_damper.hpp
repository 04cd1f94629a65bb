#pragma once
// Linear spring-damper between two body points (either may be a ground point), planar or
// spatial, acting along the line between them, with exact derivatives for the Newton matrix
// (internal; built by Model::add_spring_damper).
//
//     d = r_b - r_a, l = |d|, e = d / l, l' = e . (dr_b/dt - dr_a/dt)
//     tension T = stiffness (l - rest_length) + damping l'
//     force on point a: +T e, on point b: -T e (a stretched spring pulls the points together)

#include "body_point.hpp"
#include "fsi/mbd/force_element.hpp"
#include "measured_force.hpp"
#include "sink_elements.hpp"

namespace fsi::mbd::detail {

// Point: BodyPoint (D = 2, planar) or SpatialPoint (D = 3); explicitly instantiated for both.
template <typename Point, int D>
class BasicSpringDamper final : public SparseForceElement, public MeasuredForce {
 public:
  using Vector = Eigen::Matrix<double, D, 1>;
  using Matrix = Eigen::Matrix<double, D, D>;
  BasicSpringDamper(Point a, Point b, double stiffness, double damping, double rest_length);

  // Tension T at (q, v) [N].
  double tension(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;

  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                 Eigen::VectorXd& force) const override;
  bool add_jacobian_entries(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            MatrixSink& force_by_position,
                            MatrixSink& force_by_velocity) const override;
  // k (l - rest_length)^2 / 2.
  double potential_energy(double time, const Eigen::VectorXd& q) const override;
  double measured_force(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override {
    return tension(q, v);
  }

 private:
  Point a_;
  Point b_;
  double stiffness_;
  double damping_;
  double rest_length_;
};

using SpringDamper = BasicSpringDamper<BodyPoint, 2>;
class SpatialPoint;
using SpatialSpringDamper = BasicSpringDamper<SpatialPoint, 3>;

}  // namespace fsi::mbd::detail
