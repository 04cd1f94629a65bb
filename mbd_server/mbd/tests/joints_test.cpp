// The joint and spring-damper elements against finite differences: G against differences of C,
// d(G^T lambda)/dq against differences of G, the acceleration remainder against the second
// difference of C along q + v t, and the spring-damper's dQ/dq, dQ/dv against differences of Q.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "body.hpp"
#include "body_point.hpp"
#include "constraint.hpp"
#include "fsi/common/error.hpp"
#include "spring_damper.hpp"

namespace fsi::mbd {
namespace {

struct TwoBodies {
  std::unique_ptr<detail::RigidBody2D> first;
  std::unique_ptr<detail::RigidBody2D> second;
  Eigen::VectorXd q;
  Eigen::VectorXd v;
};

TwoBodies two_bodies() {
  RigidBody2DSpec spec;
  spec.name = "a";
  spec.mass = 2.0;
  spec.inertia = 0.3;
  TwoBodies bodies{std::make_unique<detail::RigidBody2D>(spec), nullptr, {}, {}};
  spec.name = "b";
  bodies.second = std::make_unique<detail::RigidBody2D>(spec);
  bodies.q.resize(6);
  bodies.v.resize(6);
  bodies.q << 0.3, -0.2, 0.7, 1.1, 0.4, -2.1;
  bodies.v << 0.5, -1.5, 2.0, -0.7, 0.9, 3.0;
  return bodies;
}

// The pairs of points a test runs over: body-body and body-ground in both orders.
std::vector<std::pair<detail::BodyPoint, detail::BodyPoint>> point_pairs(const TwoBodies& b) {
  const detail::BodyPoint on_first(b.first.get(), 0, {0.2, -0.15});
  const detail::BodyPoint on_second(b.second.get(), 3, {-0.1, 0.35});
  const detail::BodyPoint on_ground(nullptr, 0, {-0.4, 0.25});
  return {{on_first, on_second}, {on_first, on_ground}, {on_ground, on_second}};
}

Eigen::RowVectorXd row_of(const ConstraintElement& c, const Eigen::VectorXd& q) {
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(1, q.size());
  c.jacobian_row(0.0, q, g.row(0));
  return g.row(0);
}

void expect_constraint_derivatives_exact(const ConstraintElement& c, const Eigen::VectorXd& q,
                                         const Eigen::VectorXd& v, const std::string& what) {
  const int n = static_cast<int>(q.size());
  const double step = 1e-6;
  const Eigen::RowVectorXd g = row_of(c, q);
  const double multiplier = 1.7;
  Eigen::MatrixXd force_derivative = Eigen::MatrixXd::Zero(n, n);
  c.add_force_derivative(0.0, q, multiplier, force_derivative);
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd plus = q, minus = q;
    plus(j) += step;
    minus(j) -= step;
    const double dc = (c.residual(0.0, plus, v) - c.residual(0.0, minus, v)) / (2 * step);
    EXPECT_NEAR(g(j), dc, 1e-9) << what << ", G column " << j;
    const Eigen::RowVectorXd dg = (row_of(c, plus) - row_of(c, minus)) / (2 * step);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(force_derivative(i, j), multiplier * dg(i), 1e-8)
          << what << ", d(G^T lambda)/dq (" << i << ", " << j << ")";
    }
  }
  // d^2/dt^2 C(q + v t) at t = 0 is the remainder (the acceleration is zero along that path).
  const double dt = 1e-4;
  const double second = (c.residual(0.0, q + dt * v, v) - 2 * c.residual(0.0, q, v) +
                         c.residual(0.0, q - dt * v, v)) /
                        (dt * dt);
  EXPECT_NEAR(c.acceleration_remainder(0.0, q, v), second, 1e-6 * (1 + std::abs(second))) << what;
}

TEST(MbdJoints, RevoluteJointRowsHaveExactDerivatives) {
  const TwoBodies bodies = two_bodies();
  int pair_index = 0;
  for (const auto& [a, b] : point_pairs(bodies)) {
    for (int axis = 0; axis < 2; ++axis) {
      const detail::PointConstraint row("joint", a, b, axis);
      expect_constraint_derivatives_exact(
          row, bodies.q, bodies.v,
          "pair " + std::to_string(pair_index) + ", axis " + std::to_string(axis));
    }
    ++pair_index;
  }
}

TEST(MbdJoints, DistanceConstraintHasExactDerivatives) {
  const TwoBodies bodies = two_bodies();
  int pair_index = 0;
  for (const auto& [a, b] : point_pairs(bodies)) {
    const detail::DistanceConstraint rod("rod", a, b, 0.8);
    expect_constraint_derivatives_exact(rod, bodies.q, bodies.v,
                                        "pair " + std::to_string(pair_index++));
  }
}

