// Spatial (3D) bodies and connectors: the rigid body in natural coordinates, the point mass, the
// ANCF cable, spherical and revolute joints and the spatial rod, against exact derivatives
// (central differences), closed-form motions and the planar beam's reference values.
// Measured numbers: docs/theory.md ("Spatial bodies").
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ancf_cable_3d.hpp"
#include "direction_rows.hpp"
#include "element_checks.hpp"
#include "force_elements.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/ida.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/mbd/static_analysis.hpp"
#include "point_rows.hpp"
#include "point_to_point_force.hpp"
#include "rigid_body_3d.hpp"

namespace fsi::mbd {
namespace {

using testing::error_message;

constexpr double kGravity = 9.81;
constexpr NewtonOptions kTight{.relative_tolerance = 1e-12, .max_iterations = 20};

Eigen::Matrix3d rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

RigidBody3DSpec top_spec() {
  RigidBody3DSpec spec;
  spec.name = "top";
  spec.mass = 1.5;
  spec.inertia = Eigen::Vector3d(2.0, 2.0, 1.0).asDiagonal();
  spec.inertia(0, 1) = spec.inertia(1, 0) = 0.1;  // not in principal axes
  spec.position = {0.3, -0.2, 0.5};
  spec.orientation = rotation(0.7, {1.0, -2.0, 0.5});
  spec.velocity = {0.4, 0.1, -0.3};
  spec.angular_velocity = {0.5, -1.2, 2.0};
  return spec;
}

TEST(MbdSpatialRigidBody, KineticEnergyIsThatOfTranslationAndRotation) {
  Model model;
  const RigidBody3DSpec spec = top_spec();
  model.add_rigid_body_3d(spec);
  const State state = model.initial_state();
  const Eigen::Matrix3d r = spec.orientation;
  const Eigen::Vector3d& w = spec.angular_velocity;
  const double expected = 0.5 * spec.mass * spec.velocity.squaredNorm() +
                          0.5 * w.dot(r * spec.inertia * r.transpose() * w);
  EXPECT_NEAR(kinetic_energy(model, state), expected, 1e-13 * expected);
  EXPECT_EQ(model.coordinate_count(), 12);
  EXPECT_EQ(model.constraint_count(), 6);
  EXPECT_TRUE(angular_velocity(model, state, 0).isApprox(w, 1e-14));
  EXPECT_EQ(model.constraint_description(3), "rigid body 'top' orthonormality (e1.e2)");
  EXPECT_EQ(model.coordinate_description(7), "body 'top' coordinate e2.y");
}

// A general (not orthonormal) configuration of two rigid bodies, 24 coordinates.
struct SpatialPair {
  detail::RigidBody3D first{top_spec()};
  detail::RigidBody3D second{top_spec()};
  Eigen::VectorXd q;
  Eigen::VectorXd v;
  SpatialPair() {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    q.resize(24);
    v.resize(24);
    for (int k = 0; k < 24; ++k) {
      q(k) = value(random);
      v(k) = value(random);
    }
  }
};

TEST(MbdSpatialRigidBody, OrthonormalityRowsHaveExactDerivatives) {
  const SpatialPair pair;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      const detail::OrthonormalityConstraint row("row", 12, i, j);
      testing::expect_exact_row_derivatives(row, pair.q, pair.v,
                                            "e" + std::to_string(i) + ".e" + std::to_string(j));
    }
  }
}

// The ends a row's derivative checks use: body to body, body to ground, ground to body.
std::array<std::pair<detail::SpatialPoint, detail::SpatialPoint>, 3> point_pairs(
    const SpatialPair& pair) {
  const detail::SpatialPoint on_first(&pair.first, 0, {0.2, -0.15, 0.3});
  const detail::SpatialPoint on_second(&pair.second, 12, {-0.1, 0.35, -0.2});
  const detail::SpatialPoint on_ground(nullptr, 0, {-0.4, 0.25, 0.1});
  return {{{on_first, on_second}, {on_first, on_ground}, {on_ground, on_second}}};
}

TEST(MbdSpatialJoints, RowsHaveExactDerivativesBetweenBodiesAndTheGround) {
  const SpatialPair pair;
  const auto ends = point_pairs(pair);
  for (const auto& [a, b] : ends) {
    for (int axis = 0; axis < 3; ++axis) {
      testing::expect_exact_row_derivatives(detail::SpatialPointConstraint("p", a, b, axis), pair.q,
                                            pair.v, "point row " + std::to_string(axis));
    }
    testing::expect_exact_row_derivatives(detail::SpatialDistanceConstraint("d", a, b, 0.7), pair.q,
                                          pair.v, "distance row");
    const detail::SpatialDirection da{
        a, detail::SpatialPoint(a.body(), 0, a.local() + Eigen::Vector3d(0.3, 0.1, -0.5))};
    const detail::SpatialDirection db{
        b, detail::SpatialPoint(b.body(), b.on_ground() ? 0 : 12,
                                b.local() + Eigen::Vector3d(-0.2, 0.6, 0.4))};
    testing::expect_exact_row_derivatives(detail::PerpendicularityConstraint("n", da, db), pair.q,
                                          pair.v, "perpendicularity row");
  }
}

// Q = (dr/dq)^T f against the work f . dr along a random motion (central difference).
void expect_virtual_work(Model& model, int marker, const std::string& what) {
  State state = model.initial_state();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const int n = model.coordinate_count();
  Eigen::VectorXd direction(n);
  for (int k = 0; k < n; ++k)
    direction(k) = value(random);
  const Eigen::Vector3d f(0.7, -1.3, 2.1);
  std::vector<double> loads(3 * model.marker_count(), 0.0);
  Eigen::VectorXd without, with;
  model.set_point_loads(loads);
  model.applied_force(0.0, state.q, state.v, without);
  for (int k = 0; k < 3; ++k)
    loads[3 * marker + k] = f(k);
  model.set_point_loads(loads);
  model.applied_force(0.0, state.q, state.v, with);
  const double step = 1e-6;
  State plus = state, minus = state;
  plus.q += step * direction;
  minus.q -= step * direction;
  const double work =
      f.dot(marker_position(model, plus, marker) - marker_position(model, minus, marker)) /
      (2.0 * step);
  const double predicted = (with - without).dot(direction);
  EXPECT_NEAR(predicted, work, 1e-7 * (1.0 + std::abs(work))) << what;
}

TEST(MbdSpatialBodies, VertexForcesDoTheWorkVirtualWorkPredicts) {
  {
    Model model;
    const BodyId body = model.add_rigid_body_3d(top_spec());
    model.add_spatial_marker(body, {0.3, -0.4, 0.25});
    model.add_spatial_marker(body, {-0.1, 0.2, 0.6});
    expect_virtual_work(model, 1, "rigid body");
  }
  {
    Model model;
    const BodyId mass = model.add_point_mass({"mass", 2.0, {1.0, 2.0, 3.0}, {}});
    model.add_spatial_marker(mass, Eigen::Vector3d::Zero());
    expect_virtual_work(model, 0, "point mass");
  }
  {
    Model model;
    AncfCableSpec spec;
    spec.name = "cable";
    spec.start = {0.0, 0.0, 0.0};
    spec.end = {1.0, 0.5, -0.3};
    spec.element_count = 3;
    spec.axial_stiffness = 1e4;
    spec.bending_stiffness = 1.0;
    spec.mass_per_length = 0.5;
    const BodyId cable = model.add_ancf_cable(spec);
    model.add_spatial_marker(cable, {0.2, 0.0, 0.0});
    model.add_spatial_marker(cable, {0.77, 0.0, 0.0});
    expect_virtual_work(model, 1, "cable");
  }
}

