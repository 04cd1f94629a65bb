#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "error_message.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"
#include "test_elements.hpp"

namespace fsi::mbd {
namespace {

using testing::error_message;

RigidBody2DSpec body_spec(const std::string& name, double x = 0.0, double y = 0.0,
                          double angle = 0.0) {
  RigidBody2DSpec spec;
  spec.name = name;
  spec.mass = 2.0;
  spec.inertia = 0.5;
  spec.position = {x, y};
  spec.angle = angle;
  return spec;
}

// Work of constant world-frame loads, W(q) = sum_k f_k . r_k(q); its gradient is the
// generalised force of the loads (virtual work, thesis eq. 2.6-2.8).
TEST(MbdModel, PointLoadGeneralisedForceIsTheGradientOfItsWork) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Model model;
    model.add_rigid_body(body_spec("other", u(rng), u(rng), u(rng)));
    const BodyId b = model.add_rigid_body(body_spec("b", u(rng), u(rng), 3.0 * u(rng)));
    model.add_marker(b, {u(rng), u(rng)});
    model.add_marker(b, {u(rng), u(rng)});
    model.add_marker(kGround, {u(rng), u(rng)});
    const std::vector<double> loads{u(rng), u(rng), u(rng), u(rng), 5.0, 5.0};
    model.set_point_loads(loads);
    const State state = model.initial_state();
    Eigen::VectorXd force;
    model.applied_force(0.0, state.q, state.v, force);
    auto work = [&](const Eigen::VectorXd& q) {
      State probe = state;
      probe.q = q;
      double sum = 0.0;
      for (int k = 0; k < 2; ++k)  // the ground marker does no work
        sum += Eigen::Vector2d(loads[2 * k], loads[2 * k + 1])
                   .dot(marker_position(model, probe, k).head<2>());
      return sum;
    };
    for (int j = 0; j < model.coordinate_count(); ++j) {
      Eigen::VectorXd plus = state.q, minus = state.q;
      plus(j) += 1e-6;
      minus(j) -= 1e-6;
      EXPECT_NEAR(force(j), (work(plus) - work(minus)) / 2e-6, 1e-9) << "coordinate " << j;
    }
    // The angle component is the torque about the centre of mass.
    EXPECT_NEAR(force(model.coordinate_index(b, Coordinate::Angle)),
                point_load_resultant(model, state, b).planar()(2), 1e-14);
  }
}

TEST(MbdModel, MarkerJacobianAndVelocityMatchDifferencesOfThePosition) {
  Model model;
  model.add_rigid_body(body_spec("a", 0.3, -0.2, 0.1));
  const BodyId b = model.add_rigid_body(body_spec("b", 1.0, 2.0, 2.5));
  const int marker = model.add_marker(b, {0.4, -0.7});
  State state = model.initial_state();
  state.v << 0.1, 0.2, 0.3, -0.5, 0.25, 1.5;
  const Eigen::MatrixXd jacobian = model.marker_jacobian(state.q, marker);
  ASSERT_EQ(jacobian.rows(), 2);
  ASSERT_EQ(jacobian.cols(), 6);
  for (int j = 0; j < 6; ++j) {
    State plus = state, minus = state;
    plus.q(j) += 1e-6;
    minus.q(j) -= 1e-6;
    const Eigen::Vector2d difference =
        (marker_position(model, plus, marker) - marker_position(model, minus, marker)).head<2>() /
        2e-6;
    EXPECT_NEAR((jacobian.col(j) - difference).norm(), 0.0, 1e-9) << "coordinate " << j;
  }
  EXPECT_NEAR((marker_velocity(model, state, marker).head<2>() - jacobian * state.v).norm(), 0.0,
              1e-15);
  EXPECT_EQ(model.marker_jacobian(state.q, model.add_marker(kGround, {1, 1})).norm(), 0.0);
}

TEST(MbdModel, MarkersFollowTheBody) {
  Model model;
  const BodyId b = model.add_rigid_body(body_spec("b", 1.0, 2.0, std::numbers::pi / 2));
  model.add_marker(b, {1.0, 0.0});
  model.add_marker(kGround, {-3.0, 4.0});
  State state = model.initial_state();
  state.v << 0.5, 0.0, 2.0;
  std::vector<double> r(4), u(4);
  marker_positions(model, state, r);
  marker_velocities(model, state, u);
  EXPECT_NEAR(r[0], 1.0, 1e-15);
  EXPECT_NEAR(r[1], 3.0, 1e-15);
  // u = v_c + omega x (r - c) = (0.5, 0) + 2 (-1, 0).
  EXPECT_NEAR(u[0], 0.5 - 2.0, 1e-15);
  EXPECT_NEAR(u[1], 0.0, 1e-15);
  EXPECT_EQ(r[2], -3.0);
  EXPECT_EQ(r[3], 4.0);
  EXPECT_EQ(u[2], 0.0);
  EXPECT_EQ(u[3], 0.0);
}

