#pragma once
// A force along the line between two body points (either may be a ground point), planar or
// spatial, whose tension is a TensionLaw of the elongation, its rate and the time, with exact
// derivatives for the Newton matrix up to the law's own (internal; built by Model's
// add_spring_damper, add_nonlinear_spring_damper, add_spring_actor and their spatial forms).
// One element, several laws: the linear spring-damper is this element with LinearTension.
//
//     d = r_b - r_a, l = |d|, e = d / l, l' = e . (dr_b/dt - dr_a/dt)
//     tension T = law(l - rest_length, l', t)
//     force on point a: +T e, on point b: -T e (a stretched spring pulls the points together)

#include <memory>
#include <string>

#include "body_point.hpp"
#include "fsi/mbd/force_element.hpp"
#include "measured_force.hpp"
#include "sink_elements.hpp"
#include "tension_law.hpp"

namespace fsi::mbd::detail {

// Point: BodyPoint (D = 2, planar) or SpatialPoint (D = 3); explicitly instantiated for both.
template <typename Point, int D>
class BasicPointToPointForce final : public SparseForceElement, public MeasuredForce {
 public:
  using Vector = Eigen::Matrix<double, D, 1>;
  using Matrix = Eigen::Matrix<double, D, D>;
  BasicPointToPointForce(std::string description, Point a, Point b, double rest_length,
                         std::shared_ptr<const TensionLaw> law);

  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                 Eigen::VectorXd& force) const override;
  bool add_jacobian_entries(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            MatrixSink& force_by_position,
                            MatrixSink& force_by_velocity) const override;
  // The law's work from the rest length to the current length at zero rate.
  double potential_energy(double time, const Eigen::VectorXd& q) const override;
  bool user_law() const override { return law_->user(); }
  // The tension T [N].
  double measured_force(double time, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& v) const override;

 private:
  Point a_;
  Point b_;
  double rest_length_;
  std::shared_ptr<const TensionLaw> law_;
};

using PointToPointForce = BasicPointToPointForce<BodyPoint, 2>;
class SpatialPoint;
using SpatialPointToPointForce = BasicPointToPointForce<SpatialPoint, 3>;

}  // namespace fsi::mbd::detail