TEST(MbdSpatialRigidBody, TorqueFreeSymmetricTopPrecessesAsEulersEquationsSay) {
  // Body axes principal, A = J1 = J2 = 2, C = J3 = 1: in the body frame omega_3 is constant
  // and (omega_1, omega_2) turn at Omega = (C - A) omega_3 / A.
  Model model;
  RigidBody3DSpec spec;
  spec.name = "top";
  spec.mass = 1.0;
  spec.inertia = Eigen::Vector3d(2.0, 2.0, 1.0).asDiagonal();
  spec.orientation = rotation(0.4, {0.3, 1.0, -0.2});
  const Eigen::Vector3d body_rate(1.0, 0.0, 3.0);
  spec.angular_velocity = spec.orientation * body_rate;
  const BodyId top = model.add_rigid_body_3d(spec);
  State state = model.initial_state();
  RadauIIA integrator({.stages = 3, .newton = kTight});
  const double h = 1e-3;
  const double energy = kinetic_energy(model, state);
  auto momentum = [&](const State& s) {
    const Eigen::Matrix3d r = orientation(model, s, top);
    return Eigen::Vector3d(r * spec.inertia * r.transpose() * angular_velocity(model, s, top));
  };
  const Eigen::Vector3d start_momentum = momentum(state);
  double energy_drift = 0.0, momentum_drift = 0.0, orthonormality = 0.0;
  for (int i = 0; i < 2000; ++i) {
    integrator.step(model, state, h);
    energy_drift = std::max(energy_drift, std::abs(kinetic_energy(model, state) - energy));
    momentum_drift = std::max(momentum_drift, (momentum(state) - start_momentum).norm());
    orthonormality = std::max(orthonormality, position_constraint_drift(model, state));
  }
  const double omega = (1.0 - 2.0) * 3.0 / 2.0;
  const Eigen::Vector3d expected(std::cos(omega * state.time), std::sin(omega * state.time), 3.0);
  const Eigen::Matrix3d r = orientation(model, state, top);
  const Eigen::Vector3d measured = r.transpose() * angular_velocity(model, state, top);
  const double error = (measured - expected).norm();
  std::printf(
      "torque-free top, Radau IIA 3, h = 1e-3 s, t = 2 s: body-frame omega off Euler's solution "
      "by %.2e rad/s, energy drift %.2e J (of %.3f), |L| drift %.2e, orthonormality %.2e\n",
      error, energy_drift, energy, momentum_drift, orthonormality);
  EXPECT_LT(error, 1e-8);
  EXPECT_LT(energy_drift, 1e-9 * energy);
  EXPECT_LT(momentum_drift, 1e-9 * start_momentum.norm());
  EXPECT_LT(orthonormality, 1e-12);
}

// The compound pendulum: pivot 0.8 m from the centre of mass, J = 0.16 kg m^2 about it, m = 1 kg:
// equivalent length L + J / (m L) = 1 m, so released from rest at 90 degrees its period is the
// mathematical pendulum's exact 2.3678419476 s (issue 4's reference).
constexpr double kExactPeriod = 2.3678419476;

struct Swing {
  double period = 0.0;
  double constraint_drift = 0.0;
};

// Integrates a bit more than one period; the centre of mass passes below the pivot (its offset
// along `out` changes sign) at T/4 and 3T/4.
Swing swing(Model& model, BodyId body, const Eigen::Vector3d& out, double h) {
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = model.initial_state();
  Swing result;
  std::vector<double> crossings;
  auto offset = [&](const State& s) {
    return point_position(model, s, SpatialPointSpec{body, Eigen::Vector3d::Zero()}).dot(out);
  };
  auto rate = [&](const State& s) {
    return point_velocity(model, s, SpatialPointSpec{body, Eigen::Vector3d::Zero()}).dot(out);
  };
  while (state.time < 1.1 * kExactPeriod) {
    const State before = state;
    integrator.step(model, state, h);
    if ((offset(before) > 0) != (offset(state) > 0)) {
      // The root of the cubic Hermite interpolant (error O(h^4)), by bisection.
      const double x0 = offset(before), v0 = rate(before), x1 = offset(state), v1 = rate(state);
      double low = 0.0, high = 1.0;
      auto x = [&](double s) {
        const double s2 = s * s, s3 = s2 * s;
        return (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * h * v0 + (-2 * s3 + 3 * s2) * x1 +
               (s3 - s2) * h * v1;
      };
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (low + high);
        ((x(low) < 0) == (x(mid) < 0) ? low : high) = mid;
      }
      crossings.push_back(before.time + 0.5 * (low + high) * h);
    }
    result.constraint_drift =
        std::max(result.constraint_drift, position_constraint_drift(model, state));
  }
  EXPECT_EQ(crossings.size(), 2u);
  if (crossings.size() >= 2) result.period = 2.0 * (crossings[1] - crossings[0]);
  return result;
}

RigidBody3DSpec compound_bob(const Eigen::Vector3d& out) {
  RigidBody3DSpec spec;
  spec.name = "bob";
  spec.mass = 1.0;
  spec.inertia = 0.16 * Eigen::Matrix3d::Identity();
  spec.position = 0.8 * out;
  return spec;
}

TEST(MbdSpatialJoints, CompoundPendulumOnASphericalJointHasTheExactPeriod) {
  const Eigen::Vector3d out = Eigen::Vector3d(1.0, 2.0, 0.0).normalized();
  Model model;
  model.set_spatial_gravity({0.0, 0.0, -kGravity});
  const BodyId bob = model.add_rigid_body_3d(compound_bob(out));
  model.add_spherical_joint({bob, -0.8 * out}, {kGround, Eigen::Vector3d::Zero()}, "pivot");
  const Swing result = swing(model, bob, out, 1e-3);
  const double error = std::abs(result.period - kExactPeriod) / kExactPeriod;
  std::printf(
      "compound pendulum, spherical joint: period %.10f s, relative error %.2e, |C| <= %.2e\n",
      result.period, error, result.constraint_drift);
  EXPECT_LT(error, 1e-8);
  EXPECT_LT(result.constraint_drift, 1e-12);
}

TEST(MbdSpatialJoints, CompoundPendulumOnAnObliqueRevoluteJointHasTheExactPeriod) {
  // The hinge axis is horizontal and oblique, the bob's axes are turned against the world.
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -1.0, 0.0).normalized();
  const Eigen::Vector3d out = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  Model model;
  model.set_spatial_gravity({0.0, 0.0, -kGravity});
  RigidBody3DSpec spec = compound_bob(out);
  spec.orientation = rotation(1.1, {0.2, 0.5, 1.0});
  const BodyId bob = model.add_rigid_body_3d(spec);
  RevoluteJoint3DSpec hinge;
  hinge.name = "hinge";
  hinge.a = {kGround, Eigen::Vector3d::Zero()};
  hinge.b = {bob, spec.orientation.transpose() * (-0.8 * out)};
  hinge.axis = axis;
  model.add_revolute_joint_3d(hinge);
  EXPECT_EQ(model.constraint_description(model.constraint_count() - 1),
            "revolute joint 'hinge' (axis normal 2)");
  const Swing result = swing(model, bob, out, 1e-3);
  const double error = std::abs(result.period - kExactPeriod) / kExactPeriod;
  std::printf("compound pendulum, oblique revolute joint: period %.10f s, relative error %.2e\n",
              result.period, error);
  EXPECT_LT(error, 1e-8);
}

