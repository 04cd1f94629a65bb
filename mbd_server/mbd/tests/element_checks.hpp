#pragma once
// Finite-difference checks of element derivatives, shared by the connector and force-element
// tests: a constraint row's G, d(G^T lambda)/dq and acceleration remainder, and a force element's
// dQ/dq and dQ/dv, each against central differences of the function it differentiates; and the
// bodies those tests put the elements between.

#include <gtest/gtest.h>

#include <Eigen/SparseCore>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "body.hpp"
#include "body_point.hpp"
#include "error_message.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/constraint_element.hpp"
#include "fsi/mbd/force_element.hpp"
#include "fsi/mbd/model.hpp"

namespace fsi::mbd::testing {

inline RigidBody2DSpec rigid(const std::string& name, double mass, double inertia) {
  RigidBody2DSpec spec;
  spec.name = name;
  spec.mass = mass;
  spec.inertia = inertia;
  return spec;
}

// A 1 kg body at (1, 0) that may only slide along x (y and angle held): one end of a spring
// from the origin.
inline BodyId slider_along_x(Model& model) {
  RigidBody2DSpec spec = rigid("slider", 1.0, 1.0);
  spec.position = {1.0, 0.0};
  const BodyId slider = model.add_rigid_body(spec);
  model.add_coordinate_constraint(slider, Coordinate::Y);
  model.add_coordinate_constraint(slider, Coordinate::Angle);
  return slider;
}

// The slider on a seat whose law jumps at contact (a preload dropped inside the seat: no
// integrator gets past it), and a smooth spring on another body that must not be blamed for it.
inline void slider_on_a_jumping_seat(Model& model) {
  const BodyId slider = slider_along_x(model);
  model.add_nonlinear_spring_damper(
      {.name = "seat",
       .a = {kGround, {0.0, 0.0}},
       .b = {slider, {0.0, 0.0}},
       .tension = [](double e, double, double) { return e < 0.0 ? 1e3 * e : 5.0 + 10.0 * e; },
       .rest_length = 1.0});
  RigidBody2DSpec spec = rigid("other", 1.0, 1.0);
  spec.position = {0.0, 3.0};
  const BodyId other = model.add_rigid_body(spec);
  model.add_nonlinear_spring_damper({.name = "smooth",
                                     .a = {kGround, {0.0, 2.0}},
                                     .b = {other, {0.0, 0.0}},
                                     .tension = [](double e, double, double) { return 10.0 * e; }});
}

// Two bodies at a general configuration with general velocities, q = (x, y, phi) of each.
struct BodyPair {
  detail::RigidBody2D first{rigid("first", 2.0, 0.3)};
  detail::RigidBody2D second{rigid("second", 1.5, 0.2)};
  Eigen::VectorXd q{{0.3, -0.2, 0.7, 1.1, 0.4, -2.1}};
  Eigen::VectorXd v{{0.5, -1.5, 2.0, -0.7, 0.9, 3.0}};

  // The ends an element test runs over: body-body, body-ground and ground-body.
  std::vector<std::pair<detail::BodyPoint, detail::BodyPoint>> point_pairs() const {
    const detail::BodyPoint on_first(&first, 0, {0.2, -0.15});
    const detail::BodyPoint on_second(&second, 3, {-0.1, 0.35});
    const detail::BodyPoint on_ground(nullptr, 0, {-0.4, 0.25});
    return {{on_first, on_second}, {on_first, on_ground}, {on_ground, on_second}};
  }
};

// At `time`: differences of C for G (to 1e-9), of G for mu d(G^T)/dq (to 1e-8), of C in time for
// the explicit dC/dt of a position row (to 1e-8), and the second difference of C along
// (q + v s, time + s) for the acceleration remainder (relative 1e-6).
inline void expect_exact_row_derivatives(const ConstraintElement& row, const Eigen::VectorXd& q,
                                         const Eigen::VectorXd& v, const std::string& what,
                                         double time = 0.0) {
  const auto n = q.size();
  const double step = 1e-6;
  const double multiplier = -2.3;
  auto jacobian_at = [&](const Eigen::VectorXd& position) {
    Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(1, n);
    row.jacobian_row(time, position, jacobian.row(0));
    return Eigen::RowVectorXd(jacobian.row(0));
  };
  const Eigen::RowVectorXd g = jacobian_at(q);
  Eigen::MatrixXd force_derivative = Eigen::MatrixXd::Zero(n, n);
  row.add_force_derivative(time, q, multiplier, force_derivative);
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::VectorXd plus = q, minus = q;
    plus(j) += step;
    minus(j) -= step;
    const double by_difference =
        (row.residual(time, plus, v) - row.residual(time, minus, v)) / (2.0 * step);
    EXPECT_NEAR(g(j), by_difference, 1e-9) << what << ": G(" << j << ")";
    const Eigen::RowVectorXd g_by_difference =
        (jacobian_at(plus) - jacobian_at(minus)) / (2.0 * step);
    for (Eigen::Index i = 0; i < n; ++i) {
      EXPECT_NEAR(force_derivative(i, j), multiplier * g_by_difference(i), 1e-8)
          << what << ": d(G^T lambda)/dq(" << i << ", " << j << ")";
    }
  }
  if (row.level() == ConstraintLevel::Position) {
    const double by_time =
        (row.residual(time + step, q, v) - row.residual(time - step, q, v)) / (2.0 * step);
    EXPECT_NEAR(row.explicit_time_derivative(time, q), by_time, 1e-8) << what << ": explicit dC/dt";
  }
  const double dt = 1e-4;
  const double second = (row.residual(time + dt, q + dt * v, v) - 2.0 * row.residual(time, q, v) +
                         row.residual(time - dt, q - dt * v, v)) /
                        (dt * dt);
  EXPECT_NEAR(row.acceleration_remainder(time, q, v), second, 1e-6 * (1.0 + std::abs(second)))
      << what << ": acceleration remainder";
}

