// The spatial rotational spring-damper (spatial_rotational_spring.hpp): exact derivatives, a
// force that is minus the gradient of its energy at any state, the damped torsion oscillator on an
// oblique hinge against the closed form and against the body's own rotation, action = reaction
// between two bodies, a damper turning many times, a spring wound past its range stopped with the
// reason, and the specs it refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "element_checks.hpp"
#include "error_message.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/ida.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"
#include "rigid_body_3d.hpp"
#include "spatial_rotational_spring.hpp"
#include "tension_law.hpp"

namespace fsi::mbd {
namespace {

using testing::error_message;

constexpr NewtonOptions kTight{.relative_tolerance = 1e-12, .max_iterations = 20};

Eigen::Matrix3d rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

RigidBody3DSpec rotor_spec(const std::string& name) {
  RigidBody3DSpec spec;
  spec.name = name;
  spec.mass = 2.0;
  spec.inertia = Eigen::Vector3d(0.3, 0.5, 0.7).asDiagonal();
  spec.inertia(0, 2) = spec.inertia(2, 0) = 0.05;
  spec.position = {0.1, 0.2, -0.3};
  spec.orientation = rotation(0.8, {1.0, 2.0, -1.0});
  return spec;
}

// Directions of two bodies of 12 coordinates each (a at 0, b at 12): e1, e2 of a normal to
// the axis (0, 0, 1) of a, u of b; the state random, so not a rigid motion (the formulas hold for
// any bilinear x, y).
struct Pair {
  detail::RigidBody3D a{rotor_spec("a")};
  detail::RigidBody3D b{rotor_spec("b")};
  Eigen::VectorXd q = Eigen::VectorXd::Zero(24);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(24);
  detail::SpatialDirection on_a(const Eigen::Vector3d& d) const {
    return {detail::SpatialPoint(&a, 0, Eigen::Vector3d::Zero()), detail::SpatialPoint(&a, 0, d)};
  }
  detail::SpatialDirection on_b(const Eigen::Vector3d& d) const {
    return {detail::SpatialPoint(&b, 12, Eigen::Vector3d::Zero()), detail::SpatialPoint(&b, 12, d)};
  }
  detail::SpatialDirection on_ground(const Eigen::Vector3d& d) const {
    return {detail::SpatialPoint(nullptr, 0, Eigen::Vector3d::Zero()),
            detail::SpatialPoint(nullptr, 0, d)};
  }
  explicit Pair(unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    for (int k = 0; k < 24; ++k) {
      q(k) = value(random);
      v(k) = value(random);
    }
  }
};

TEST(MbdSpatialRotationalSpring, ForceIsMinusTheGradientOfItsEnergyWithExactDerivatives) {
  // A nonlinear law with damping and time (central-difference partials), between two bodies and
  // between a body and the ground, at random states.
  auto law = std::make_shared<detail::UserTension>(
      [](double s, double r, double t) { return 3.0 * s + s * s * s + 0.5 * r + 0.2 * s * r * t; });
  for (unsigned seed : {3u, 4u, 5u}) {
    const Pair pair(seed);
    const detail::SpatialRotationalSpringDamper between("between", pair.on_a({0.3, -0.1, 0.2}),
                                                        pair.on_a({-0.2, 0.4, 0.1}),
                                                        pair.on_b({0.5, 0.3, -0.2}), 0.2, law);
    testing::expect_exact_force_derivatives(between, 0.7, pair.q, pair.v, "between bodies");
    const detail::SpatialRotationalSpringDamper grounded(
        "grounded", pair.on_a({0.3, -0.1, 0.2}), pair.on_a({-0.2, 0.4, 0.1}),
        pair.on_ground({0.1, 0.9, 0.4}), -0.4, law);
    testing::expect_exact_force_derivatives(grounded, 0.7, pair.q, pair.v, "to the ground");

    // At zero rate the force is -dE/dq, E the law's energy of the twist (central differences).
    const detail::SpatialRotationalSpringDamper spring(
        "spring", pair.on_a({0.3, -0.1, 0.2}), pair.on_a({-0.2, 0.4, 0.1}),
        pair.on_b({0.5, 0.3, -0.2}), 0.2, std::make_shared<detail::LinearTension>(2.5, 0.0));
    Eigen::VectorXd force = Eigen::VectorXd::Zero(24);
    spring.add_force(0.0, pair.q, pair.v, force);
    for (Eigen::Index j = 0; j < 24; ++j) {
      Eigen::VectorXd plus = pair.q, minus = pair.q;
      plus(j) += 1e-6;
      minus(j) -= 1e-6;
      const double gradient =
          (spring.potential_energy(0.0, plus) - spring.potential_energy(0.0, minus)) / 2e-6;
      EXPECT_NEAR(force(j), -gradient, 1e-7 * (1.0 + std::abs(gradient))) << "coordinate " << j;
    }
    // The rate is the twist's time derivative along v.
    const double h = 1e-6;
    const double rate_by_difference =
        (spring.twist(pair.q + h * pair.v) - spring.twist(pair.q - h * pair.v)) / (2.0 * h);
    EXPECT_NEAR(spring.twist_rate(pair.q, pair.v), rate_by_difference, 1e-7);
  }
}

// A rotor on a revolute joint to the ground about an oblique axis through its centre of mass,
// held by a rotational spring-damper about the same axis; returns the model and fills the axis
// (world) and the rotor's moment of inertia about it.
struct TorsionOscillator {
  Model model;
  BodyId rotor = kGround;
  int spring = -1;
  Eigen::Vector3d axis_world;
  double inertia = 0.0;
  TorsionOscillator(double stiffness, double damping, double spin, double rest_angle = 0.0) {
    RigidBody3DSpec spec = rotor_spec("rotor");
    const Eigen::Vector3d axis_body(0.4, -0.3, 0.8);
    const Eigen::Vector3d n = axis_body.normalized();
    axis_world = spec.orientation * n;
    inertia = n.dot(spec.inertia * n);
    spec.angular_velocity = spin * axis_world;
    rotor = model.add_rigid_body_3d(spec);
    RevoluteJoint3DSpec hinge;
    hinge.name = "hinge";
    hinge.a = {rotor, Eigen::Vector3d::Zero()};
    hinge.b = {kGround, spec.position};
    hinge.axis = axis_body;
    model.add_revolute_joint_3d(hinge);
    SpatialRotationalSpringDamperSpec coil;
    coil.name = "coil";
    coil.a = rotor;
    coil.axis = axis_body;
    coil.stiffness = stiffness;
    coil.damping = damping;
    if (rest_angle != 0.0) coil.rest_angle = rest_angle;
    spring = model.add_spatial_rotational_spring_damper(coil);
  }
  // The rotor's turn about the axis from its initial orientation, from its axes alone.
  double turned(const State& state, const Eigen::Matrix3d& initial) const {
    const Eigen::AngleAxisd relative(orientation(model, state, rotor) * initial.transpose());
    return relative.angle() * relative.axis().dot(axis_world);
  }
};

TEST(MbdSpatialRotationalSpring, TorsionOscillatorOnAnObliqueHingeMovesAsTheClosedFormSays) {
  // J theta'' + c theta' + k theta = 0, theta(0) = 0, theta'(0) = w0:
  // theta = w0 / wd exp(-zeta wn t) sin(wd t).
  const double k = 3.0, c = 0.08, w0 = 1.2;
  TorsionOscillator oscillator(k, c, w0);
  const double wn = std::sqrt(k / oscillator.inertia);
  const double zeta = c / (2.0 * std::sqrt(k * oscillator.inertia));
  const double wd = wn * std::sqrt(1.0 - zeta * zeta);
  const Eigen::Matrix3d initial = rotor_spec("rotor").orientation;
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = oscillator.model.initial_state();
  const double h = 1e-3;
  double largest_error = 0.0, largest_angle = 0.0;
  for (int i = 1; i <= 3000; ++i) {
    integrator.step(oscillator.model, state, h);
    const double t = i * h;
    const double exact = w0 / wd * std::exp(-zeta * wn * t) * std::sin(wd * t);
    // The body's own turn is what the spring measures: a's rotation about the axis.
    EXPECT_NEAR(oscillator.turned(state, initial), exact, 1e-8) << "t = " << t;
    largest_error = std::max(largest_error, std::abs(oscillator.turned(state, initial) - exact));
    largest_angle = std::max(largest_angle, std::abs(exact));
  }
  std::printf("torsion oscillator: |theta - exact| <= %.2e rad of %.3f rad over 3 s\n",
              largest_error, largest_angle);
  // The sensor reading: the torque on the rotor, -k theta - c theta'.
  const double t = state.time;
  const double envelope = std::exp(-zeta * wn * t);
  const double theta = w0 / wd * envelope * std::sin(wd * t);
  const double rate = w0 / wd * envelope * (wd * std::cos(wd * t) - zeta * wn * std::sin(wd * t));
  EXPECT_NEAR(force_element_force(oscillator.model, state, oscillator.spring),
              -k * theta - c * rate, 1e-7);
  EXPECT_NEAR(force_element_power(oscillator.model, state, oscillator.spring),
              (-k * theta - c * rate) * rate, 1e-7);
  EXPECT_NEAR(potential_energy(oscillator.model, state), 0.5 * k * theta * theta, 1e-8);
}

TEST(MbdSpatialRotationalSpring, PreloadedSpringSettlesAtItsRestAngle) {
  // rest_angle = 0.4: relaxed 0.4 rad ahead of the start; without damping the rotor swings
  // about it with amplitude 0.4 (theta = 0.4 (1 - cos wn t)), and its energy is conserved.
  const double k = 3.0;
  TorsionOscillator oscillator(k, 0.0, 0.0, 0.4);
  const Eigen::Matrix3d initial = rotor_spec("rotor").orientation;
  const double wn = std::sqrt(k / oscillator.inertia);
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = oscillator.model.initial_state();
  const double energy = potential_energy(oscillator.model, state);
  EXPECT_NEAR(energy, 0.5 * k * 0.16, 1e-14);
  for (int i = 1; i <= 2000; ++i) {
    integrator.step(oscillator.model, state, 1e-3);
    EXPECT_NEAR(oscillator.turned(state, initial), 0.4 * (1.0 - std::cos(wn * i * 1e-3)), 1e-8);
  }
  EXPECT_NEAR(kinetic_energy(oscillator.model, state) + potential_energy(oscillator.model, state),
              energy, 1e-10);
}

TEST(MbdSpatialRotationalSpring, TwoFreeBodiesFeelOppositeTorquesAndKeepTheirAngularMomentum) {
  // Two rotors hinged to each other about an oblique axis, free in space, spinning against the
  // spring between them: no external torque, so the total angular momentum stays; no damping, so
  // the energy stays.
  Model model;
  RigidBody3DSpec first = rotor_spec("first");
  RigidBody3DSpec second = rotor_spec("second");
  second.position = first.position + first.orientation * Eigen::Vector3d(0.0, 0.0, 0.3);
  second.orientation = rotation(-0.5, {0.2, 1.0, 0.3});
  const Eigen::Vector3d axis_body(0.0, 0.0, 1.0);
  const Eigen::Vector3d axis_world = first.orientation * axis_body;
  first.angular_velocity = 0.7 * axis_world;
  second.angular_velocity = -0.4 * axis_world;
  // The hinge point (on the axis, 0.15 m from each centre) moves alike on both bodies.
  const Eigen::Vector3d hinge_world = first.position + 0.15 * axis_world;
  first.velocity = first.angular_velocity.cross(first.position - hinge_world);
  second.velocity = second.angular_velocity.cross(second.position - hinge_world);
  const BodyId a = model.add_rigid_body_3d(first);
  const BodyId b = model.add_rigid_body_3d(second);
  RevoluteJoint3DSpec hinge;
  hinge.a = {a, Eigen::Vector3d(0.0, 0.0, 0.15)};
  hinge.b = {b, second.orientation.transpose() * (hinge_world - second.position)};
  hinge.axis = axis_body;
  model.add_revolute_joint_3d(hinge);
  SpatialRotationalSpringDamperSpec coil;
  coil.a = a;
  coil.b = b;
  coil.axis = axis_body;
  coil.stiffness = 2.0;
  model.add_spatial_rotational_spring_damper(coil);

  auto momentum = [&](const State& state) {
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (BodyId body : {a, b}) {
      const RigidBody3DSpec& spec = model.rigid_body_3d(body);
      const Eigen::Matrix3d r = orientation(model, state, body);
      const Eigen::Vector3d centre =
          point_position(model, state, SpatialPointSpec{body, Eigen::Vector3d::Zero()});
      const Eigen::Vector3d velocity =
          point_velocity(model, state, SpatialPointSpec{body, Eigen::Vector3d::Zero()});
      total += spec.mass * centre.cross(velocity) +
               r * spec.inertia * r.transpose() * angular_velocity(model, state, body);
    }
    return total;
  };
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = model.initial_state();
  const Eigen::Vector3d start = momentum(state);
  const double energy = kinetic_energy(model, state) + potential_energy(model, state);
  double largest_twist = 0.0;
  for (int i = 0; i < 2000; ++i) {
    integrator.step(model, state, 1e-3);
    largest_twist = std::max(largest_twist, potential_energy(model, state));
  }
  EXPECT_GT(largest_twist, 0.01);  // the spring was wound and did its work
  EXPECT_NEAR((momentum(state) - start).norm(), 0.0, 1e-10);
  EXPECT_NEAR(kinetic_energy(model, state) + potential_energy(model, state), energy, 1e-10);
}

TEST(MbdSpatialRotationalSpring, APureDamperTurnsAnyNumberOfTimes) {
  // J w' = -c w: w = w0 exp(-c t / J), the rotor turning about 4 times in 2 s.
  const double c = 0.3, w0 = 20.0;
  TorsionOscillator oscillator(0.0, c, w0);
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = oscillator.model.initial_state();
  for (int i = 0; i < 2000; ++i)
    integrator.step(oscillator.model, state, 1e-3);
  const double expected = w0 * std::exp(-c * 2.0 / oscillator.inertia);
  const double turns =
      w0 * oscillator.inertia / c * (1.0 - expected / w0) / (2.0 * std::numbers::pi);
  EXPECT_GT(turns, 3.0);
  EXPECT_NEAR(
      angular_velocity(oscillator.model, state, oscillator.rotor).dot(oscillator.axis_world),
      expected, 1e-9 * w0);
  EXPECT_EQ(potential_energy(oscillator.model, state), 0.0);
}

TEST(MbdSpatialRotationalSpring, ASpringWoundPastItsRangeStopsWithTheReason) {
  // Undamped, k = J: the amplitude is w0 rad. 2.8 rad (160 degrees) stays within the range and
  // swings back; 3.2 rad passes 170 degrees and the step fails naming the twist.
  {
    TorsionOscillator oscillator(1.0, 0.0, 0.0);
    TorsionOscillator within(oscillator.inertia, 0.0, 2.8);
    RadauIIA integrator({.stages = 3, .newton = kTight});
    State state = within.model.initial_state();
    double largest = 0.0;
    const Eigen::Matrix3d initial = rotor_spec("rotor").orientation;
    for (int i = 0; i < 4000; ++i) {  // beyond a period (2 pi s)
      integrator.step(within.model, state, 2e-3);
      largest = std::max(largest, within.turned(state, initial));
    }
    EXPECT_NEAR(largest, 2.8, 1e-4);
  }
  TorsionOscillator probe(1.0, 0.0, 0.0);
  TorsionOscillator beyond(probe.inertia, 0.0, 3.2);
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = beyond.model.initial_state();
  const std::string message = error_message([&] {
    for (int i = 0; i < 2000; ++i)
      integrator.step(beyond.model, state, 2e-3);
  });
  EXPECT_NE(message.find("rotational spring-damper 'coil': twisted past"), std::string::npos)
      << message;
  EXPECT_NE(message.find("+-170 degrees from its rest angle"), std::string::npos) << message;
  // A one-sided stop (nothing below its rest) turned the free way past -170 degrees: flat where
  // the rotor is, but the law jumps from 0 to 50 pi at the half turn, so the run stops too.
  {
    Model model;
    RigidBody3DSpec spec = rotor_spec("rotor");
    spec.angular_velocity = -4.0 * spec.orientation.col(2);
    const BodyId rotor = model.add_rigid_body_3d(spec);
    model.add_revolute_joint_3d({"hinge",
                                 {rotor, Eigen::Vector3d::Zero()},
                                 {kGround, spec.position},
                                 Eigen::Vector3d::UnitZ(),
                                 std::nullopt});
    SpatialRotationalSpringDamperSpec stop;
    stop.name = "stop";
    stop.a = rotor;
    stop.torque = [](double s, double, double) { return s > 0.0 ? 50.0 * s : 0.0; };
    model.add_spatial_rotational_spring_damper(stop);
    RadauIIA one_sided({.stages = 3, .newton = kTight});
    State turning = model.initial_state();
    const std::string text = error_message([&] {
      for (int i = 0; i < 1000; ++i)
        one_sided.step(model, turning, 2e-3);
    });
    // Stopped on the free side at -170 degrees (0.742 s at 4 rad/s), not after the jump at the
    // half turn (0.785 s), where the law's own slope would first show.
    EXPECT_NE(text.find("'stop': twisted past"), std::string::npos) << text;
    EXPECT_NE(text.find("(-170.0"), std::string::npos) << text;
    EXPECT_GT(turning.time, 0.73);
    EXPECT_LT(turning.time, 0.745);
  }
  // IDA stops there too, with the same reason beside the row it names.
  TorsionOscillator again(probe.inertia, 0.0, 3.2);
  IdaIntegrator ida({.relative_tolerance = 1e-8, .absolute_tolerance = 1e-10});
  State ida_state = again.model.initial_state();
  const std::string ida_message = error_message([&] { ida.advance(again.model, ida_state, 4.0); });
  EXPECT_NE(ida_message.find("rotational spring-damper 'coil': twisted past"), std::string::npos)
      << ida_message;
}

TEST(MbdSpatialRotationalSpring, RefusesWhatItCannotMeasureWithTheFix) {
  Model model;
  const BodyId a = model.add_rigid_body_3d(rotor_spec("a"));
  PointMassSpec mass;
  mass.name = "bob";
  mass.mass = 1.0;
  const BodyId bob = model.add_point_mass(mass);
  auto refused = [&](SpatialRotationalSpringDamperSpec spec) {
    spec.name = "coil";
    return error_message([&] { model.add_spatial_rotational_spring_damper(spec); });
  };
  SpatialRotationalSpringDamperSpec good;
  good.a = a;
  good.stiffness = 1.0;
  SpatialRotationalSpringDamperSpec spec = good;
  spec.a = kGround;
  spec.b = a;
  EXPECT_NE(refused(spec).find("body a is the ground"), std::string::npos);
  spec = good;
  spec.b = bob;
  EXPECT_NE(refused(spec).find("'bob' is not a rigid body"), std::string::npos);
  spec = good;
  spec.b = a;
  EXPECT_NE(refused(spec).find("same body"), std::string::npos) << refused(spec);
  spec = good;
  spec.axis = Eigen::Vector3d::Zero();
  EXPECT_NE(refused(spec).find("finite, non-zero vector"), std::string::npos);
  spec = good;
  spec.axis.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(refused(spec).find("finite, non-zero vector"), std::string::npos);
  spec = good;
  spec.stiffness = -1.0;
  EXPECT_NE(refused(spec).find("non-negative"), std::string::npos);
  spec = good;
  spec.torque = [](double s, double, double) { return s; };
  EXPECT_NE(refused(spec).find("write the whole torque in the law"), std::string::npos);
  spec = good;
  spec.rest_angle = std::numeric_limits<double>::infinity();
  EXPECT_NE(refused(spec).find("rest angle is not finite"), std::string::npos);
  spec = good;
  spec.rest_angle = -3.0;
  EXPECT_NE(refused(spec).find("beyond the +-170 degrees"), std::string::npos);
  EXPECT_EQ(model.force_element_count(), 0);
  EXPECT_EQ(model.add_spatial_rotational_spring_damper(good), 0);
}

}  // namespace
}  // namespace fsi::mbd