TEST(MbdSpatialJoints, ConicalPendulumOfAPointMassOnARodKeepsItsCone) {
  // A point mass on a rod of L = 1 m at 30 degrees from the vertical turns at
  // Omega^2 = g / (L cos theta) and stays at height -L cos theta.
  const double theta = std::numbers::pi / 6.0;
  const double omega = std::sqrt(kGravity / std::cos(theta));
  const double radius = std::sin(theta);
  Model model;
  model.set_spatial_gravity({0.0, 0.0, -kGravity});
  const BodyId mass = model.add_point_mass(
      {"bob", 0.5, {radius, 0.0, -std::cos(theta)}, {0.0, omega * radius, 0.0}});
  model.add_spatial_distance_constraint({kGround, Eigen::Vector3d::Zero()},
                                        {mass, Eigen::Vector3d::Zero()});
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = model.initial_state();
  double height_error = 0.0;
  for (int i = 0; i < 2000; ++i) {
    integrator.step(model, state, 1e-3);
    height_error = std::max(height_error, std::abs(state.q(2) + std::cos(theta)));
  }
  const double azimuth = std::atan2(state.q(1), state.q(0));
  const double expected = std::remainder(omega * state.time, 2.0 * std::numbers::pi);
  std::printf(
      "conical pendulum: height off the cone by <= %.2e m, azimuth off by %.2e rad "
      "after 2 s, rod force %.9f N (m g / cos theta = %.9f)\n",
      height_error, std::abs(azimuth - expected), state.lambda(0),
      0.5 * kGravity / std::cos(theta));
  EXPECT_LT(height_error, 1e-9);
  EXPECT_LT(std::abs(azimuth - expected), 1e-8);
  // lambda of index-3 Radau IIA 3 converges with order s - 1 = 2 (docs/theory.md), not 5 like
  // the positions: measured 2.1e-7 relative at h = 1e-3.
  EXPECT_NEAR(std::abs(state.lambda(0)), 0.5 * kGravity / std::cos(theta),
              5e-7 * 0.5 * kGravity / std::cos(theta));
}

TEST(MbdSpatialLoads, TorqueAndPointForceHaveExactDerivativesAndSpinUpAsNewtonSays) {
  const SpatialPair pair;
  const detail::SpatialTorque torque("t", 3,
                                     [](double t) { return Eigen::Vector3d(0.3, -1.2, 2.0 * t); });
  testing::expect_exact_force_derivatives(torque, 0.7, pair.q, pair.v, "spatial torque");
  const detail::SpatialPointForce force("f",
                                        detail::SpatialPoint(&pair.second, 12, {0.1, 0.2, 0.3}),
                                        [](double t) { return Eigen::Vector3d(1.0, t, -t * t); });
  testing::expect_exact_force_derivatives(force, 0.7, pair.q, pair.v, "spatial point force");

  // tau = (0, 0, 6 t) about a principal axis of a turned body: J omega' = tau, omega = 3 t^2 / J.
  Model model;
  RigidBody3DSpec spec;
  spec.name = "rotor";
  spec.mass = 2.0;
  spec.inertia = Eigen::Vector3d(2.0, 3.0, 4.0).asDiagonal();
  spec.orientation = rotation(0.9, {1.0, 1.0, 0.0});
  const BodyId rotor = model.add_rigid_body_3d(spec);
  const Eigen::Vector3d axis = spec.orientation.col(2);
  model.add_spatial_torque(
      {"drive", rotor, [axis](double t) { return Eigen::Vector3d(6.0 * t * axis); }});
  model.add_spatial_point_force({"push", {rotor, Eigen::Vector3d::Zero()}, [](double t) {
                                   return Eigen::Vector3d(0.0, 4.0 * t, 0.0);
                                 }});
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = model.initial_state();
  for (int i = 0; i < 100; ++i)
    integrator.step(model, state, 0.01);
  const Eigen::Vector3d omega = angular_velocity(model, state, rotor);
  EXPECT_NEAR((omega - 3.0 / 4.0 * axis).norm(), 0.0, 1e-10);
  // m x'' = 4 t: y = 4 t^3 / (6 m) at t = 1.
  EXPECT_NEAR(state.q(1), 4.0 / 12.0, 1e-10);
  EXPECT_NE(error_message([&] {
              model.add_spatial_torque({"", kGround, nullptr});
            }).find("ground"),
            std::string::npos);
}

TEST(MbdSpatialJoints, FixedJointHoldsABodyAndReportsTheForceAndTorqueItExerts) {
  // Fixed to the ground, the joint balances gravity and a point load off the centre (reaction
  // -(weight + load), torque -(arm x load)); fixed to a spinning body, a body turns with it.
  Model model;
  model.set_spatial_gravity({0.0, 0.0, -kGravity});
  RigidBody3DSpec spec = top_spec();
  spec.velocity.setZero();
  spec.angular_velocity.setZero();
  const BodyId body = model.add_rigid_body_3d(spec);
  const int first = model.add_fixed_joint_3d({"weld", body, kGround});
  const Eigen::Vector3d local(0.2, -0.1, 0.3);
  model.add_spatial_marker(body, local);
  const Eigen::Vector3d load(1.0, -2.0, 0.5);
  model.set_point_loads(std::vector<double>{load.x(), load.y(), load.z()});
  State state = model.initial_state();
  RadauIIA integrator({.stages = 3, .newton = kTight});
  for (int i = 0; i < 10; ++i)
    integrator.step(model, state, 1e-2);
  const Eigen::Matrix<double, 6, 1> reaction =
      joint_reaction(model, state, first, 6, body).stacked();
  const Eigen::Vector3d weight(0.0, 0.0, -spec.mass * kGravity);
  const Eigen::Vector3d arm = spec.orientation * local;
  EXPECT_LT((reaction.head<3>() + weight + load).norm(), 1e-9);
  EXPECT_LT((reaction.tail<3>() + arm.cross(load)).norm(), 1e-9);
  std::printf("fixed joint: force off -(weight + load) by %.2e N, torque off by %.2e N m\n",
              (reaction.head<3>() + weight + load).norm(),
              (reaction.tail<3>() + arm.cross(load)).norm());
  EXPECT_LT((state.q.head<3>() - spec.position).norm(), 1e-12);
  EXPECT_EQ(model.constraint_description(first + 5), "fixed joint 'weld' (e2 . e3')");

  Model pair;
  const BodyId holder = pair.add_rigid_body_3d(top_spec());
  RigidBody3DSpec second = top_spec();
  second.name = "second";
  second.position += Eigen::Vector3d(0.5, 0.0, 0.0);
  second.velocity =
      top_spec().velocity + top_spec().angular_velocity.cross(Eigen::Vector3d(0.5, 0.0, 0.0));
  const BodyId carried = pair.add_rigid_body_3d(second);
  pair.add_fixed_joint_3d({"", carried, holder});
  State moving = pair.initial_state();
  for (int i = 0; i < 100; ++i)
    integrator.step(pair, moving, 1e-2);
  // The carried body turns with the holder: same orientation change, same relative offset.
  const Eigen::Matrix3d turn =
      orientation(pair, moving, holder) * top_spec().orientation.transpose();
  EXPECT_LT((orientation(pair, moving, carried) - turn * second.orientation).norm(), 1e-9);
  const Eigen::Vector3d offset = moving.q.segment<3>(12) - moving.q.head<3>();
  EXPECT_LT((offset - turn * Eigen::Vector3d(0.5, 0.0, 0.0)).norm(), 1e-9);
}