// dF/dq and dF/dv against central differences of F: gravity, point loads on rotated bodies,
// an element with analytic derivatives and one differentiated by the model.
TEST(MbdModel, AppliedForceDerivativesMatchDifferences) {
  Model model;
  model.set_gravity({0.3, -9.81});
  const BodyId a = model.add_rigid_body(body_spec("a", 0.1, 0.2, 0.7));
  const BodyId b = model.add_rigid_body(body_spec("b", -0.4, 0.5, -2.1));
  model.add_marker(a, {0.3, 0.1});
  model.add_marker(b, {-0.2, 0.6});
  model.add_marker(b, {0.5, -0.1});
  model.set_point_loads(std::vector<double>{1.5, -2.0, 0.7, 3.0, -4.0, 0.2});
  model.add_force_element(
      std::make_unique<testing::LinearSpring>(model.coordinate_index(a, Coordinate::X), 40.0));
  model.add_force_element(std::make_unique<testing::NonlinearCoupling>(
      model.coordinate_index(a, Coordinate::Angle), model.coordinate_index(b, Coordinate::Y)));
  State state = model.initial_state();
  state.v << 0.3, -0.1, 0.8, 0.2, 0.4, -0.6;
  const double t = 0.25;
  Eigen::MatrixXd by_position, by_velocity;
  model.applied_force_derivatives(t, state.q, state.v, by_position, by_velocity);
  Eigen::VectorXd plus, minus;
  for (int j = 0; j < 6; ++j) {
    Eigen::VectorXd q = state.q, v = state.v;
    const double step = 1e-5;
    q(j) += step;
    model.applied_force(t, q, state.v, plus);
    q(j) -= 2 * step;
    model.applied_force(t, q, state.v, minus);
    EXPECT_LE((by_position.col(j) - (plus - minus) / (2 * step)).norm(), 1e-8) << "q " << j;
    v(j) += step;
    model.applied_force(t, state.q, v, plus);
    v(j) -= 2 * step;
    model.applied_force(t, state.q, v, minus);
    EXPECT_LE((by_velocity.col(j) - (plus - minus) / (2 * step)).norm(), 1e-8) << "v " << j;
  }
  EXPECT_NE(by_position(2, 2), 0.0) << "point loads at offsets make the torque depend on phi";
}

TEST(MbdModel, LoadsOnGroundMarkersAreIgnored) {
  Model model;
  model.add_rigid_body(body_spec("b"));
  model.add_marker(kGround, {0.0, 0.0});
  model.set_point_loads(std::vector<double>{100.0, 100.0});
  const State state = model.initial_state();
  Eigen::VectorXd force;
  model.applied_force(0.0, state.q, state.v, force);
  EXPECT_EQ(force.norm(), 0.0);
  EXPECT_NE(error_message([&] {
              model.set_point_loads(std::vector<double>{1.0});
            }).find("one (x, y) pair per marker"),
            std::string::npos);
}

TEST(MbdModel, ResultantOfPointLoadsGivesForceAndTorqueAboutTheCentreOfMass) {
  Model model;
  const BodyId b = model.add_rigid_body(body_spec("b", 5.0, 7.0, std::numbers::pi / 2));
  model.add_marker(b, {1.0, 0.0});   // at (5, 8)
  model.add_marker(b, {-1.0, 0.0});  // at (5, 6)
  model.set_point_loads(std::vector<double>{1.0, 0.0, 1.0, 0.0});
  const State state = model.initial_state();
  Eigen::Vector3d resultant = point_load_resultant(model, state, b).planar();
  EXPECT_NEAR(resultant(0), 2.0, 1e-15);
  EXPECT_NEAR(resultant(1), 0.0, 1e-15);
  EXPECT_NEAR(resultant(2), 0.0, 1e-15);
  model.set_point_loads(std::vector<double>{1.0, 0.0, -1.0, 0.0});
  resultant = point_load_resultant(model, state, b).planar();
  EXPECT_NEAR(resultant(2), -2.0, 1e-15);  // (0, 1) x (1, 0) + (0, -1) x (-1, 0) = -1 - 1
}

TEST(MbdModel, EnergiesOfARigidBody) {
  Model model;
  model.set_gravity({0.0, -9.81});
  RigidBody2DSpec spec = body_spec("b", 1.0, 3.0);
  spec.velocity = {2.0, -1.0};
  spec.angular_velocity = 4.0;
  model.add_rigid_body(spec);
  const State state = model.initial_state();
  EXPECT_DOUBLE_EQ(kinetic_energy(model, state), 0.5 * 2.0 * 5.0 + 0.5 * 0.5 * 16.0);
  EXPECT_DOUBLE_EQ(potential_energy(model, state), 2.0 * 9.81 * 3.0);
}

