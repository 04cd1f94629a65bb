#pragma once
// A quantity integrated in time along the solution by the integrator itself, as SUNDIALS calls a
// quadrature: W(t) = integral of g(t, q, v, lambda) dt, e.g. the work of a force element (its
// power Q . v). Each integrator integrates it with its own rule over each of its own steps, so
// the integral is as accurate as the motion it follows and not the trapezoid of a caller's
// output interval:
//   Radau IIA / Lobatto IIIA  h sum_i b_i g(t0 + c_i h, Q_i, V_i), the tableau's quadrature on the
//                             stage values (exact for g a polynomial in t of degree 2s - 2 /
//                             2s - 3; along a motion, as accurate as the stage values),
//   adaptive Radau IIA        that, over the two half steps of every accepted step,
//   IDA                       IDAS' quadrature, the BDF of the motion's steps (not error-tested:
//                             an integrand does not change the steps the motion takes).
// g must be smooth along the motion for those orders, as the forces must.

#include <Eigen/Dense>

#include <functional>

#include "fsi/mbd/constrained_system.hpp"

namespace fsi::mbd {

struct Integrand {
  int size = 0;  // number of integrated values; 0: none
  // Writes the `size` values of g at `state` (time, q, v, lambda) into `values` (sized by the
  // caller).
  std::function<void(const State& state, Eigen::VectorXd& values)> evaluate;
};

}  // namespace fsi::mbd