TEST(MbdSpatialJoints, RevoluteDriveRowHasExactDerivativesAtAnyTime) {
  // G, d(G^T lambda)/dq, the explicit dC/dt and the acceleration remainder (with its time terms)
  // against differences in q and t, at a time where sin(phi) and cos(phi) are both far from 0.
  const SpatialPair pair;
  const auto ends = point_pairs(pair);
  for (const auto& [a, b] : ends) {
    auto direction = [](const detail::SpatialPoint& p, int offset, const Eigen::Vector3d& d) {
      return detail::SpatialDirection{
          p, detail::SpatialPoint(p.body(), p.on_ground() ? 0 : offset, p.local() + d)};
    };
    const detail::RotationDriveConstraint drive("drive", direction(a, 0, {0.3, 0.1, -0.5}),
                                                direction(a, 0, {-0.6, 0.2, 0.1}),
                                                direction(b, 12, {0.4, -0.7, 0.2}), 2.3);
    testing::expect_exact_row_derivatives(drive, pair.q, pair.v, "drive row", 0.37);
  }
}

// A rotor on a driven revolute joint to the ground: rate w about an oblique axis, the rotor's
// axes turned against the world and its inertia not principal about the axis.
struct DrivenRotor {
  static constexpr double kRate = 3.0;                                  // [rad/s]
  Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.4, 1.0).normalized();  // rotor frame
  RigidBody3DSpec spec;
  Model model;
  BodyId rotor = kGround;
  int first_row = 0;
  Eigen::Vector3d hinge_local{0.0, 0.0, 0.0};

  DrivenRotor() {
    model.set_spatial_gravity({0.0, 0.0, -kGravity});
    spec.name = "rotor";
    spec.mass = 2.0;
    spec.inertia = Eigen::Vector3d(0.05, 0.07, 0.11).asDiagonal();
    spec.inertia(0, 2) = spec.inertia(2, 0) = 0.01;
    spec.position = {0.1, 0.2, 0.3};
    spec.orientation = rotation(0.8, {1.0, 0.5, -0.3});
    spec.angular_velocity = kRate * (spec.orientation * axis);
    rotor = model.add_rigid_body_3d(spec);
    // The hinge point on the axis, 0.25 m from the centre of mass: the centre stays on the axis.
    hinge_local = 0.25 * axis;
    RevoluteJoint3DSpec hinge;
    hinge.name = "motor";
    hinge.a = {rotor, hinge_local};
    hinge.b = {kGround, spec.position + spec.orientation * hinge_local};
    hinge.axis = axis;
    hinge.rate = kRate;
    first_row = model.add_revolute_joint_3d(hinge);
  }
  Eigen::Vector3d world_axis() const { return spec.orientation * axis; }
};

TEST(MbdSpatialJoints, DrivenRevoluteJointTurnsTheRotorAtItsRate) {
  DrivenRotor driven;
  Model& model = driven.model;
  EXPECT_EQ(model.constraint_count(), 6 + 6);
  EXPECT_EQ(model.constraint_description(driven.first_row + 5), "revolute joint 'motor' (drive)");
  const Eigen::Vector3d n = driven.world_axis();
  const double end = 1.0;
  struct Tolerance {
    double angle, omega, torque;
  };
  auto check = [&](const State& state, const std::string& how, Tolerance tolerance) {
    // R(T) = Rot(w T, n) R(0): the angle about the axis is w T, the other rotations are zero.
    const Eigen::Matrix3d expected =
        rotation(DrivenRotor::kRate * end, n) * driven.spec.orientation;
    const Eigen::Matrix3d turned = orientation(model, state, driven.rotor);
    const Eigen::AngleAxisd off(turned * expected.transpose());
    const Eigen::Vector3d omega = angular_velocity(model, state, driven.rotor);
    const Eigen::Vector3d hinge =
        point_position(model, state, SpatialPointSpec{driven.rotor, driven.hinge_local});
    const Eigen::Vector3d held =
        driven.spec.position + driven.spec.orientation * driven.hinge_local;
    // The drive balances nothing about the axis: the centre of mass is on it, so gravity and the
    // gyroscopic moment of the non-principal axis are normal to it.
    const double drive_torque = state.lambda(driven.first_row + 5);
    std::printf(
        "driven rotor (%s), w = %.1f rad/s, T = %.1f s: rotation off Rot(w T) by %.2e rad, "
        "|omega - w n| = %.2e rad/s, hinge gap %.2e m, drive torque %.2e N m\n",
        how.c_str(), DrivenRotor::kRate, end, off.angle(), (omega - DrivenRotor::kRate * n).norm(),
        (hinge - held).norm(), drive_torque);
    EXPECT_LT(off.angle(), tolerance.angle) << how;
    EXPECT_LT((omega - DrivenRotor::kRate * n).norm(), tolerance.omega) << how;
    EXPECT_LT((hinge - held).norm(), tolerance.angle) << how;
    EXPECT_LT(std::abs(drive_torque), tolerance.torque) << how;
  };
  // Index 3 holds C exactly, its velocities and multipliers converge with lower order (h = 1e-2:
  // ~1e-8 rad/s, ~3e-7 N m); index 2 holds the velocity level.
  RadauIIA radau({.stages = 3, .newton = kTight});
  RadauIIA index2({.stages = 3, .newton = kTight, .constraint_form = ConstraintForm::Index2});
  State state = model.initial_state();
  State stabilised = state;
  for (int i = 0; i < 100; ++i) {
    radau.step(model, state, 1e-2);
    index2.step(model, stabilised, 1e-2);
  }
  check(state, "Radau IIA 3, index 3", {1e-12, 1e-7, 1e-6});
  check(stabilised, "Radau IIA 3, index 2", {1e-12, 1e-9, 1e-9});
  // IDA (GGL form, C_t and dG/dt in its velocity rows); it fails to start on this rotor below
  // relative_tolerance 1e-6 with the drive as without it.
  IdaIntegrator ida({.relative_tolerance = 1e-6, .absolute_tolerance = 1e-8});
  State bdf = model.initial_state();
  ida.advance(model, bdf, end);
  check(bdf, "IDA, GGL", {1e-12, 1e-12, 1e-5});
}

