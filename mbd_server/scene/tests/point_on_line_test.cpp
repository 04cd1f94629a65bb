// The PointOnLine family (src/family_point_on_line.cpp): its row's derivatives are exact, a bead
// on an inclined line slides as the closed form says and its reaction sensor reads the normal
// force, and mistakes are problems at the block.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/scene/scene.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

class PointOnLineScene : public testing::FolderPerTest {
 protected:
  // A structure-only scene: no mesh, LIGGGHTS or Coupling needed.
  Scene build(const std::string& body) const {
    return build_scene(write("slider.scene",
                             "scene_language = 1\n"
                             "SolverOptions { end_time = 0.5; Timeint { step_size = 1e-3 } }\n" +
                                 body),
                       {}, SceneMode::MbdOnly);
  }
};

// Line on a turned carrier, point on a turned bead: every term of the row is non-zero.
const char* const kTwoBodies = R"scene(
RigidBody2D { name = "carrier"; mass = 2; inertia = 0.3 }
RigidBody2D { name = "bead"; mass = 1; inertia = 0.1; position = [0.65, 1.03] }
PointOnLine { name = "slot"; body_a = "carrier"; point_a = [0.1, 0.2]; axis = [0.6, 0.8];
              body_b = "bead"; point_b = [0.05, -0.03] }
)scene";

TEST_F(PointOnLineScene, RowDerivativesMatchDifferences) {
  const Scene scene = build(kTwoBodies);
  const mbd::Model& model = scene.model;
  ASSERT_EQ(model.constraint_count(), 1);
  const Eigen::VectorXd q{{0.3, -0.2, 0.7, 1.1, 0.4, -2.1}};
  const Eigen::VectorXd v{{0.5, -1.5, 2.0, -0.7, 0.9, 3.0}};
  auto residual = [&](const Eigen::VectorXd& at) {
    Eigen::VectorXd c;
    model.constraint_residual(0.0, at, v, c);
    return c(0);
  };
  auto jacobian = [&](const Eigen::VectorXd& at) {
    Eigen::MatrixXd g;
    model.constraint_jacobian(0.0, at, g);
    return Eigen::RowVectorXd(g.row(0));
  };
  const double multiplier = -2.3;
  const Eigen::RowVectorXd g = jacobian(q);
  Eigen::MatrixXd force_derivative;
  model.constraint_force_derivative(0.0, q, Eigen::VectorXd::Constant(1, multiplier),
                                    force_derivative);
  const double step = 1e-6;
  for (Eigen::Index j = 0; j < q.size(); ++j) {
    Eigen::VectorXd plus = q, minus = q;
    plus(j) += step;
    minus(j) -= step;
    EXPECT_NEAR(g(j), (residual(plus) - residual(minus)) / (2.0 * step), 1e-9) << "G(" << j << ")";
    const Eigen::RowVectorXd g_difference = (jacobian(plus) - jacobian(minus)) / (2.0 * step);
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      EXPECT_NEAR(force_derivative(i, j), multiplier * g_difference(i), 1e-8)
          << "d(G^T lambda)/dq(" << i << ", " << j << ")";
    }
  }
  const double dt = 1e-4;
  const double second =
      (residual(q + dt * v) - 2.0 * residual(q) + residual(q - dt * v)) / (dt * dt);
  Eigen::VectorXd remainder;
  model.constraint_acceleration_remainder(0.0, q, v, remainder);
  EXPECT_NEAR(remainder(0), second, 1e-6 * (1.0 + std::abs(second)));
}

// A bead on a frictionless line at angle alpha to the horizontal: along the line it falls with
// g sin(alpha), so x(t) = -1/2 g sin(alpha) cos(alpha) t^2, and the line pushes it with the normal
// force m g cos(alpha) along n = (-sin(alpha), cos(alpha)).
TEST_F(PointOnLineScene, BeadSlidesDownAnInclinedLine) {
  const double alpha = 0.5, g = 9.81, mass = 2.0;
  Scene scene = build(R"scene(
Gravity { acceleration = [0, -9.81] }
RigidBody2D { name = "bead"; mass = 2; inertia = 0.1; angular_velocity = 3 }
PointOnLine { name = "wire"; body_b = "bead"; axis = [cos(0.5), sin(0.5)] }
Sensor { name = "normal_x"; type = "joint_force"; joint = "wire"; component = "x" }
Sensor { name = "normal_y"; type = "joint_force"; joint = "wire"; component = "y" }
Sensor { name = "bead_x"; type = "position"; body = "bead"; component = "x" }
Sensor { name = "spin"; type = "velocity"; body = "bead"; component = "angle" }
)scene");
  ASSERT_EQ(scene.sensors.size(), 4u);
  EXPECT_EQ(scene.sensors[0].unit, "N/m");
  mbd::State state = scene.model.initial_state();
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  for (int step = 0; step < 500; ++step)
    integrator.step(scene.model, state, scene.solver.step_size);
  const double t = state.time;
  ASSERT_NEAR(t, 0.5, 1e-12);
  const double normal = mass * g * std::cos(alpha);
  // lambda is as exact as the Newton iterations that give it (relative tolerance 1e-10).
  const double force_tolerance = 1e-9 * normal;
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[0], state),
              -normal * std::sin(alpha), force_tolerance);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[1], state),
              normal * std::cos(alpha), force_tolerance);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[2], state),
              -0.5 * g * std::sin(alpha) * std::cos(alpha) * t * t, 1e-10);
  // The rotation is free: the bead keeps spinning.
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[3], state), 3.0, 1e-10);
}

TEST_F(PointOnLineScene, MistakesAreProblemsAtTheBlock) {
  auto problems = [&](const std::string& body) -> std::string {
    try {
      build(body);
    } catch (const Error& error) {
      return error.what();
    }
    return "(accepted)";
  };
  EXPECT_NE(problems("PointOnLine { axis = [1, 0] }\n")
                .find("slider.scene:3:1: both points of the PointOnLine are on the ground"),
            std::string::npos);
  EXPECT_NE(problems("RigidBody2D { name = \"bead\"; mass = 1; inertia = 1 }\n"
                     "PointOnLine { body_b = \"bead\"; axis = [0, 0] }\n")
                .find("slider.scene:4:"),
            std::string::npos);
  // Off the line at the start: the initial state is refused, naming the row.
  EXPECT_NE(problems("RigidBody2D { name = \"bead\"; mass = 1; inertia = 1; position = [0, 1] }\n"
                     "PointOnLine { name = \"wire\"; body_b = \"bead\" }\n")
                .find("point on line 'wire'"),
            std::string::npos);
  EXPECT_NE(problems("PointOnLine { body_b = \"nobody\" }\n").find("slider.scene:3:"),
            std::string::npos);
}

}  // namespace
}  // namespace fsi::scene
