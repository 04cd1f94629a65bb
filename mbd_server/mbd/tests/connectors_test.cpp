// Prismatic joint and rigid clamp: their rows against finite differences (body-body and both
// body-ground orders), a block sliding down a frictionless incline against the closed form with
// its normal force and the locked rotation's torque, and a clamped pair rotating as one body.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "body.hpp"
#include "body_point.hpp"
#include "coordinate_rows.hpp"
#include "element_checks.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"
#include "point_rows.hpp"

namespace fsi::mbd {
namespace {

constexpr NewtonOptions kTight{.relative_tolerance = 1e-12, .max_iterations = 20};

using testing::rigid;
using Pair = testing::BodyPair;

TEST(MbdConnectors, PrismaticRowHasExactDerivatives) {
  const Pair pair;
  const Eigen::Vector2d axis(1.2, -1.6);  // not a unit vector: the row divides by its length
  const Eigen::Vector2d on_first(0.2, -0.15), on_second(-0.1, 0.35), on_ground(-0.4, 0.25);
  struct Case {
    const char* name;
    detail::BodyPoint origin, tip, slider;
  };
  const std::vector<Case> cases = {{"body on body",
                                    {&pair.first, 0, on_first},
                                    {&pair.first, 0, on_first + axis},
                                    {&pair.second, 3, on_second}},
                                   {"body on a ground axis",
                                    {nullptr, 0, on_ground},
                                    {nullptr, 0, on_ground + axis},
                                    {&pair.second, 3, on_second}},
                                   {"ground point on a body axis",
                                    {&pair.first, 0, on_first},
                                    {&pair.first, 0, on_first + axis},
                                    {nullptr, 0, on_ground}}};
  for (const Case& c : cases) {
    const detail::PrismaticConstraint row("prismatic", c.origin, c.tip, c.slider, axis.norm());
    testing::expect_exact_row_derivatives(row, pair.q, pair.v, c.name);
  }
}

TEST(MbdConnectors, RelativeAngleRowHasExactDerivatives) {
  const Pair pair;
  testing::expect_exact_row_derivatives(detail::RelativeAngleConstraint("angle", 2, 5, 0.4), pair.q,
                                        pair.v, "two bodies");
  testing::expect_exact_row_derivatives(detail::RelativeAngleConstraint("angle", -1, 5, 0.4),
                                        pair.q, pair.v, "ground and body");
  const detail::RelativeAngleConstraint row("angle", 2, 5, 0.4);
  EXPECT_DOUBLE_EQ(row.residual(0.0, pair.q, pair.v), 0.7 - (-2.1) - 0.4);
}

// A block of mass 2 on a frictionless incline at 30 degrees (prismatic joint to the ground),
// under gravity and a time-dependent torque tau(t) = 2 + t that the locked rotation takes up.
TEST(MbdConnectors, PrismaticJointSlidesDownTheIncline) {
  const double angle = std::numbers::pi / 6.0;
  const double mass = 2.0, g = 9.81;
  Model model;
  model.set_gravity({0.0, -g});
  const BodyId block = model.add_rigid_body(rigid("block", mass, 0.1));
  const Eigen::Vector2d axis(std::cos(angle), std::sin(angle));
  const int row = model.add_prismatic_joint({.name = "incline",
                                             .a = {kGround, {0.0, 0.0}},
                                             .b = {block, {0.0, 0.0}},
                                             .axis = 3.0 * axis});
  model.add_torque({.name = "motor", .body = block, .torque = [](double t) { return 2.0 + t; }});
  State state = model.initial_state();
  RadauIIA integrator(3, kTight);
  const double h = 0.01;
  for (int n = 0; n < 100; ++n)
    integrator.step(model, state, h);
  // Along the incline s = -g sin(angle) t^2 / 2 = -2.4525 m at t = 1 s.
  const double along = -0.5 * g * std::sin(angle);
  EXPECT_NEAR(model.coordinate(state, block, Coordinate::X), along * axis.x(), 1e-10);
  EXPECT_NEAR(model.coordinate(state, block, Coordinate::Y), along * axis.y(), 1e-10);
  EXPECT_NEAR(model.coordinate(state, block, Coordinate::Angle), 0.0, 1e-12);
  // The normal force m g cos(angle) = 16.99 N (lambda of the normal row), the reaction on the
  // block m (a - g), and the torque -tau(1) = -3 N m: the load at the stage time t = 1.
  EXPECT_NEAR(std::abs(state.lambda(row)), mass * g * std::cos(angle), 1e-9);
  const Eigen::Vector3d reaction = joint_reaction(model, state, row, 2, block).planar();
  const Eigen::Vector2d normal(-axis.y(), axis.x());
  EXPECT_NEAR(reaction.head<2>().dot(normal), mass * g * std::cos(angle), 1e-9);
  EXPECT_NEAR(reaction.head<2>().dot(axis), 0.0, 1e-9);
  EXPECT_NEAR(reaction.z(), -3.0, 1e-9);
}

// Body b is clamped to a freely spinning body a at (0.5, 0) in a's frame and 0.5 rad relative
// to it: the pair turns as one rigid body, keeps b's pose in a's frame and conserves energy and
// momentum.
TEST(MbdConnectors, ClampedPairTurnsAsOneBody) {
  Model model;
  const double omega = 2.0, start = 0.4;
  RigidBody2DSpec a = rigid("hub", 3.0, 0.4);
  a.angle = start;
  a.angular_velocity = omega;
  const Eigen::Vector2d arm_offset = Eigen::Rotation2Dd(start) * Eigen::Vector2d(0.5, 0.0);
  RigidBody2DSpec b = rigid("arm", 1.0, 0.05);
  b.position = arm_offset;
  b.velocity = omega * Eigen::Vector2d(-arm_offset.y(), arm_offset.x());  // omega x r
  b.angle = start + 0.5;
  b.angular_velocity = omega;
  const BodyId hub = model.add_rigid_body(a);
  const BodyId arm = model.add_rigid_body(b);
  const int row = model.add_clamp({.name = "weld", .body = arm, .to = hub});
  EXPECT_EQ(model.constraint_count(), 3);
  EXPECT_NE(model.constraint_description(row).find("clamp 'weld'"), std::string::npos);
  State state = model.initial_state();
  const double energy = kinetic_energy(model, state);
  RadauIIA integrator(3, kTight);
  for (int n = 0; n < 200; ++n)
    integrator.step(model, state, 0.005);
  const double phi = model.coordinate(state, hub, Coordinate::Angle);
  const Eigen::Vector2d offset(
      model.coordinate(state, arm, Coordinate::X) - model.coordinate(state, hub, Coordinate::X),
      model.coordinate(state, arm, Coordinate::Y) - model.coordinate(state, hub, Coordinate::Y));
  const Eigen::Vector2d in_hub = Eigen::Rotation2Dd(phi).inverse() * offset;
  EXPECT_NEAR(in_hub.x(), 0.5, 1e-10);
  EXPECT_NEAR(in_hub.y(), 0.0, 1e-10);
  EXPECT_NEAR(model.coordinate(state, arm, Coordinate::Angle), phi + 0.5, 1e-12);
  EXPECT_NEAR(kinetic_energy(model, state), energy, 1e-8 * energy);
  // The combined centre of mass moves uniformly with the momentum m_b v_b over 4 kg.
  for (const Coordinate c : {Coordinate::X, Coordinate::Y}) {
    const int k = static_cast<int>(c);
    const double centre =
        (3.0 * model.coordinate(state, hub, c) + 1.0 * model.coordinate(state, arm, c)) / 4.0;
    EXPECT_NEAR(centre, (arm_offset(k) + 1.0 * b.velocity(k)) / 4.0, 1e-10);
  }
}

TEST(MbdConnectors, ClampToGroundHoldsTheBodyAgainstGravity) {
  Model model;
  model.set_gravity({0.0, -9.81});
  RigidBody2DSpec spec = rigid("gate", 4.0, 0.5);
  spec.position = {1.0, 2.0};
  spec.angle = 0.3;
  const BodyId gate = model.add_rigid_body(spec);
  model.add_point_force({.name = "push", .point = {gate, {0.5, 0.0}}, .force = [](double) {
                           return Eigen::Vector2d(10.0, 0.0);
                         }});
  const int row = model.add_clamp({.name = "bolt", .body = gate, .to = kGround});
  State state = model.initial_state();
  RadauIIA integrator(2, kTight);
  for (int n = 0; n < 10; ++n)
    integrator.step(model, state, 0.01);
  EXPECT_NEAR(model.coordinate(state, gate, Coordinate::X), 1.0, 1e-12);
  EXPECT_NEAR(model.coordinate(state, gate, Coordinate::Angle), 0.3, 1e-12);
  // The clamp balances gravity and the push: (-10, 39.24) N and the push's torque about the
  // centre of mass, -(R(0.3) (0.5, 0)) x (10, 0) = 10 * 0.5 sin(0.3).
  const Eigen::Vector3d reaction = joint_reaction(model, state, row, 3, gate).planar();
  EXPECT_NEAR(reaction.x(), -10.0, 1e-9);
  EXPECT_NEAR(reaction.y(), 4.0 * 9.81, 1e-9);
  EXPECT_NEAR(reaction.z(), 5.0 * std::sin(0.3), 1e-9);
}

TEST(MbdConnectors, InvalidConnectorsAreErrorsNamingThem) {
  Model model;
  const BodyId body = model.add_rigid_body(rigid("slider", 1.0, 1.0));
  EXPECT_NE(testing::error_message([&] {
              model.add_prismatic_joint(
                  {.name = "rail", .a = {body, {0, 0}}, .b = {body, {1, 0}}, .axis = {1, 0}});
            }).find("prismatic joint 'rail'"),
            std::string::npos);
  EXPECT_NE(testing::error_message([&] {
              model.add_prismatic_joint(
                  {.name = "rail", .a = {kGround, {0, 0}}, .b = {body, {0, 0}}, .axis = {0, 0}});
            }).find("axis"),
            std::string::npos);
  EXPECT_NE(testing::error_message([&] {
              model.add_clamp({.name = "bolt", .body = body, .to = body});
            }).find("clamp 'bolt'"),
            std::string::npos);
  EXPECT_NE(testing::error_message([&] {
              model.add_clamp({.name = "bolt", .body = 5, .to = kGround});
            }).find("clamp 'bolt'"),
            std::string::npos);
}

}  // namespace
}  // namespace fsi::mbd