TEST(MbdSpatialJoints, DriveTorqueBalancesAnAppliedTorqueAboutTheAxis) {
  // A constant torque tau n on the rotor: the drive holds the rate with -tau about the axis, and
  // the joint's reaction on the rotor (all six rows) has that axial component.
  DrivenRotor driven;
  Model& model = driven.model;
  const double tau = 0.7;  // [N m]
  const Eigen::Vector3d n = driven.world_axis();
  model.add_spatial_torque({"load", driven.rotor, [n, tau](double) { return tau * n; }});
  RadauIIA radau({.stages = 3, .newton = kTight, .constraint_form = ConstraintForm::Index2});
  State state = model.initial_state();
  for (int i = 0; i < 50; ++i)
    radau.step(model, state, 1e-2);
  const double drive = state.lambda(driven.first_row + 5);
  const Wrench reaction = joint_reaction(model, state, driven.first_row, 6, driven.rotor);
  std::printf("drive against tau = %.2f N m: drive torque %.12f N m, reaction . n %.12f N m\n", tau,
              drive, reaction.torque.dot(n));
  EXPECT_NEAR(drive, -tau, 1e-9);
  EXPECT_NEAR(reaction.torque.dot(n), -tau, 1e-9);
  EXPECT_NEAR(angular_velocity(model, state, driven.rotor).dot(n), DrivenRotor::kRate, 1e-9);
}

TEST(MbdSpatialJoints, DriveTurnsARotorRelativeToASprungCarrier) {
  // The carrier hangs on four springs and bounces under gravity; the rotor's hinge is on the
  // carrier: its orientation relative to the carrier is Rot(w t, n_c) of the initial one.
  Model model;
  model.set_spatial_gravity({0.0, 0.0, -kGravity});
  RigidBody3DSpec carrier = top_spec();
  carrier.name = "carrier";
  carrier.velocity.setZero();
  carrier.angular_velocity.setZero();
  const BodyId holder = model.add_rigid_body_3d(carrier);
  for (const Eigen::Vector3d& corner :
       {Eigen::Vector3d(0.3, 0.3, 0.0), Eigen::Vector3d(-0.3, 0.3, 0.0),
        Eigen::Vector3d(0.3, -0.4, 0.0), Eigen::Vector3d(-0.3, -0.2, 0.0)}) {
    const Eigen::Vector3d world = carrier.position + carrier.orientation * corner;
    model.add_spatial_spring_damper({"",
                                     {holder, corner},
                                     {kGround, world + Eigen::Vector3d(0.1, 0.0, 0.5)},
                                     400.0,
                                     2.0,
                                     std::nullopt});
  }
  const double rate = -4.0;
  const Eigen::Vector3d axis(0.0, 1.0, 0.0);  // in the rotor's axes
  RigidBody3DSpec rotor = top_spec();
  rotor.name = "rotor";
  rotor.mass = 0.5;
  rotor.position = carrier.position + carrier.orientation * Eigen::Vector3d(0.0, 0.0, 0.2);
  rotor.orientation = rotation(0.4, {0.0, 1.0, 1.0});
  rotor.velocity.setZero();
  rotor.angular_velocity = rate * (rotor.orientation * axis);
  const BodyId spinning = model.add_rigid_body_3d(rotor);
  RevoluteJoint3DSpec hinge;
  hinge.a = {spinning, Eigen::Vector3d::Zero()};
  hinge.b = {holder, Eigen::Vector3d(0.0, 0.0, 0.2)};
  hinge.axis = axis;
  hinge.rate = rate;
  model.add_revolute_joint_3d(hinge);
  RadauIIA radau({.stages = 3, .newton = kTight});
  State state = model.initial_state();
  for (int i = 0; i < 100; ++i)
    radau.step(model, state, 1e-2);
  const Eigen::Vector3d n_carrier = carrier.orientation.transpose() * (rotor.orientation * axis);
  const Eigen::Matrix3d relative =
      orientation(model, state, holder).transpose() * orientation(model, state, spinning);
  const Eigen::Matrix3d expected =
      rotation(rate * state.time, n_carrier) * carrier.orientation.transpose() * rotor.orientation;
  const double moved = (state.q.head<3>() - carrier.position).norm();
  std::printf("rotor on a sprung carrier (carrier moved %.3f m): relative rotation off by %.2e\n",
              moved, Eigen::AngleAxisd(relative * expected.transpose()).angle());
  EXPECT_GT(moved, 0.01);
  EXPECT_LT(Eigen::AngleAxisd(relative * expected.transpose()).angle(), 1e-9);
}

TEST(MbdSpatialBadInput, DriveRateMustBeFiniteAndTheInitialSpinAgree) {
  DrivenRotor driven;
  RevoluteJoint3DSpec hinge;
  hinge.name = "motor2";
  hinge.a = {driven.rotor, Eigen::Vector3d::Zero()};
  hinge.b = {kGround, driven.spec.position};
  hinge.rate = std::numeric_limits<double>::infinity();
  const std::string message = error_message([&] { driven.model.add_revolute_joint_3d(hinge); });
  EXPECT_NE(message.find("revolute joint 'motor2'"), std::string::npos) << message;
  EXPECT_NE(message.find("drive rate is not finite"), std::string::npos) << message;
  EXPECT_NE(message.find("give a finite rate"), std::string::npos) << message;
  // A rotor at rest on a driven joint: its initial spin contradicts the drive, named by the row.
  Model model;
  RigidBody3DSpec spec;
  spec.name = "still";
  spec.mass = 1.0;
  spec.inertia = Eigen::Matrix3d::Identity();
  const BodyId still = model.add_rigid_body_3d(spec);
  model.add_revolute_joint_3d({"drive",
                               {still, Eigen::Vector3d::Zero()},
                               {kGround, Eigen::Vector3d::Zero()},
                               Eigen::Vector3d::UnitZ(),
                               1.5});
  const std::string inconsistent =
      error_message([&] { model.check_consistency(model.initial_state()); });
  EXPECT_NE(inconsistent.find("revolute joint 'drive' (drive): velocity residual"),
            std::string::npos)
      << inconsistent;
}

TEST(MbdSpatialLoads, SpringDamperHasExactDerivativesAndOscillatesAtItsFrequency) {
  const SpatialPair pair;
  const detail::SpatialPoint on_first(&pair.first, 0, {0.2, -0.15, 0.3});
  const detail::SpatialPoint on_second(&pair.second, 12, {-0.1, 0.35, -0.2});
  const detail::SpatialPoint on_ground(nullptr, 0, {-0.4, 0.25, 0.1});
  testing::expect_exact_force_derivatives(
      detail::SpatialPointToPointForce("spring", on_first, on_second, 0.4,
                                       std::make_shared<detail::LinearTension>(350.0, 12.0)),
      0.0, pair.q, pair.v, "spatial spring, body-body");
  testing::expect_exact_force_derivatives(
      detail::SpatialPointToPointForce("spring", on_ground, on_second, 0.4,
                                       std::make_shared<detail::LinearTension>(350.0, 12.0)),
      0.0, pair.q, pair.v, "spatial spring, ground-body");
  // A point mass on an oblique spring: x(t) = amplitude cos(sqrt(k/m) t) along the spring.
  Model model;
  const Eigen::Vector3d along = Eigen::Vector3d(1.0, -2.0, 2.0) / 3.0;
  const BodyId mass = model.add_point_mass({"m", 0.5, 1.1 * along, Eigen::Vector3d::Zero()});
  const int spring = model.add_spatial_spring_damper({"coil",
                                                      {kGround, Eigen::Vector3d::Zero()},
                                                      {mass, Eigen::Vector3d::Zero()},
                                                      200.0,
                                                      0.0,
                                                      1.0});
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = model.initial_state();
  for (int i = 0; i < 500; ++i)
    integrator.step(model, state, 1e-3);
  const double expected = 1.0 + 0.1 * std::cos(std::sqrt(200.0 / 0.5) * state.time);
  EXPECT_NEAR(state.q.head<3>().dot(along), expected, 1e-9);
  EXPECT_NEAR(force_element_force(model, state, spring), 200.0 * (expected - 1.0), 1e-6);
}

