#pragma once
// Force elements for the tests: a linear spring with analytic derivatives and a nonlinear
// element that leaves its derivatives to the model's finite differences.

#include <cmath>

#include "fsi/mbd/force_element.hpp"

namespace fsi::mbd::testing {

// Q_i -= stiffness * q_i.
class LinearSpring final : public ForceElement {
 public:
  LinearSpring(int coordinate, double stiffness) : coordinate_(coordinate), stiffness_(stiffness) {}
  void add_force(double, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                 Eigen::VectorXd& force) const override {
    force(coordinate_) -= stiffness_ * q(coordinate_);
  }
  bool add_jacobians(double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                     Eigen::MatrixXd& by_position, Eigen::MatrixXd&) const override {
    by_position(coordinate_, coordinate_) -= stiffness_;
    return true;
  }

 private:
  int coordinate_;
  double stiffness_;
};

// A nonlinear, velocity- and time-dependent coupling of two coordinates (no analytic
// derivatives): Q_a += sin(q_b) v_a^2 + t, Q_b -= q_a^3 v_b.
class NonlinearCoupling final : public ForceElement {
 public:
  NonlinearCoupling(int a, int b) : a_(a), b_(b) {}
  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                 Eigen::VectorXd& force) const override {
    force(a_) += std::sin(q(b_)) * v(a_) * v(a_) + time;
    force(b_) -= q(a_) * q(a_) * q(a_) * v(b_);
  }

 private:
  int a_;
  int b_;
};

}  // namespace fsi::mbd::testing
