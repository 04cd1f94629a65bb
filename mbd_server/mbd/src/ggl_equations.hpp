#pragma once
// The equations of motion of a ConstrainedSystem (fsi::mbd::Model or any other) in the stabilised
// index-2 form of Gear, Gupta and Leimkuhler (GGL), as a fully implicit DAE r(t, y, y') = 0 for
// SUNDIALS IDA (internal; the driver is ida_integrator.cpp, the reasons for this form are in
// docs/theory.md).
//
// Unknowns y = (q, v, lambda, mu): n coordinates, n velocities, one multiplier per constraint
// row (m) and one stabilising multiplier mu per position-level row (p of them, in row order).
// Residual rows, in this order (the last two blocks sit where lambda and mu sit in y):
//     kinematic   q' - v + G_p(q)^T mu                           (n)   [m/s]
//     dynamic     M v' - F(t, q, v) + G(q)^T lambda              (n)   [N]
//     velocity    G v + C_t (position rows), G v - g (velocity rows)   (m)   [m/s]
//     position    C(q, t) of the position rows                  (p)   [m]
// The exact solution has mu = 0: mu only projects q onto C = 0 against the discretisation's
// drift, so both the position and the velocity level hold at every step (no drift), and the
// system has index 2. lambda and mu are algebraic (excluded from IDA's error test).
//
// Iteration matrix dr/dy + c_j dr/dy':
//     kinematic  [c_j I + d(G_p^T mu)/dq,  -I,               0,    G_p^T]
//     dynamic    [d(G^T lambda)/dq - dF/dq, c_j M - dF/dv,   G^T,  0    ]
//     velocity   [d(G v + C_t)/dq,          G,               0,    0    ]
//     position   [G_p,                      0,               0,    0    ]
// d(G v)/dq has the rows v^T H_k (H_k the Hessian of row k, which the constraint elements give
// through add_force_derivative with a unit multiplier); d(C_t)/dq = dG/dt is taken by a central
// difference of G in time (exact for G linear in t; it only affects Newton's convergence rate).
// Velocity-level rows have G independent of q (constraint_element.hpp), so d(G v - g)/dq = 0.
//
// A row released over the bound interval (ConstrainedSystem::release_time) has the residual
// lambda_k (and mu of a position row) instead of its constraint and no G row: the size stays,
// the multipliers are zero. The driver never integrates across a release (it stops there and
// binds again).

#include <Eigen/Dense>

#include <string>
#include <vector>

#include "fsi/mbd/constrained_system.hpp"

namespace fsi::mbd::detail {

class GglEquations {
 public:
  // Binds the model (sizes, which rows are on position level) and the rows released over the
  // interval to be integrated (one flag per row; empty: none).
  void bind(const ConstrainedSystem& system, std::vector<bool> released = {});
  const std::vector<bool>& released() const { return released_; }

  int size() const { return 2 * n_ + m_ + p_; }
  int coordinates() const { return n_; }
  int constraints() const { return m_; }
  int position_rows() const { return p_; }
  // Offsets of the blocks of y (and of the matching residual rows: kinematic, dynamic, position,
  // velocity).
  int q_offset() const { return 0; }
  int v_offset() const { return n_; }
  int lambda_offset() const { return 2 * n_; }
  int mu_offset() const { return 2 * n_ + m_; }

  void residual(double time, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                Eigen::VectorXd& residual);
  // dr/dy + cj dr/dy', written into `jacobian` (size() x size()).
  void jacobian(double time, double cj, const Eigen::VectorXd& y,
                Eigen::Ref<Eigen::MatrixXd> jacobian);

  // Consistent y, y' from q and v at state.time: lambda and the accelerations from
  // [M G^T; G 0] [a; lambda] = [F; -remainder] (the current point loads), mu = 0, q' = v,
  // v' = a, lambda' = mu' = 0. Returns false if that system is singular (redundant rows).
  bool consistent_vectors(const State& state, Eigen::VectorXd& y, Eigen::VectorXd& yp);
  // What residual row `row` is, for error messages: "equation of motion of body 'arm' coordinate
  // angle", "velocity level of <constraint description>", ...
  std::string describe_row(int row) const;
  // What component `index` of y is: "velocity of body 'arm' coordinate angle", "multiplier of
  // <constraint description>", ...
  std::string describe_variable(int index) const;
  // q, v and lambda of y.
  void to_state(const Eigen::VectorXd& y, double time, State& state) const;
  // The element whose force or row is not finite at y (ConstrainedSystem::non_finite_source,
  // with its reason where it knows one); empty when all are.
  std::string non_finite_source(double time, const Eigen::VectorXd& y) const;

 private:
  const ConstrainedSystem* system_ = nullptr;
  int n_ = 0, m_ = 0, p_ = 0;
  std::vector<int> position_rows_;  // constraint index of each mu
  std::vector<bool> released_;
  // Zeroes the released rows of g_ (and of the derivative rows in `matrix`, if given).
  void drop_released_rows(Eigen::MatrixXd& matrix) const;
  // Scratch.
  Eigen::VectorXd q_, v_, lambda_, mu_full_, force_, constraint_, rate_;
  Eigen::MatrixXd g_, g_plus_, g_minus_, by_position_, by_velocity_, derivative_, hessian_;
};

}  // namespace fsi::mbd::detail
