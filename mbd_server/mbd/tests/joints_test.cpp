// The joint and spring-damper elements against finite differences: G against differences of C,
// d(G^T lambda)/dq against differences of G, the acceleration remainder against the second
// difference of C along q + v t, and the spring-damper's dQ/dq, dQ/dv against differences of Q.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "body.hpp"
#include "body_point.hpp"
#include "coordinate_rows.hpp"
#include "element_checks.hpp"
#include "fsi/common/error.hpp"
#include "point_rows.hpp"
#include "point_to_point_force.hpp"

namespace fsi::mbd {
namespace {

using Pair = testing::BodyPair;

TEST(MbdJoints, RevoluteJointRowsHaveExactDerivatives) {
  const Pair bodies;
  int pair_index = 0;
  for (const auto& [a, b] : bodies.point_pairs()) {
    for (int axis = 0; axis < 2; ++axis) {
      const detail::PointConstraint row("joint", a, b, axis);
      testing::expect_exact_row_derivatives(
          row, bodies.q, bodies.v,
          "pair " + std::to_string(pair_index) + ", axis " + std::to_string(axis));
    }
    ++pair_index;
  }
}

TEST(MbdJoints, DistanceConstraintHasExactDerivatives) {
  const Pair bodies;
  int pair_index = 0;
  for (const auto& [a, b] : bodies.point_pairs()) {
    const detail::DistanceConstraint rod("rod", a, b, 0.8);
    testing::expect_exact_row_derivatives(rod, bodies.q, bodies.v,
                                          "pair " + std::to_string(pair_index++));
  }
}

TEST(MbdJoints, SpringDamperForceDerivativesAreExact) {
  const Pair bodies;
  int pair_index = 0;
  for (const auto& [a, b] : bodies.point_pairs()) {
    const detail::PointToPointForce spring("spring", a, b, 0.4,
                                           std::make_shared<detail::LinearTension>(350.0, 12.0));
    testing::expect_exact_force_derivatives(spring, 0.0, bodies.q, bodies.v,
                                            "pair " + std::to_string(pair_index++));
  }
}

// The spring force is along the line and its tension is k (l - l0) + c dl/dt.
TEST(MbdJoints, SpringDamperPullsAlongTheLine) {
  Model model;
  RigidBody2DSpec spec = testing::rigid("mass", 1.0, 1.0);
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
  const BodyId body = model.add_rigid_body(testing::rigid("link", 1.0, 1.0));
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
