#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"

namespace fsi::mbd {
namespace {

class LinearSpring : public ForceElement {
 public:
  LinearSpring(int coordinate, double stiffness) : coordinate_(coordinate), stiffness_(stiffness) {}
  void add_force(double, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                 Eigen::VectorXd& force) const override {
    force(coordinate_) -= stiffness_ * q(coordinate_);
  }

 private:
  int coordinate_;
  double stiffness_;
};

class NotANumber : public ForceElement {
 public:
  void add_force(double t, const Eigen::VectorXd&, const Eigen::VectorXd&,
                 Eigen::VectorXd& force) const override {
    if (t > 0.25) force(0) = std::nan("");
  }
};

RigidBody2DSpec unit_body(const std::string& name) {
  RigidBody2DSpec spec;
  spec.name = name;
  spec.mass = 1.0;
  spec.inertia = 1.0;
  return spec;
}

double oscillator_error(int stages, int steps) {
  Model model;
  RigidBody2DSpec spec = unit_body("mass");
  spec.position = {1.0, 0.0};
  const BodyId b = model.add_rigid_body(spec);
  model.add_force_element(
      std::make_unique<LinearSpring>(model.coordinate_index(b, Coordinate::X), 1.0));
  RadauIIA integrator(stages, NewtonOptions{1e-14, 20, 20, 0.5});
  State state = model.initial_state();
  const double h = 1.0 / steps;
  for (int i = 0; i < steps; ++i)
    integrator.step(model, state, h);
  return std::abs(state.q(0) - std::cos(1.0));
}

TEST(RadauIIA, ObservedOrderOnTheHarmonicOscillator) {
  const int base_steps[] = {0, 64, 8, 4};
  for (int s = 1; s <= 3; ++s) {
    const double coarse = oscillator_error(s, base_steps[s]);
    const double fine = oscillator_error(s, 2 * base_steps[s]);
    const double order = std::log2(coarse / fine);
    std::printf("Radau IIA %d stages: errors %.3e, %.3e, observed order %.2f\n", s, coarse, fine,
                order);
    EXPECT_NEAR(order, 2 * s - 1, 0.3) << s << " stages";
  }
}

TEST(RadauIIA, FreeFallIsExactForThreeStages) {
  Model model;
  RigidBody2DSpec spec = unit_body("stone");
  spec.velocity = {1.0, 2.0};
  spec.angular_velocity = 3.0;
  model.add_rigid_body(spec);
  model.set_gravity({0.0, -9.81});
  RadauIIA integrator(3);
  State state = model.initial_state();
  for (int i = 0; i < 100; ++i)
    integrator.step(model, state, 0.01);
  EXPECT_NEAR(state.q(0), 1.0, 1e-13);
  EXPECT_NEAR(state.q(1), 2.0 - 0.5 * 9.81, 1e-12);
  EXPECT_NEAR(state.q(2), 3.0, 1e-13);
  EXPECT_NEAR(state.v(1), 2.0 - 9.81, 1e-12);
}

// The coupled run measures the fluid weight through the multipliers of a held body.
TEST(RadauIIA, MultipliersOfAHeldBodyBalanceTheLoadsAtEveryStep) {
  Model model;
  RigidBody2DSpec spec = unit_body("bottom");
  spec.mass = 0.1;
  spec.inertia = 2e-5;
  spec.position = {0.025, 0.0};
  const BodyId b = model.add_rigid_body(spec);
  model.set_gravity({0.0, -9.81});
  model.add_marker(b, {-0.025, 0.0025});
  model.add_marker(b, {0.025, 0.0025});
  for (Coordinate c : {Coordinate::X, Coordinate::Y, Coordinate::Angle})
    model.add_coordinate_constraint(b, c);
  RadauIIA integrator(3);
  State state = model.initial_state();
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> load(-10.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    const std::vector<double> loads{0.1 * load(rng), load(rng), 0.1 * load(rng), load(rng)};
    model.set_point_loads(loads);
    integrator.step(model, state, 5e-6);
    const Eigen::Vector3d applied = model.point_load_resultant(state, b);
    EXPECT_EQ(state.q(1), 0.0);
    EXPECT_EQ(state.q(0), 0.025);
    const double weight = -spec.mass * 9.81;
    const double from_multipliers_y = -model.constraint_force(state, b, Coordinate::Y) - weight;
    ASSERT_NEAR(from_multipliers_y, applied(1), 1e-10 * std::abs(applied(1))) << "step " << i;
    const double from_multipliers_x = -model.constraint_force(state, b, Coordinate::X);
    ASSERT_NEAR(from_multipliers_x, applied(0), 1e-10 * std::max(std::abs(applied(0)), 1.0));
    const double torque = -model.constraint_force(state, b, Coordinate::Angle);
    ASSERT_NEAR(torque, applied(2), 1e-10 * std::max(std::abs(applied(2)), 1e-3));
  }
}

TEST(RadauIIA, VelocityConstraintDrivesTheBodyExactly) {
  Model model;
  RigidBody2DSpec spec = unit_body("piston");
  spec.mass = 0.1;
  spec.position = {0.0, 0.0725};
  spec.velocity = {0.0, -0.05};
  const BodyId b = model.add_rigid_body(spec);
  model.set_gravity({0.0, -9.81});
  model.add_coordinate_constraint(b, Coordinate::X);
  model.add_coordinate_constraint(b, Coordinate::Angle);
  model.add_velocity_constraint(b, Coordinate::Y, -0.05);
  RadauIIA integrator(3);
  State state = model.initial_state();
  for (int i = 1; i <= 1000; ++i) {
    integrator.step(model, state, 1e-5);
    ASSERT_NEAR(state.q(1), 0.0725 - 0.05 * i * 1e-5, 1e-14);
    ASSERT_NEAR(state.v(1), -0.05, 1e-15);
    // The drive carries the weight: constraint force = +m g.
    ASSERT_NEAR(model.constraint_force(state, b, Coordinate::Y), 0.1 * 9.81, 1e-10);
  }
  EXPECT_LE(model.position_constraint_drift(state), 1e-15);
  EXPECT_LE(model.velocity_constraint_drift(state), 1e-15);
}

// A world-fixed load at a body-fixed offset makes the rotation a pendulum (nonlinear in phi).
double pendulum_angle(int stages, int steps, const NewtonOptions& options = {1e-14, 20, 20, 0.5}) {
  Model model;
  RigidBody2DSpec spec = unit_body("swing");
  spec.angle = 0.3;
  spec.inertia = 0.2;
  const BodyId b = model.add_rigid_body(spec);
  model.add_marker(b, {1.0, 0.0});
  model.set_point_loads(std::vector<double>{0.0, -1.0});
  RadauIIA integrator(stages, options);
  State state = model.initial_state();
  for (int i = 0; i < steps; ++i)
    integrator.step(model, state, 2.0 / steps);
  return state.q(2);
}

TEST(RadauIIA, FifthOrderOnANonlinearRotation) {
  const double reference = pendulum_angle(3, 4096);
  const double coarse = std::abs(pendulum_angle(3, 16) - reference);
  const double fine = std::abs(pendulum_angle(3, 32) - reference);
  const double order = std::log2(coarse / fine);
  std::printf("nonlinear rotation: errors %.3e, %.3e, observed order %.2f\n", coarse, fine, order);
  EXPECT_NEAR(order, 5.0, 0.4);
}

TEST(RadauIIA, ModifiedAndFullNewtonAgree) {
  const double modified = pendulum_angle(3, 64, {1e-12, 20, 50, 0.5});
  const double full = pendulum_angle(3, 64, {1e-12, 20, 0, 0.5});
  EXPECT_NEAR(modified, full, 1e-10);
}

TEST(RadauIIA, FailureNamesTimeAndStep) {
  Model model;
  const BodyId b = model.add_rigid_body(unit_body("b"));
  (void)b;
  model.add_force_element(std::make_unique<NotANumber>());
  RadauIIA integrator(3);
  State state = model.initial_state();
  integrator.step(model, state, 0.1);
  integrator.step(model, state, 0.1);
  const State before = state;
  try {
    integrator.step(model, state, 0.1);
    FAIL() << "NaN forces accepted";
  } catch (const fsi::Error& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("did not converge at t = 0.2"), std::string::npos) << text;
    EXPECT_NE(text.find("step 0.1"), std::string::npos) << text;
  }
  EXPECT_EQ(state.time, before.time);
  EXPECT_EQ(state.q, before.q);
}

}  // namespace
}  // namespace fsi::mbd