TEST(MbdModel, BadBodiesAndReferencesAreNamed) {
  Model model;
  RigidBody2DSpec bad = body_spec("heavy");
  bad.mass = -1.0;
  EXPECT_NE(error_message([&] { model.add_rigid_body(bad); }).find("rigid body 'heavy'"),
            std::string::npos);
  bad = body_spec("spinner");
  bad.inertia = 0.0;
  EXPECT_NE(error_message([&] { model.add_rigid_body(bad); }).find("inertia must be positive"),
            std::string::npos);
  bad = body_spec("lost");
  bad.angle = std::nan("");
  EXPECT_NE(error_message([&] { model.add_rigid_body(bad); }).find("rigid body 'lost'"),
            std::string::npos);
  model.add_rigid_body(body_spec("a"));
  EXPECT_NE(error_message([&] { model.add_rigid_body(body_spec("a")); }).find("second body"),
            std::string::npos);
  EXPECT_NE(error_message([&] { model.find_body("b"); }).find("known bodies: a"),
            std::string::npos);
  EXPECT_THROW(model.add_marker(3, {0.0, 0.0}), fsi::Error);
  EXPECT_THROW(model.add_coordinate_constraint(1, Coordinate::X), fsi::Error);
  EXPECT_THROW(model.add_velocity_constraint(0, Coordinate::Y, std::nan("")), fsi::Error);
  EXPECT_EQ(model.body_count(), 1);
  EXPECT_EQ(model.coordinate_count(), 3);
}

TEST(MbdModel, EveryInconsistencyOfTheInitialStateIsReportedAtOnce) {
  Model model;
  RigidBody2DSpec piston = body_spec("piston", 0.0, 1.0);
  piston.velocity = {0.2, 0.0};
  const BodyId b = model.add_rigid_body(piston);
  model.add_coordinate_constraint(b, Coordinate::Y, 2.0);    // at y = 1
  model.add_coordinate_constraint(b, Coordinate::X);         // holds x but vx = 0.2
  model.add_velocity_constraint(b, Coordinate::Angle, 0.3);  // omega = 0
  model.add_velocity_constraint(b, Coordinate::Y, 0.0);      // y constrained twice
  const std::string text = error_message([&] { model.initial_state(); });
  EXPECT_NE(text.find("coordinate constraint on piston.y: position residual C = -1"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("coordinate constraint on piston.x: velocity residual dC/dt = 0.2"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("velocity constraint on piston.angle: velocity residual = -0.3"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("velocity constraint on piston.y: redundant"), std::string::npos) << text;
  EXPECT_NE(text.find("how to fix"), std::string::npos) << text;
}

TEST(MbdModel, ConsistentInitialStatePasses) {
  Model model;
  RigidBody2DSpec piston = body_spec("piston", 0.025, 0.0725);
  piston.velocity = {0.0, -0.05};
  const BodyId b = model.add_rigid_body(piston);
  model.add_coordinate_constraint(b, Coordinate::X);
  model.add_coordinate_constraint(b, Coordinate::Angle);
  model.add_velocity_constraint(b, Coordinate::Y, -0.05);
  const State state = model.initial_state();
  EXPECT_EQ(position_constraint_drift(model, state), 0.0);
  EXPECT_EQ(velocity_constraint_drift(model, state), 0.0);
  EXPECT_EQ(model.constraint_description(2), "velocity constraint on piston.y");
  EXPECT_EQ(model.constraint_level(2), ConstraintLevel::Velocity);
}

// -G^T lambda of a held body balances gravity and loads already at t = 0 (consistent lambda).
TEST(MbdModel, InitialMultipliersBalanceGravityAndLoads) {
  Model model;
  model.set_gravity({0.0, -9.81});
  RigidBody2DSpec spec = body_spec("bottom", 0.025, 0.0, 0.3);
  spec.mass = 0.25;
  spec.inertia = 5e-5;
  const BodyId b = model.add_rigid_body(spec);
  model.add_marker(b, {0.02, 0.003});
  model.set_point_loads(std::vector<double>{1.0, -10.0});
  for (Coordinate c : {Coordinate::X, Coordinate::Y, Coordinate::Angle})
    model.add_coordinate_constraint(b, c);
  const State state = model.initial_state();
  Eigen::VectorXd applied;
  model.applied_force(0.0, state.q, state.v, applied);
  const Eigen::VectorXd constraint = generalised_constraint_force(model, state);
  EXPECT_NEAR((constraint + applied).norm(), 0.0, 1e-14);
  EXPECT_DOUBLE_EQ(constraint_force(model, state, b, Coordinate::Y), -applied(1));
  // The sign convention: the constraint force is -G^T lambda, G = identity rows here.
  EXPECT_DOUBLE_EQ(state.lambda(1), applied(1));
}

}  // namespace
}  // namespace fsi::mbd
