#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fsi/common/error.hpp"
#include "fsi/mbd/model.hpp"

namespace fsi::mbd {
namespace {

RigidBody2DSpec body(const std::string& name, double x = 0.0, double y = 0.0, double angle = 0.0) {
  RigidBody2DSpec spec;
  spec.name = name;
  spec.mass = 2.0;
  spec.inertia = 0.5;
  spec.position = {x, y};
  spec.angle = angle;
  return spec;
}

TEST(Model, PointLoadGeneralisedForceIsTheGradientOfItsWork) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Model model;
    const BodyId b = model.add_rigid_body(body("b", u(rng), u(rng), 3.0 * u(rng)));
    model.add_marker(b, {u(rng), u(rng)});
    model.add_marker(b, {u(rng), u(rng)});
    model.add_marker(kGround, {u(rng), u(rng)});
    const std::vector<double> loads{u(rng), u(rng), u(rng), u(rng), 5.0, 5.0};
    model.set_point_loads(loads);
    State state = model.initial_state();
    Eigen::VectorXd force;
    model.applied_force(0.0, state.q, state.v, force);
    // Work of constant world-frame loads W(q) = sum f . r(q); Q = dW/dq.
    auto work = [&](const Eigen::VectorXd& q) {
      State probe = state;
      probe.q = q;
      std::vector<double> r(6);
      model.marker_positions(probe, r);
      double sum = 0.0;
      for (int k = 0; k < 4; ++k)
        sum += loads[k] * r[k];  // ground marker: no work
      return sum;
    };
    for (int j = 0; j < 3; ++j) {
      Eigen::VectorXd plus = state.q, minus = state.q;
      plus(j) += 1e-6;
      minus(j) -= 1e-6;
      EXPECT_NEAR(force(j), (work(plus) - work(minus)) / 2e-6, 1e-8) << "coordinate " << j;
    }
  }
}

TEST(Model, MarkersFollowTheBody) {
  Model model;
  const BodyId b = model.add_rigid_body(body("b", 1.0, 2.0, M_PI / 2));
  model.add_marker(b, {1.0, 0.0});
  State state = model.initial_state();
  state.v << 0.5, 0.0, 2.0;
  std::vector<double> r(2), u(2);
  model.marker_positions(state, r);
  model.marker_velocities(state, u);
  EXPECT_NEAR(r[0], 1.0, 1e-15);
  EXPECT_NEAR(r[1], 3.0, 1e-15);
  // u = v_c + omega x (r - c) = (0.5, 0) + 2 * (-1, 0)
  EXPECT_NEAR(u[0], 0.5 - 2.0, 1e-15);
  EXPECT_NEAR(u[1], 0.0, 1e-15);
}

TEST(Model, ResultantOfPointLoadsGivesForceAndTorque) {
  Model model;
  const BodyId b = model.add_rigid_body(body("b"));
  model.add_marker(b, {1.0, 0.0});
  model.add_marker(b, {-1.0, 0.0});
  model.set_point_loads(std::vector<double>{0.0, 1.0, 0.0, 1.0});
  const Eigen::Vector3d resultant = model.point_load_resultant(model.initial_state(), b);
  EXPECT_DOUBLE_EQ(resultant(0), 0.0);
  EXPECT_DOUBLE_EQ(resultant(1), 2.0);
  EXPECT_DOUBLE_EQ(resultant(2), 0.0);
  model.set_point_loads(std::vector<double>{0.0, 1.0, 0.0, -1.0});
  EXPECT_DOUBLE_EQ(model.point_load_resultant(model.initial_state(), b)(2), 2.0);
}

TEST(Model, BadInputIsNamed) {
  Model model;
  RigidBody2DSpec bad = body("heavy");
  bad.mass = -1.0;
  try {
    model.add_rigid_body(bad);
    FAIL();
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find("rigid body 'heavy'"), std::string::npos);
  }
  model.add_rigid_body(body("a"));
  EXPECT_THROW(model.add_rigid_body(body("a")), fsi::Error);
  try {
    model.find_body("b");
    FAIL();
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find("known bodies: a"), std::string::npos);
  }
}

TEST(Model, InconsistentInitialConstraintsAreAllReported) {
  Model model;
  const BodyId b = model.add_rigid_body(body("piston", 0.0, 1.0));
  model.add_coordinate_constraint(b, Coordinate::Y, 2.0);
  model.add_velocity_constraint(b, Coordinate::X, 0.3);
  try {
    model.initial_state();
    FAIL();
  } catch (const fsi::Error& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("coordinate constraint on piston.y"), std::string::npos) << text;
    EXPECT_NE(text.find("velocity constraint on piston.x"), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace fsi::mbd
