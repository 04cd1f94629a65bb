// Bad models are reported naming the offending element, never a crash or a NaN state: redundant
// and contradictory constraints, a zero mass, a force element that turns non-finite, and Newton
// iterations that do not converge.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "element_checks.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"

namespace fsi::mbd {
namespace {

using testing::error_message;
using testing::rigid;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(MbdBadModels, RedundantJointIsNamed) {
  Model model;
  const BodyId door = model.add_rigid_body(rigid("door", 1.0, 1.0));
  model.add_clamp({.name = "frame", .body = door, .to = kGround});
  model.add_revolute_joint({door, {0.0, 0.0}}, {kGround, {0.0, 0.0}}, "hinge");
  const std::string message = error_message([&] { (void)model.initial_state(); });
  EXPECT_TRUE(contains(message, "revolute joint 'hinge' (x): redundant")) << message;
  EXPECT_TRUE(contains(message, "revolute joint 'hinge' (y): redundant")) << message;
  EXPECT_FALSE(contains(message, "clamp 'frame' (x): redundant")) << message;
}

TEST(MbdBadModels, ContradictoryConstraintsAreNamed) {
  Model model;
  const BodyId slider = model.add_rigid_body(rigid("slider", 1.0, 1.0));
  model.add_prismatic_joint(
      {.name = "rail", .a = {kGround, {0.0, 0.0}}, .b = {slider, {0.0, 0.0}}, .axis = {1.0, 0.0}});
  // The rail holds y = 0 and the angle; this row asks for y = 0.5.
  model.add_coordinate_constraint(slider, Coordinate::Y, 0.5);
  const std::string message = error_message([&] { (void)model.initial_state(); });
  EXPECT_TRUE(contains(message, "coordinate constraint on slider.y: position residual C = -0.5"))
      << message;
  EXPECT_TRUE(contains(message, "coordinate constraint on slider.y: redundant")) << message;
}

TEST(MbdBadModels, ZeroMassOrInertiaIsNamed) {
  Model model;
  EXPECT_TRUE(contains(error_message([&] { model.add_rigid_body(rigid("wheel", 0.0, 1.0)); }),
                       "rigid body 'wheel'"));
  EXPECT_TRUE(contains(error_message([&] { model.add_rigid_body(rigid("wheel", 1.0, 0.0)); }),
                       "inertia must be positive"));
  EXPECT_EQ(model.body_count(), 0);
}

// A spring that pushes the valve open and whose law turns NaN beyond 0.1 m (sqrt of a negative
// number): the step fails naming the spring and leaves the state as it was.
TEST(MbdBadModels, NonFiniteForceElementIsNamedAndTheStateKept) {
  Model model;
  RigidBody2DSpec spec = rigid("valve", 1.0, 1.0);
  spec.position = {1.0, 0.0};
  spec.velocity = {2.0, 0.0};
  const BodyId valve = model.add_rigid_body(spec);
  model.add_nonlinear_spring_damper(
      {.name = "valve spring",
       .a = {kGround, {0.0, 0.0}},
       .b = {valve, {0.0, 0.0}},
       .tension = [](double e, double, double) { return -100.0 * std::sqrt(0.1 - e); }});
  State state = model.initial_state();
  RadauIIA integrator(3);
  std::string message;
  int steps = 0;
  for (; steps < 100 && message.empty(); ++steps) {
    const State before = state;
    message = error_message([&] { integrator.step(model, state, 0.01); }, "");
    if (!message.empty()) {
      EXPECT_EQ(state.q, before.q);
      EXPECT_EQ(state.time, before.time);
    }
  }
  std::printf("non-finite spring after %d steps: %s\n", steps, message.c_str());
  EXPECT_TRUE(contains(message, "not finite: nonlinear spring-damper 'valve spring'")) << message;
  EXPECT_TRUE(state.q.allFinite() && state.v.allFinite() && state.lambda.allFinite());
  EXPECT_LT(steps, 100);
}

TEST(MbdBadModels, NonFiniteSourceNamesTheElement) {
  Model model;
  const BodyId arm = model.add_rigid_body(rigid("arm", 1.0, 1.0));
  model.add_torque({.name = "motor", .body = arm, .torque = [](double t) {
                      return t > 1.0 ? std::numeric_limits<double>::infinity() : 0.0;
                    }});
  const State state = model.initial_state();
  EXPECT_EQ(model.non_finite_source(0.5, state.q, state.v), "");
  EXPECT_EQ(model.non_finite_source(2.0, state.q, state.v), "torque 'motor'");
  Eigen::VectorXd bad = state.q;
  bad(2) = std::nan("");
  EXPECT_EQ(model.non_finite_source(0.5, bad, state.v), "body 'arm' coordinate angle");
}

// One Newton iteration cannot solve a stiff nonlinear spring's step: the message names the
// equation with the largest residual.
TEST(MbdBadModels, NonConvergentNewtonNamesTheLargestResidual) {
  Model model;
  RigidBody2DSpec spec = rigid("bob", 1.0, 1.0);
  spec.position = {0.0, -1.0};
  const BodyId bob = model.add_rigid_body(spec);
  model.add_distance_constraint({kGround, {0.0, 0.0}}, {bob, {0.0, 0.0}}, std::nullopt, "rod");
  model.add_nonlinear_spring_damper(
      {.name = "stiff",
       .a = {kGround, {1.0, -1.0}},
       .b = {bob, {0.0, 0.0}},
       .tension = [](double e, double, double) { return 1e6 * e * e * e + 1e4 * e; },
       .rest_length = 0.5});
  State state = model.initial_state();
  RadauIIA integrator(3, NewtonOptions{.relative_tolerance = 1e-12, .max_iterations = 1});
  const std::string message = error_message([&] { integrator.step(model, state, 0.05); });
  std::printf("one Newton iteration: %s\n", message.c_str());
  EXPECT_TRUE(contains(message, "no convergence within the iteration limit")) << message;
  EXPECT_TRUE(contains(message, "largest residual in")) << message;
  EXPECT_TRUE(contains(message, "'bob'") || contains(message, "'rod'")) << message;
}

// A law that jumps (a preload dropped inside a seat) has no derivative at its jump: Newton fails
// at every step size, and the message names the user's law on the failing equation, not the
// user's law on another body.
TEST(MbdBadModels, ALawThatJumpsIsNamedWhereNewtonFails) {
  Model model;
  testing::slider_on_a_jumping_seat(model);
  State state = model.initial_state();
  RadauIIA integrator(3, NewtonOptions{.relative_tolerance = 1e-10, .max_iterations = 12});
  const std::string message = error_message([&] {
    for (int n = 0; n < 1000; ++n)
      integrator.step(model, state, 1e-3);
  });
  std::printf("a law that jumps: %s\n", message.c_str());
  EXPECT_TRUE(contains(message, "equation of motion of body 'slider'")) << message;
  EXPECT_TRUE(contains(message, "a user's law acts on it (nonlinear spring-damper 'seat')"))
      << message;
  EXPECT_TRUE(contains(message, "Write user laws continuous")) << message;
  EXPECT_FALSE(contains(message, "'smooth'")) << message;
}

}  // namespace
}  // namespace fsi::mbd