// A user's law along a spatial line: its derivatives (a law in elongation, rate and time), and a
// rope (tension only when stretched) that catches a falling mass: free fall while slack, then the
// deepest stretch of the energy balance m g (slack + e) = k e^2 / 2.
TEST(MbdSpatialLoads, NonlinearSpringDamperIsTheUsersLawAlongTheLine) {
  const SpatialPair pair;
  const detail::SpatialPoint on_first(&pair.first, 0, {0.2, -0.15, 0.3});
  const detail::SpatialPoint on_second(&pair.second, 12, {-0.1, 0.35, -0.2});
  const detail::SpatialPoint on_ground(nullptr, 0, {-0.4, 0.25, 0.1});
  const auto law = std::make_shared<detail::UserTension>([](double e, double r, double t) {
    return 300.0 * e + 4e3 * e * e * e + 15.0 * r + 2.0 * r * r * r + 7.0 * std::sin(3.0 * t);
  });
  testing::expect_exact_force_derivatives(
      detail::SpatialPointToPointForce("cubic", on_first, on_second, 0.4, law), 0.3, pair.q, pair.v,
      "spatial nonlinear spring, body-body");
  testing::expect_exact_force_derivatives(
      detail::SpatialPointToPointForce("cubic", on_ground, on_second, 0.4, law), 0.3, pair.q,
      pair.v, "spatial nonlinear spring, ground-body");

  const double mass = 0.5, stiffness = 200.0, slack = 0.2, rest = 1.0;
  Model model;
  model.set_spatial_gravity({0.0, 0.0, -kGravity});
  const BodyId bob =
      model.add_point_mass({"bob", mass, {0.0, 0.0, -(rest - slack)}, Eigen::Vector3d::Zero()});
  const int rope = model.add_spatial_nonlinear_spring_damper(
      {.name = "rope",
       .a = {kGround, Eigen::Vector3d::Zero()},
       .b = {bob, Eigen::Vector3d::Zero()},
       .tension = [&](double e, double, double) { return e > 0.0 ? stiffness * e : 0.0; },
       .rest_length = rest});
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = model.initial_state();
  double deepest = 0.0, largest_tension = 0.0;
  for (int i = 0; i < 4000; ++i) {
    integrator.step(model, state, 1e-4);
    if (i == 999) {  // t = 0.1 s: falling freely
      EXPECT_NEAR(state.q(2), -(rest - slack) - 0.5 * kGravity * 0.01, 1e-12);
      EXPECT_EQ(force_element_force(model, state, rope), 0.0);
    }
    deepest = std::max(deepest, -state.q(2) - rest);
    largest_tension = std::max(largest_tension, force_element_force(model, state, rope));
  }
  const double weight = mass * kGravity;
  const double expected =
      (weight + std::sqrt(weight * weight + 2.0 * stiffness * weight * slack)) / stiffness;
  std::printf("rope: deepest stretch %.9f m (energy balance %.9f), largest tension %.6f N\n",
              deepest, expected, largest_tension);
  EXPECT_NEAR(deepest, expected, 1e-6);
  EXPECT_NEAR(largest_tension, stiffness * expected, 2e-4);
  EXPECT_NEAR(state.q(0), 0.0, 1e-12);  // along the line only
  EXPECT_NEAR(state.q(1), 0.0, 1e-12);

  const std::string missing = error_message([&] {
    model.add_spatial_nonlinear_spring_damper(
        {.name = "loose", .a = {kGround, Eigen::Vector3d::Zero()}, .b = {bob, {}}, .tension = {}});
  });
  EXPECT_NE(missing.find("nonlinear spring-damper 'loose'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("no tension function"), std::string::npos) << missing;
}

// A bead on a rod turned at a constant rate w about z slides out as r0 cosh(w t) (no force along
// the rod; in the turning frame r'' = w^2 r) and turns with the rod: the prismatic joint holds the
// bead on the rod's line and its orientation to the rod's, here with both bodies turned off their
// principal frames.
TEST(MbdSpatialJoints, PrismaticJointSlidesABeadOutOnATurningRod) {
  const double w = 2.0, r0 = 0.1;
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d along(std::cos(0.3), std::sin(0.3), 0.0);
  Model model;
  model.set_spatial_gravity({0.0, 0.0, -kGravity});  // carried by the joints, normal to the rod
  RigidBody3DSpec rod = top_spec();
  rod.name = "rod";
  rod.position.setZero();
  rod.velocity.setZero();
  rod.angular_velocity = w * z;
  const BodyId turning = model.add_rigid_body_3d(rod);
  model.add_revolute_joint_3d({.name = "motor",
                               .a = {turning, Eigen::Vector3d::Zero()},
                               .b = {kGround, Eigen::Vector3d::Zero()},
                               .axis = rod.orientation.transpose() * z,
                               .rate = w});
  RigidBody3DSpec bead = top_spec();
  bead.name = "bead";
  bead.mass = 0.2;
  bead.position = r0 * along;
  bead.velocity = w * z.cross(bead.position);
  bead.angular_velocity = w * z;
  const BodyId sliding = model.add_rigid_body_3d(bead);
  const int first = model.add_prismatic_joint_3d({.name = "slider",
                                                  .a = {sliding, Eigen::Vector3d::Zero()},
                                                  .b = {turning, Eigen::Vector3d::Zero()},
                                                  .axis = bead.orientation.transpose() * along});
  EXPECT_EQ(model.constraint_count() - first, 5);
  model.check_consistency(model.initial_state());
  RadauIIA integrator({.stages = 3, .newton = kTight});
  State state = model.initial_state();
  for (int i = 0; i < 1000; ++i)
    integrator.step(model, state, 1e-3);
  const Eigen::Vector3d centre = state.q.segment<3>(12);
  const Eigen::Matrix3d turned = rotation(w * state.time, z);
  const double radius = r0 * std::cosh(w * state.time);
  std::printf(
      "bead on a turning rod: r(1 s) = %.12f m (r0 cosh(w t) = %.12f), off the rod's "
      "line %.2e m\n",
      centre.norm(), radius, (centre - radius * (turned * along)).norm());
  EXPECT_NEAR(centre.norm(), radius, 1e-9);
  EXPECT_LT((centre - radius * (turned * along)).norm(), 1e-9);
  for (int k = 0; k < 3; ++k) {  // the bead's axes turned with the rod
    EXPECT_LT((state.q.segment<3>(15 + 3 * k) - turned * bead.orientation.col(k)).norm(), 1e-9)
        << "axis " << k;
  }

  const auto mistake = [&](const PrismaticJoint3DSpec& spec) {
    return error_message([&] { model.add_prismatic_joint_3d(spec); });
  };
  const std::string off = mistake(
      {.name = "off", .a = {sliding, {}}, .b = {turning, {0.0, 0.0, 0.05}}, .axis = {1, 0, 0}});
  EXPECT_NE(off.find("prismatic joint 'off'"), std::string::npos) << off;
  EXPECT_NE(off.find("off the sliding line"), std::string::npos) << off;
  const std::string zero =
      mistake({.name = "", .a = {sliding, {}}, .b = {turning, {}}, .axis = {0, 0, 0}});
  EXPECT_NE(zero.find("the axis must be a finite, non-zero vector"), std::string::npos) << zero;
  const std::string same =
      mistake({.name = "", .a = {sliding, {}}, .b = {sliding, {}}, .axis = {1, 0, 0}});
  EXPECT_NE(same.find("same body"), std::string::npos) << same;
}

// --- the cable ---

AncfCableSpec steel_cable(int elements, const Eigen::Vector3d& end) {
  AncfCableSpec spec;  // Gerstmayr & Irschik's cantilever (ancf_cantilever_test.cpp)
  spec.name = "cable";
  spec.start = Eigen::Vector3d::Zero();
  spec.end = end;
  spec.element_count = elements;
  spec.axial_stiffness = 2.07e11 * 0.01;
  spec.bending_stiffness = 2.07e11 * 1e-4 / 12.0;
  spec.mass_per_length = 7800.0 * 0.01;
  return spec;
}

TEST(MbdSpatialCable, TubeVerticesStayOnTheTubeAroundTheBentCentreLine) {
  Model model;
  const double length = 2.0, radius = 0.05;
  const BodyId cable = model.add_ancf_cable(steel_cable(4, {length, 0.0, 0.0}));
  model.add_cable_clamp(cable, 0);
  std::vector<int> vertices;
  for (double s : {0.3, 1.1, 2.0}) {
    for (int k = 0; k < 6; ++k)
      vertices.push_back(
          model.add_cable_surface_marker(cable, s, k * std::numbers::pi / 3, radius));
  }
  const int tip = model.add_spatial_marker(cable, {length, 0.0, 0.0});
  std::vector<double> loads(3 * model.marker_count(), 0.0);
  loads[3 * tip + 1] = 1e6;  // bends the cable in the x-y plane, well past small deflection
  loads[3 * tip + 2] = -5e5;
  model.set_point_loads(loads);
  const State bent = solve_static(model, model.initial_state()).state;
  for (int k = 0; k < static_cast<int>(vertices.size()); ++k) {
    const double s = model.marker_local_coordinates(vertices[k]).x();
    const Eigen::Vector3d centre =
        point_position(model, bent, SpatialPointSpec{cable, {s, 0.0, 0.0}});
    const Eigen::Vector3d offset = marker_position(model, bent, vertices[k]) - centre;
    const double h = 1e-6;
    const Eigen::Vector3d ahead =
        point_position(model, bent, SpatialPointSpec{cable, {std::max(0.0, s - h), 0.0, 0.0}});
    const Eigen::Vector3d tangent = (centre - ahead).normalized();
    EXPECT_NEAR(offset.norm(), radius, 1e-12) << k;
    EXPECT_NEAR(offset.normalized().dot(tangent), 0.0, 1e-6) << k;
  }
  EXPECT_GT(std::abs(marker_position(model, bent, tip).y()), 0.5);
}

TEST(MbdSpatialCable, ElasticForceIsMinusTheGradientOfTheStrainEnergyWithExactDerivatives) {
  AncfCableSpec spec = steel_cable(2, {1.0, 0.4, -0.3});
  spec.axial_stiffness = 50.0;  // comparable axial and bending parts
  spec.bending_stiffness = 2.0;
  spec.axial_damping = 0.3;
  spec.bending_damping = 0.05;
  const detail::AncfCable3D cable(spec);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> value(-0.2, 0.2);
  Eigen::VectorXd q = cable.reference_coordinates(), v(q.size());
  for (Eigen::Index k = 0; k < q.size(); ++k) {
    q(k) += value(random);
    v(k) = 5.0 * value(random);
  }
  const auto n = q.size();
  auto force = [&](const Eigen::VectorXd& position, const Eigen::VectorXd& velocity) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
    cable.add_internal_force(position, velocity, f);
    return f;
  };
  Eigen::MatrixXd by_position = Eigen::MatrixXd::Zero(n, n), by_velocity = by_position;
  cable.add_internal_force_derivatives(q, v, by_position, by_velocity);
  const Eigen::VectorXd elastic = force(q, Eigen::VectorXd::Zero(n));
  const double step = 1e-6;
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::VectorXd plus = q, minus = q;
    plus(j) += step;
    minus(j) -= step;
    const double gradient = (cable.strain_energy(plus) - cable.strain_energy(minus)) / (2.0 * step);
    EXPECT_NEAR(elastic(j), -gradient, 1e-7 * (1.0 + std::abs(gradient))) << j;
    const Eigen::VectorXd by_q = (force(plus, v) - force(minus, v)) / (2.0 * step);
    Eigen::VectorXd vp = v, vm = v;
    vp(j) += step;
    vm(j) -= step;
    const Eigen::VectorXd by_v = (force(q, vp) - force(q, vm)) / (2.0 * step);
    for (Eigen::Index i = 0; i < n; ++i) {
      EXPECT_NEAR(by_position(i, j), by_q(i), 1e-6 * (1.0 + std::abs(by_q(i)))) << i << "," << j;
      EXPECT_NEAR(by_velocity(i, j), by_v(i), 1e-6 * (1.0 + std::abs(by_v(i)))) << i << "," << j;
    }
  }
}

