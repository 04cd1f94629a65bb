// Coordinates driven as functions of time: a prescribed position s(t) (position level, its rate
// given) and a prescribed velocity g(t) (velocity level), against their closed forms, with the
// drive's force from lambda; a rate that is not ds/dt is refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "error_message.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"

namespace fsi::mbd {
namespace {

Model shaker(RigidBody2DSpec& spec) {
  spec.name = "table";
  spec.mass = 2.0;
  spec.inertia = 0.1;
  Model model;
  model.add_rigid_body(spec);
  return model;
}

TEST(MbdPrescribedMotion, PositionFollowsItsFunctionAndLambdaIsTheDriveForce) {
  RigidBody2DSpec spec;
  spec.velocity = {0.2, 0.0};  // ds/dt at t = 0
  Model model = shaker(spec);
  PrescribedMotionSpec drive;
  drive.name = "shaker";
  drive.body = 0;
  drive.coordinate = Coordinate::X;
  drive.position = [](double t) { return 0.01 * std::sin(20.0 * t); };
  drive.rate = [](double t) { return 0.2 * std::cos(20.0 * t); };
  drive.check_times = {0.0, 0.5, 1.0};
  const int row = model.add_prescribed_motion(drive);
  EXPECT_EQ(model.constraint_description(row), "prescribed motion 'shaker'");
  // Over 0.5 s at h and h/2: the position is exact to round-off, lambda (the drive force, index-3
  // Radau IIA 3) converges with order s - 1 = 2 (docs/theory.md).
  double force_errors[2] = {0.0, 0.0};
  for (int refinement = 0; refinement < 2; ++refinement) {
    const double h = 2.5e-3 / (1 << refinement);
    RadauIIA integrator(
        {.stages = 3, .newton = {.relative_tolerance = 1e-12, .max_iterations = 20}});
    State state = model.initial_state();
    double position_error = 0.0;
    for (int i = 0; i < static_cast<int>(std::lround(0.5 / h)); ++i) {
      integrator.step(model, state, h);
      const double t = state.time;
      position_error = std::max(position_error, std::abs(state.q(0) - 0.01 * std::sin(20.0 * t)));
      // -G^T lambda = m x'' = -m 4 sin(20 t): lambda = 8 sin(20 t) [N].
      force_errors[refinement] = std::max(force_errors[refinement],
                                          std::abs(state.lambda(row) - 8.0 * std::sin(20.0 * t)));
    }
    std::printf(
        "prescribed position, h = %.3g s: x off s(t) by <= %.2e m, drive force off m s'' "
        "by <= %.2e N (of 8 N)\n",
        h, position_error, force_errors[refinement]);
    EXPECT_LT(position_error, 1e-13);
  }
  EXPECT_NEAR(std::log2(force_errors[0] / force_errors[1]), 2.0, 0.3);
  EXPECT_LT(force_errors[1], 1e-4 * 8.0);
}

TEST(MbdPrescribedMotion, VelocityFollowsItsFunction) {
  RigidBody2DSpec spec;
  Model model = shaker(spec);
  model.add_velocity_constraint(0, Coordinate::Y, [](double t) { return 0.1 * t; });
  RadauIIA integrator({.stages = 3, .newton = {}});
  State state = model.initial_state();
  for (int i = 0; i < 100; ++i)
    integrator.step(model, state, 1e-2);
  EXPECT_NEAR(state.v(1), 0.1, 1e-12);
  EXPECT_NEAR(state.q(1), 0.05, 1e-12);  // y = 0.05 t^2, integrated exactly (order 5)
}

TEST(MbdPrescribedMotion, ARateThatIsNotTheDerivativeIsRefused) {
  RigidBody2DSpec spec;
  Model model = shaker(spec);
  PrescribedMotionSpec drive;
  drive.body = 0;
  drive.coordinate = Coordinate::Angle;
  drive.position = [](double t) { return 0.3 * t * t; };
  drive.rate = [](double t) { return 0.3 * t; };  // should be 0.6 t
  drive.check_times = {0.0, 1.0};
  const std::string text = testing::error_message([&] { model.add_prescribed_motion(drive); });
  EXPECT_NE(text.find("prescribed motion on table.angle"), std::string::npos) << text;
  EXPECT_NE(text.find("is not the derivative of the position"), std::string::npos) << text;
}

// A fast drive's exact rate is accepted (a user's crank spun up by 1e-3 (1 - cos(1000 t)): at the
// check's first step h = 1e-3, omega h = 1, its 4th-order difference was off by 5 %), and a rate
// off by 0.1 % is still refused.
TEST(MbdPrescribedMotion, AFastDrivesExactRateIsAcceptedAndAWrongOneRefused) {
  for (const double factor : {1.0, 1.001}) {
    RigidBody2DSpec spec;
    Model model = shaker(spec);
    PrescribedMotionSpec drive;
    drive.body = 0;
    drive.coordinate = Coordinate::Angle;
    drive.position = [](double t) { return 1e-3 * (1.0 - std::cos(1000.0 * t)); };
    drive.rate = [factor](double t) { return factor * std::sin(1000.0 * t); };
    drive.check_times = {0.0, 0.0123, 0.5, 2.0};
    const std::string text = testing::error_message([&] { model.add_prescribed_motion(drive); });
    if (factor == 1.0) {
      EXPECT_EQ(text, "accepted") << text;
    } else {
      EXPECT_NE(text.find("is not the derivative of the position"), std::string::npos) << text;
    }
  }
}

}  // namespace
}  // namespace fsi::mbd
