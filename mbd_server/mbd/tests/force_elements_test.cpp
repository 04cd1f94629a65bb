// Rotational, nonlinear and piecewise-linear spring-dampers and time-dependent loads: exact
// derivatives against finite differences, their laws and energies against closed forms, a torsion
// oscillator against cos(omega t), and a sine force integrated at the stage times.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "body.hpp"
#include "body_point.hpp"
#include "element_checks.hpp"
#include "force_elements.hpp"
#include "point_to_point_force.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"

namespace fsi::mbd {
namespace {

constexpr NewtonOptions kTight{.relative_tolerance = 1e-12, .max_iterations = 20};

using testing::rigid;

using Pair = testing::BodyPair;

// A point-to-point force with `law` between each of the pair's sets of ends has exact derivatives.
void expect_point_to_point_derivatives(const std::string& name, double rest_length,
                                       const std::shared_ptr<const detail::TensionLaw>& law) {
  const Pair pair;
  int index = 0;
  for (const auto& [a, b] : pair.point_pairs()) {
    const detail::PointToPointForce force(name, a, b, rest_length, law);
    testing::expect_exact_force_derivatives(force, 0.0, pair.q, pair.v,
                                            "ends " + std::to_string(index++));
  }
}

TEST(MbdForceElements, RotationalSpringDamperTorqueAndDerivatives) {
  const Pair pair;
  const auto linear = std::make_shared<detail::LinearTension>(40.0, 1.5);
  const detail::RotationalSpringDamper spring("torsion", 2, 5, 0.5, linear);
  // -k (0.7 + 2.1 - 0.5) - c (2 - 3) = -92 + 1.5 on a, the opposite on b.
  Eigen::VectorXd force = Eigen::VectorXd::Zero(6);
  spring.add_force(0.0, pair.q, pair.v, force);
  EXPECT_DOUBLE_EQ(force(2), -40.0 * 2.3 + 1.5);
  EXPECT_DOUBLE_EQ(force(5), 40.0 * 2.3 - 1.5);
  EXPECT_DOUBLE_EQ(spring.potential_energy(0.0, pair.q), 0.5 * 40.0 * 2.3 * 2.3);
  testing::expect_exact_force_derivatives(spring, 0.0, pair.q, pair.v, "two bodies");
  const detail::RotationalSpringDamper grounded("torsion", -1, 5, 0.5, linear);
  testing::expect_exact_force_derivatives(grounded, 0.0, pair.q, pair.v, "to the ground");
}

// A user's torque law: the torque on a is -f(twist, rate), its derivatives those of the law.
TEST(MbdForceElements, NonlinearRotationalSpringDamperTorqueAndDerivatives) {
  const Pair pair;
  const auto law = std::make_shared<detail::UserTension>([](double twist, double rate, double) {
    return 40.0 * twist + 3.0 * twist * twist * twist + rate;
  });
  const detail::RotationalSpringDamper spring("torsion", 2, 5, 0.5, law);
  // twist 0.7 + 2.1 - 0.5 = 2.3, rate 2 - 3 = -1.
  const double torque = 40.0 * 2.3 + 3.0 * 2.3 * 2.3 * 2.3 - 1.0;
  Eigen::VectorXd force = Eigen::VectorXd::Zero(6);
  spring.add_force(0.0, pair.q, pair.v, force);
  EXPECT_NEAR(force(2), -torque, 1e-12);
  EXPECT_NEAR(force(5), torque, 1e-12);
  EXPECT_NEAR(spring.potential_energy(0.0, pair.q), 20.0 * 2.3 * 2.3 + 0.75 * std::pow(2.3, 4),
              1e-12);
  testing::expect_exact_force_derivatives(spring, 0.0, pair.q, pair.v, "two bodies");
  const detail::RotationalSpringDamper grounded("torsion", -1, 5, 0.5, law);
  testing::expect_exact_force_derivatives(grounded, 0.0, pair.q, pair.v, "to the ground");
}

TEST(MbdForceElements, NonlinearSpringDamperHasExactDerivatives) {
  auto law = std::make_shared<detail::UserTension>([](double e, double r, double) {
    return 300.0 * e + 4e4 * e * e * e + 15.0 * r + 2.0 * r * r * r;
  });
  expect_point_to_point_derivatives("cubic", 0.9, law);
}

TEST(MbdForceElements, SpringActorHasExactDerivativesAwayFromItsKinks) {
  // The ends are 1.030, 1.045 and 1.854 m apart: elongations 0.53, 0.54 and 1.35 m from the rest
  // length 0.5, inside segments, not at a kink.
  auto law = std::make_shared<detail::PiecewiseLinearTension>(
      std::vector<Eigen::Vector2d>{{-1.0, -20.0}, {0.0, 0.0}, {0.1, 0.0}, {1.0, 900.0}}, 7.0);
  expect_point_to_point_derivatives("actor", 0.5, law);
}

TEST(MbdForceElements, SpringActorCharacteristicIsPiecewiseLinear) {
  // Compression up to 2 cm at 50 N/m, tension up to 1 cm at 5000 N/m, continued beyond.
  const detail::PiecewiseLinearTension actor({{-0.02, -1.0}, {0.0, 0.0}, {0.01, 50.0}}, 3.0);
  EXPECT_DOUBLE_EQ(actor.at(-0.03, 0.0, 0.0).value, -1.5);  // extrapolated with 50 N/m
  EXPECT_DOUBLE_EQ(actor.at(0.005, 0.0, 0.0).value, 25.0);
  EXPECT_DOUBLE_EQ(actor.at(0.02, 0.0, 0.0).value, 100.0);  // extrapolated with 5000 N/m
  EXPECT_DOUBLE_EQ(actor.at(0.005, 0.0, 0.0).by_elongation, 5000.0);
  EXPECT_DOUBLE_EQ(actor.at(-0.01, 2.0, 0.0).value, -0.5 + 6.0);
  EXPECT_DOUBLE_EQ(actor.at(-0.01, 2.0, 0.0).by_rate, 3.0);
  // Energies: 5000 (0.01)^2 / 2 = 0.25 J, 50 (0.02)^2 / 2 = 0.01 J, 0.25 + 50 * 0.01 + 5000 *
  // 0.01^2 / 2 = 1.0 J at 2 cm.
  EXPECT_NEAR(actor.energy(0.01, 0.0), 0.25, 1e-15);
  EXPECT_NEAR(actor.energy(-0.02, 0.0), 0.01, 1e-15);
  EXPECT_NEAR(actor.energy(0.02, 0.0), 1.0, 1e-14);
}

TEST(MbdForceElements, UserTensionEnergyIsTheIntegralOfTheLaw) {
  const detail::UserTension law(
      [](double e, double, double) { return 300.0 * e + 4e4 * e * e * e; });
  const double e = 0.07;
  EXPECT_NEAR(law.energy(e, 0.0), 150.0 * e * e + 1e4 * e * e * e * e, 1e-14);
  EXPECT_NEAR(law.energy(-e, 0.0), 150.0 * e * e + 1e4 * e * e * e * e, 1e-14);
  const detail::Tension t = law.at(e, 0.0, 0.0);
  // Central differences of 6e-6 m: truncation 2e-9 relative.
  EXPECT_NEAR(t.by_elongation, 300.0 + 1.2e5 * e * e, 1e-8 * 888.0);
}

TEST(MbdForceElements, PointForceHasExactDerivatives) {
  const Pair pair;
  const detail::PointForce force("push", detail::BodyPoint(&pair.first, 0, {0.2, -0.15}),
                                 [](double t) { return Eigen::Vector2d(std::sin(t), 3.0 * t); });
  testing::expect_exact_force_derivatives(force, 0.4, pair.q, pair.v, "body point");
}

// A wheel of 1 kg and J = 0.25 kg m^2 held at its centre, turned to `angle`, free to rotate.
BodyId wheel_on_its_axle(Model& model, double angle) {
  RigidBody2DSpec spec = rigid("wheel", 1.0, 0.25);
  spec.angle = angle;
  const BodyId wheel = model.add_rigid_body(spec);
  model.add_coordinate_constraint(wheel, Coordinate::X);
  model.add_coordinate_constraint(wheel, Coordinate::Y);
  return wheel;
}

// J phi'' = -k phi: phi(t) = phi0 cos(sqrt(k / J) t); the energy stays 0.5 k phi0^2.
TEST(MbdForceElements, TorsionOscillatorFollowsTheCosine) {
  Model model;
  const BodyId wheel = wheel_on_its_axle(model, 0.2);
  const int element = model.add_rotational_spring_damper(
      {.name = "torsion bar", .a = wheel, .b = kGround, .stiffness = 9.0, .rest_angle = 0.0});
  State state = model.initial_state();
  EXPECT_DOUBLE_EQ(potential_energy(model, state), 0.5 * 9.0 * 0.04);
  RadauIIA integrator(3, kTight);
  for (int n = 0; n < 1000; ++n)
    integrator.step(model, state, 1e-3);
  const double omega = std::sqrt(9.0 / 0.25);  // 6 rad/s
  EXPECT_NEAR(model.coordinate(state, wheel, Coordinate::Angle), 0.2 * std::cos(omega), 1e-10);
  EXPECT_NEAR(kinetic_energy(model, state) + potential_energy(model, state), 0.18, 1e-10);
  EXPECT_NEAR(force_element_force(model, state, element),
              -9.0 * model.coordinate(state, wheel, Coordinate::Angle), 1e-12);
}

// A hardening torsion spring, J phi'' = -(k phi + a phi^3), conserves 0.5 J omega^2 + 0.5 k phi^2
// + 0.25 a phi^4, and crosses zero after a quarter period, the integral of dphi / phi' over the
// energy curve.
TEST(MbdForceElements, NonlinearTorsionOscillatorConservesItsEnergy) {
  Model model;
  const BodyId wheel = wheel_on_its_axle(model, 0.5);
  const int element = model.add_nonlinear_rotational_spring_damper(
      {.name = "hardening",
       .a = wheel,
       .b = kGround,
       .torque = [](double phi, double, double) { return 9.0 * phi + 40.0 * phi * phi * phi; },
       .rest_angle = 0.0});
  State state = model.initial_state();
  const double energy = 0.5 * 9.0 * 0.25 + 10.0 * std::pow(0.5, 4);
  EXPECT_NEAR(potential_energy(model, state), energy, 1e-14);
  EXPECT_NEAR(force_element_force(model, state, element), -(9.0 * 0.5 + 40.0 * 0.125), 1e-13);
  // The first zero crossing: a quarter period, T/4 = int_0^phi0 dphi / sqrt(2 (E - V(phi)) / J).
  // Substituting phi = phi0 sin(s) removes the end's singularity; the integrand is then a smooth
  // function of sin^2 s, on which the midpoint rule converges faster than any power.
  double quarter = 0.0;
  {
    const int n = 400;
    for (int k = 0; k < n; ++k) {
      const double s = (k + 0.5) * (0.5 * std::numbers::pi) / n;
      const double phi = 0.5 * std::sin(s);
      const double v = 0.5 * 9.0 * phi * phi + 10.0 * std::pow(phi, 4);
      quarter +=
          0.5 * std::cos(s) / std::sqrt(2.0 * (energy - v) / 0.25) * (0.5 * std::numbers::pi) / n;
    }
  }
  RadauIIA integrator(3, kTight);
  double previous_time = 0.0, previous_angle = 0.5, crossing = -1.0, drift = 0.0;
  for (int n = 1; n <= 1000; ++n) {
    integrator.step(model, state, 1e-3);
    const double angle = model.coordinate(state, wheel, Coordinate::Angle);
    if (crossing < 0.0 && angle <= 0.0)
      crossing = previous_time + 1e-3 * previous_angle / (previous_angle - angle);
    previous_time = n * 1e-3;
    previous_angle = angle;
    drift = std::max(
        drift, std::abs(kinetic_energy(model, state) + potential_energy(model, state) - energy));
  }
  EXPECT_LT(drift, 1e-8 * energy);
  EXPECT_NEAR(crossing, quarter, 1e-6);
}

// An actuator: a spring whose rest point moves, T = k (e - a sin(w t)). From rest at e = 0,
// m e'' = -k (e - a sin w t) gives e = A (sin w t - w / w0 sin w0 t), A = a w0^2 / (w0^2 - w^2).
// The law is evaluated at the stage times (held at a step's start it would be off by ~h).
TEST(MbdForceElements, ALawInTimeDrivesItsSpring) {
  Model model;
  const BodyId slider = testing::slider_along_x(model);
  const double k = 100.0, a = 0.05, w = 3.0, w0 = 10.0;
  const int actuator = model.add_nonlinear_spring_damper(
      {.name = "actuator",
       .a = {kGround, {0.0, 0.0}},
       .b = {slider, {0.0, 0.0}},
       .tension = [=](double e, double, double t) { return k * (e - a * std::sin(w * t)); },
       .rest_length = 1.0});
  State state = model.initial_state();
  RadauIIA integrator(3, kTight);
  for (int n = 0; n < 1000; ++n)
    integrator.step(model, state, 1e-3);
  const double amplitude = a * w0 * w0 / (w0 * w0 - w * w);
  const double e = model.coordinate(state, slider, Coordinate::X) - 1.0;
  EXPECT_NEAR(e, amplitude * (std::sin(w) - w / w0 * std::sin(w0)), 1e-9);
  EXPECT_NEAR(force_element_force(model, state, actuator), k * (e - a * std::sin(w)), 1e-9);
  // The energy stored, with the law held at the state's time: the integral of k (s - a sin w t).
  EXPECT_NEAR(model.force_element(actuator).potential_energy(state.time, state.q),
              k * (0.5 * e * e - a * std::sin(w) * e), 1e-12);
}

// m x'' = sin(t) from rest: x(t) = t - sin(t). At h = 0.05 Radau IIA (order 5) gives it to
// about 1e-9; a force held at the step start would be off by about h / 2 * (1 - cos 1) = 1e-2.
TEST(MbdForceElements, TimeDependentForceIsEvaluatedAtTheStageTimes) {
  Model model;
  const BodyId body = model.add_rigid_body(rigid("cart", 1.0, 1.0));
  model.add_point_force({.name = "drive", .point = {body, {0.0, 0.5}}, .force = [](double t) {
                           return Eigen::Vector2d(std::sin(t), 0.0);
                         }});
  model.add_coordinate_constraint(body, Coordinate::Angle);
  State state = model.initial_state();
  RadauIIA integrator(3, kTight);
  for (int n = 0; n < 20; ++n)
    integrator.step(model, state, 0.05);
  EXPECT_NEAR(model.coordinate(state, body, Coordinate::X), 1.0 - std::sin(1.0), 1e-9);
  // The torque of the force about the centre of mass, -0.5 sin(1), is taken up by the held angle.
  EXPECT_NEAR(constraint_force(model, state, body, Coordinate::Angle), 0.5 * std::sin(1.0), 1e-9);
}

TEST(MbdForceElements, SpringForcesAreMeasuredAndStoreEnergy) {
  Model model;
  RigidBody2DSpec spec = rigid("valve", 1.0, 1.0);
  spec.position = {0.3, 0.0};
  const BodyId valve = model.add_rigid_body(spec);
  const int actor = model.add_spring_actor({.name = "actor",
                                            .a = {kGround, {0.0, 0.0}},
                                            .b = {valve, {0.0, 0.0}},
                                            .characteristic = {{-1.0, -10.0}, {0.0, 0.0}},
                                            .damping = 0.0,
                                            .rest_length = 0.2});
  const int cubic = model.add_nonlinear_spring_damper(
      {.name = "cubic",
       .a = {kGround, {0.0, 0.0}},
       .b = {valve, {0.0, 0.0}},
       .tension = [](double e, double, double) { return 1000.0 * e * e * e; },
       .rest_length = 0.1});
  const State state = model.initial_state();
  // The actor's table has slope 10 N/m continued beyond 0: 0.1 m -> 1 N, 0.05 J; the cubic law
  // 1000 (0.2)^3 = 8 N, 250 (0.2)^4 = 0.4 J.
  EXPECT_NEAR(force_element_force(model, state, actor), 1.0, 1e-14);
  EXPECT_NEAR(force_element_force(model, state, cubic), 8.0, 1e-13);
  EXPECT_NEAR(potential_energy(model, state), 0.05 + 0.4, 1e-13);
  EXPECT_NE(model.force_element(cubic).description().find("'cubic'"), std::string::npos);
}

TEST(MbdForceElements, InvalidElementsAreErrorsNamingThem) {
  Model model;
  const BodyId body = model.add_rigid_body(rigid("arm", 1.0, 1.0));
  EXPECT_NE(testing::error_message([&] {
              model.add_rotational_spring_damper(
                  {.name = "coil", .a = body, .b = kGround, .stiffness = -1.0});
            }).find("rotational spring-damper 'coil'"),
            std::string::npos);
  EXPECT_NE(testing::error_message([&] {
              model.add_spring_actor({.name = "stop",
                                      .a = {kGround, {1, 0}},
                                      .b = {body, {0, 0}},
                                      .characteristic = {{0.0, 0.0}, {0.0, 1.0}}});
            }).find("spring actor 'stop'"),
            std::string::npos);
  EXPECT_NE(testing::error_message([&] {
              model.add_nonlinear_spring_damper(
                  {.name = "soft", .a = {kGround, {0, 0}}, .b = {body, {0, 0}}, .tension = {}});
            }).find("nonlinear spring-damper 'soft'"),
            std::string::npos);
  EXPECT_NE(
      testing::error_message([&] {
        model.add_torque({.name = "motor", .body = kGround, .torque = [](double) { return 1.0; }});
      }).find("torque 'motor'"),
      std::string::npos);
}

}  // namespace
}  // namespace fsi::mbd