// Gerstmayr & Irschik's large-deflection cantilever (F = 3 EI / L^2 at the tip) in a vertical
// plane through an oblique line: the spatial cable bends as the planar beam, whose tip
// displacement the reference table gives (ancf_cantilever_test.cpp).
TEST(MbdSpatialCable, CantileverInAnObliquePlaneMatchesThePlanarReference) {
  struct Row {
    int elements;
    double ux;
    double uy;
  };
  // /work/shared/reference-data/ancf_cantilever_gerstmayr_irschik_2008.dat
  const Row table[] = {{4, -0.50742871545579, -1.20553370256025},
                       {8, -0.50850923657299, -1.20719775609310}};
  const Eigen::Vector3d along = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  const double length = 2.0, load = 3.0 * 2.07e11 * (1e-4 / 12.0) / (length * length);
  for (const Row& row : table) {
    Model model;
    const BodyId cable = model.add_ancf_cable(steel_cable(row.elements, length * along));
    model.add_cable_clamp(cable, 0);
    const int tip = model.add_spatial_marker(cable, {length, 0.0, 0.0});
    model.set_point_loads(std::vector<double>{0.0, 0.0, -load});
    const StaticResult result = solve_static(model, model.initial_state());
    const Eigen::Vector3d displacement = marker_position(model, result.state, tip) - length * along;
    const Eigen::Vector3d expected = row.ux * along + row.uy * Eigen::Vector3d::UnitZ();
    const double error = (displacement - expected).norm() / expected.norm();
    std::printf("spatial cable cantilever, %d elements: tip off the planar table by %.2e\n",
                row.elements, error);
    EXPECT_LT(error, 1e-3);
  }
}