// dQ/dq and dQ/dv against central differences of Q, relative 1e-6 (plus 1e-6 absolute).
inline void expect_exact_force_derivatives(const ForceElement& element, double time,
                                           const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                           const std::string& what) {
  const auto n = q.size();
  Eigen::MatrixXd by_position = Eigen::MatrixXd::Zero(n, n), by_velocity = by_position;
  ASSERT_TRUE(element.add_jacobians(time, q, v, by_position, by_velocity)) << what;
  const double step = 1e-6;
  auto force_at = [&](const Eigen::VectorXd& position, const Eigen::VectorXd& velocity) {
    Eigen::VectorXd force = Eigen::VectorXd::Zero(n);
    element.add_force(time, position, velocity, force);
    return force;
  };
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::VectorXd plus = q, minus = q;
    plus(j) += step;
    minus(j) -= step;
    const Eigen::VectorXd by_q = (force_at(plus, v) - force_at(minus, v)) / (2.0 * step);
    plus = v;
    minus = v;
    plus(j) += step;
    minus(j) -= step;
    const Eigen::VectorXd by_v = (force_at(q, plus) - force_at(q, minus)) / (2.0 * step);
    for (Eigen::Index i = 0; i < n; ++i) {
      EXPECT_NEAR(by_position(i, j), by_q(i), 1e-6 * (1.0 + std::abs(by_q(i))))
          << what << ": dQ/dq(" << i << ", " << j << ")";
      EXPECT_NEAR(by_velocity(i, j), by_v(i), 1e-6 * (1.0 + std::abs(by_v(i))))
          << what << ": dQ/dv(" << i << ", " << j << ")";
    }
  }
}

// The sparse model matrices (dF/dq, dF/dv, G, d(G^T lambda)/dq, M) against the dense ones.
inline void expect_sparse_model_matrices_equal(const Model& model, const State& state) {
  Eigen::MatrixXd dense_position, dense_velocity, dense_g, dense_derivative;
  Eigen::SparseMatrix<double> sparse_position, sparse_velocity, sparse_g, sparse_derivative;
  model.applied_force_derivatives(0.1, state.q, state.v, dense_position, dense_velocity);
  model.applied_force_derivatives(0.1, state.q, state.v, sparse_position, sparse_velocity);
  model.constraint_jacobian(0.1, state.q, dense_g);
  model.constraint_jacobian(0.1, state.q, sparse_g);
  const Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(model.constraint_count(), -2.0, 3.0);
  model.constraint_force_derivative(0.1, state.q, lambda, dense_derivative);
  model.constraint_force_derivative(0.1, state.q, lambda, sparse_derivative);
  auto difference = [](const Eigen::MatrixXd& dense, const Eigen::SparseMatrix<double>& sparse) {
    const double size = dense.lpNorm<Eigen::Infinity>();
    return (dense - Eigen::MatrixXd(sparse)).lpNorm<Eigen::Infinity>() / (size > 0 ? size : 1.0);
  };
  EXPECT_LE(difference(dense_position, sparse_position), 1e-14);
  EXPECT_LE(difference(dense_velocity, sparse_velocity), 1e-14);
  EXPECT_LE(difference(dense_g, sparse_g), 1e-15);
  EXPECT_LE(difference(dense_derivative, sparse_derivative), 1e-14);
  EXPECT_EQ(Eigen::MatrixXd(model.sparse_mass_matrix()), model.mass_matrix());
  EXPECT_EQ(model.mass_diagonal(), model.mass_matrix().diagonal());
}

}  // namespace fsi::mbd::testing