TEST(MbdJoints, SpringDamperForceDerivativesAreExact) {
  const TwoBodies bodies = two_bodies();
  const int n = 6;
  int pair_index = 0;
  for (const auto& [a, b] : point_pairs(bodies)) {
    const detail::SpringDamper spring(a, b, 350.0, 12.0, 0.4);
    Eigen::MatrixXd by_position = Eigen::MatrixXd::Zero(n, n), by_velocity = by_position;
    ASSERT_TRUE(spring.add_jacobians(0.0, bodies.q, bodies.v, by_position, by_velocity));
    const double step = 1e-6;
    for (int j = 0; j < n; ++j) {
      Eigen::VectorXd force_plus = Eigen::VectorXd::Zero(n), force_minus = force_plus;
      Eigen::VectorXd shifted = bodies.q;
      shifted(j) += step;
      spring.add_force(0.0, shifted, bodies.v, force_plus);
      shifted(j) -= 2 * step;
      spring.add_force(0.0, shifted, bodies.v, force_minus);
      const Eigen::VectorXd by_q = (force_plus - force_minus) / (2 * step);
      force_plus.setZero();
      force_minus.setZero();
      shifted = bodies.v;
      shifted(j) += step;
      spring.add_force(0.0, bodies.q, shifted, force_plus);
      shifted(j) -= 2 * step;
      spring.add_force(0.0, bodies.q, shifted, force_minus);
      const Eigen::VectorXd by_v = (force_plus - force_minus) / (2 * step);
      for (int i = 0; i < n; ++i) {
        EXPECT_NEAR(by_position(i, j), by_q(i), 1e-6 * (1 + std::abs(by_q(i))))
            << "pair " << pair_index << ", dQ/dq (" << i << ", " << j << ")";
        EXPECT_NEAR(by_velocity(i, j), by_v(i), 1e-6 * (1 + std::abs(by_v(i))))
            << "pair " << pair_index << ", dQ/dv (" << i << ", " << j << ")";
      }
    }
    ++pair_index;
  }
}

// The spring force is along the line and its tension is k (l - l0) + c dl/dt.
TEST(MbdJoints, SpringDamperPullsAlongTheLine) {
  Model model;
  RigidBody2DSpec spec;
  spec.name = "mass";
  spec.mass = 1.0;
  spec.inertia = 1.0;
  spec.position = {3.0, 4.0};
  spec.velocity = {0.6, 0.8};  // dl/dt = 1 along the line from the origin
  const BodyId body = model.add_rigid_body(spec);
  model.add_spring_damper({.a = {body, {0.0, 0.0}},
                           .b = {kGround, {0.0, 0.0}},
                           .stiffness = 10.0,
                           .damping = 2.0,
                           .rest_length = 4.0});
  const State state = model.initial_state();
  Eigen::VectorXd force;
  model.applied_force(0.0, state.q, state.v, force);
  const double tension = 10.0 * (5.0 - 4.0) + 2.0 * 1.0;
  EXPECT_NEAR(force(0), -tension * 0.6, 1e-14);
  EXPECT_NEAR(force(1), -tension * 0.8, 1e-14);
  EXPECT_NEAR(force(2), 0.0, 1e-14);
}

TEST(MbdJoints, InvalidJointsAreUserErrorsNamingTheJoint) {
  Model model;
  RigidBody2DSpec spec;
  spec.name = "link";
  spec.mass = 1.0;
  spec.inertia = 1.0;
  const BodyId body = model.add_rigid_body(spec);
  EXPECT_THROW(model.add_revolute_joint({body, {0, 0}}, {body, {1, 0}}), fsi::Error);
  EXPECT_THROW(model.add_revolute_joint({kGround, {0, 0}}, {kGround, {1, 0}}), fsi::Error);
  EXPECT_THROW(model.add_revolute_joint({7, {0, 0}}, {kGround, {1, 0}}), fsi::Error);
  EXPECT_THROW(model.add_distance_constraint({body, {0, 0}}, {kGround, {0, 0}}), fsi::Error);
  EXPECT_THROW(model.add_spring_damper({.a = {body, {0, 0}},
                                        .b = {kGround, {1, 0}},
                                        .stiffness = -1,
                                        .damping = 0,
                                        .rest_length = {}}),
               fsi::Error);
  // A joint whose points do not coincide initially is reported by the consistency check.
  model.add_revolute_joint({body, {0.5, 0.0}}, {kGround, {0.0, 0.0}});
  try {
    model.initial_state();
    FAIL() << "an inconsistent joint was accepted";
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find("revolute joint link-ground (x)"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace fsi::mbd