TEST(MbdSpatialCable, BendingFrequenciesComeInPairsAtTheReferenceValues) {
  Model model;
  const BodyId cable = model.add_ancf_cable(steel_cable(16, {0.0, 2.0, 0.0}));
  model.add_cable_clamp(cable, 0);
  const std::vector<double> f = natural_frequencies(model, model.initial_state(), 4);
  // Euler-Bernoulli clamped-free, same file: 20.8045 Hz and 130.3798 Hz, twice each (two bending
  // planes of an isotropic section).
  std::printf("spatial cable, 16 elements: %.6f %.6f %.6f %.6f Hz\n", f[0], f[1], f[2], f[3]);
  EXPECT_NEAR(f[0], 20.8045, 0.005 * 20.8045);
  EXPECT_NEAR(f[1], 20.8045, 0.005 * 20.8045);
  EXPECT_NEAR(f[2], 130.3798, 0.005 * 130.3798);
  EXPECT_NEAR(f[3], 130.3798, 0.005 * 130.3798);
}

// Every spatial element in one model: the sparse model matrices equal the dense ones and Radau
// IIA runs on the dense and the sparse path agree.
Model every_spatial_element() {
  Model model;
  model.set_spatial_gravity({0.0, 0.0, -kGravity});
  RigidBody3DSpec arm = top_spec();
  arm.name = "arm";
  arm.velocity.setZero();
  arm.angular_velocity = 0.7 * arm.orientation.col(2);
  arm.position = Eigen::Vector3d::Zero();
  const BodyId a = model.add_rigid_body_3d(arm);
  RevoluteJoint3DSpec hinge{"hinge",
                            {a, Eigen::Vector3d::Zero()},
                            {kGround, Eigen::Vector3d::Zero()},
                            Eigen::Vector3d::UnitZ()};
  model.add_revolute_joint_3d(hinge);
  RigidBody3DSpec lid = arm;
  lid.name = "lid";
  lid.position = arm.orientation * Eigen::Vector3d(0.4, 0.0, 0.0);
  lid.velocity = arm.angular_velocity.cross(lid.position);
  const BodyId b = model.add_rigid_body_3d(lid);
  model.add_fixed_joint_3d({"weld", b, a});
  const BodyId mass = model.add_point_mass(
      {"mass", 0.3, lid.position + Eigen::Vector3d(0.0, 0.0, -0.5), lid.velocity});
  model.add_spatial_distance_constraint({b, Eigen::Vector3d::Zero()},
                                        {mass, Eigen::Vector3d::Zero()});
  AncfCableSpec rope = steel_cable(3, {1.0, 0.0, 0.0});
  rope.start = {0.0, 1.0, 0.0};
  rope.end = {1.0, 1.0, 0.2};
  rope.axial_stiffness = 1e5;
  rope.bending_stiffness = 10.0;
  rope.mass_per_length = 0.5;
  const BodyId cable = model.add_ancf_cable(rope);
  model.add_cable_clamp(cable, 0);
  model.add_spatial_torque(
      {"motor", b, [](double t) { return Eigen::Vector3d(0.1, 0.2, 1.0 + t); }});
  model.add_spatial_point_force(
      {"push", {cable, {0.8, 0.0, 0.0}}, [](double t) { return Eigen::Vector3d(0.0, t, 1.0); }});
  model.add_spatial_marker(a, {0.1, 0.2, 0.0});
  model.add_spatial_marker(cable, {0.5, 0.0, 0.0});
  model.add_cable_surface_marker(cable, 0.9, 1.0, 0.02);
  model.set_point_loads(std::vector<double>{1.0, -2.0, 0.5, 0.3, 0.2, -0.1, 0.0, 1.0, 0.0});
  return model;
}

TEST(MbdSpatialBodies, SparseAssemblyEqualsTheDenseOneAndRunsAgree) {
  const Model model = every_spatial_element();
  const State state = model.initial_state();
  testing::expect_sparse_model_matrices_equal(model, state);

  State dense = state, sparse = state;
  RadauIIA dense_integrator({.stages = 3, .newton = {.linear_solver = LinearSolver::Dense}});
  RadauIIA sparse_integrator({.stages = 3, .newton = {.linear_solver = LinearSolver::Sparse}});
  for (int i = 0; i < 20; ++i) {
    dense_integrator.step(model, dense, 1e-3);
    sparse_integrator.step(model, sparse, 1e-3);
  }
  const double moved = (dense.q - state.q).lpNorm<Eigen::Infinity>();
  const double q_difference = (dense.q - sparse.q).lpNorm<Eigen::Infinity>();
  std::printf("every spatial element, 20 steps: sparse - dense q %.1e (moved %.2e)\n", q_difference,
              moved);
  EXPECT_GT(moved, 1e-4);
  EXPECT_LT(q_difference, 1e-12 * (1.0 + dense.q.lpNorm<Eigen::Infinity>()));
}

// --- bad input ---

TEST(MbdSpatialBadInput, InvalidBodiesAndMixturesAreNamed) {
  {
    RigidBody3DSpec spec = top_spec();
    spec.orientation(0, 0) = 1.5;
    Model model;
    EXPECT_NE(error_message([&] { model.add_rigid_body_3d(spec); }).find("not a rotation matrix"),
              std::string::npos);
  }
  {
    RigidBody3DSpec spec = top_spec();
    spec.inertia = Eigen::Vector3d(1.0, 1.0, 2.0).asDiagonal();  // a flat disc: E_33 = 0
    Model model;
    const std::string message = error_message([&] { model.add_rigid_body_3d(spec); });
    EXPECT_NE(message.find("rigid body 'top'"), std::string::npos) << message;
    EXPECT_NE(message.find("less than the sum of the other two"), std::string::npos) << message;
  }
  {
    Model model;
    RigidBody2DSpec planar;
    planar.name = "plate";
    planar.mass = 1.0;
    planar.inertia = 1.0;
    model.add_rigid_body(planar);
    const std::string message = error_message([&] { model.add_rigid_body_3d(top_spec()); });
    EXPECT_NE(message.find("not both"), std::string::npos) << message;
  }
  {
    Model model;
    const BodyId mass = model.add_point_mass({"mass", 1.0, {}, {}});
    const std::string message = error_message([&] {
      model.add_spatial_marker(mass, {0.1, 0.0, 0.0});
    });
    EXPECT_NE(message.find("point mass 'mass'"), std::string::npos) << message;
    EXPECT_NE(error_message([&] {
                model.add_revolute_joint({mass, {0.0, 0.0}}, {kGround, {0.0, 0.0}});
              }).find("is a spatial body"),
              std::string::npos);
  }
  {
    Model model;
    const BodyId cable = model.add_ancf_cable(steel_cable(2, {1.0, 0.0, 0.0}));
    const std::string message = error_message([&] {
      model.add_spatial_marker(cable, {0.5, 0.1, 0.0});
    });
    EXPECT_NE(message.find("off the centre line"), std::string::npos) << message;
    RevoluteJoint3DSpec hinge;
    hinge.a = {cable, Eigen::Vector3d::Zero()};
    EXPECT_NE(error_message([&] { model.add_revolute_joint_3d(hinge); }).find("not a rigid body"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace fsi::mbd
