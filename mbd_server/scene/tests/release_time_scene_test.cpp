// `release_time` on the constraint blocks (declared once, scene_builder's releasable()): every
// row a block adds is released at that time, its sensors read the holding force before and zero
// after, and a bad value is a problem at its file:line:column.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/scene/scene.hpp"
#include "fsi/scene/schema.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

class ReleaseTimeScene : public testing::FolderPerTest {
 protected:
  std::string write(const std::string& body) const {
    return write_coupled_scene(
               "r.scene", "SolverOptions { end_time = 1; Timeint { step_size = 0.01 } }\n" + body)
        .string();
  }
  std::string problems(const std::string& body) const {
    return testing::message_thrown([&] { build_scene(write(body)); });
  }
};

// A block held at x, y and angle by three coordinate constraints, y released at 0.305 s, and a
// bob hanging at rest below a revolute joint released at 0.5 s (both rows).
const char* const kReleased = R"scene(Gravity { acceleration = [0, -9.81] }
RigidBody2D { name = "block"; mass = 2; inertia = 0.1; position = [0, 1]; Mesh { points = [[0, 0], [1, 0]] } }
RigidBody2D { name = "bob"; mass = 1; inertia = 0.1; position = [3, 0] }
CoordinateConstraint { body = "block"; coordinate = "x" }
CoordinateConstraint { body = "block"; coordinate = "y"; release_time = 0.305 }
CoordinateConstraint { body = "block"; coordinate = "angle" }
RevoluteJoint { name = "pin"; body_a = "bob"; point_a = [0, 1]; point_b = [3, 1]; release_time = 0.5 }
Sensor { name = "held_y"; type = "constraint_force"; body = "block"; component = "y" }
Sensor { name = "pin_y"; type = "joint_force"; joint = "pin"; component = "y" }
)scene";

TEST_F(ReleaseTimeScene, EveryRowOfAReleasedBlockIsReleasedAtItsTime) {
  Scene scene = build_scene(write(kReleased));
  const mbd::Model& model = scene.model;
  ASSERT_EQ(model.constraint_count(), 5);
  const double never = model.release_time(0);
  EXPECT_TRUE(std::isinf(never));
  EXPECT_EQ(model.release_time(1), 0.305);
  EXPECT_TRUE(std::isinf(model.release_time(2)));
  EXPECT_EQ(model.release_time(3), 0.5);  // both rows of the revolute joint
  EXPECT_EQ(model.release_time(4), 0.5);

  mbd::RadauIIA integrator(3);
  mbd::State state = model.initial_state();
  double before = 0.0, after = 0.0, pin_before = 0.0, pin_after = 0.0;
  while (state.time < 0.7) {
    integrator.step(model, state, 0.01);
    const double held = structure_sensor_value(model, scene.sensors[0], state);
    const double pin = structure_sensor_value(model, scene.sensors[1], state);
    if (state.time <= 0.305) {
      before = std::max(before, std::abs(held - 2 * 9.81));
    } else {
      after = std::max(after, std::abs(held));
    }
    // 50 steps of 0.01 s end within rounding of 0.5 s: the row held over that step, and the
    // release is taken at its end (ConstrainedSystem::release_within).
    if (state.time <= 0.5 + 1e-9) {
      pin_before = std::max(pin_before, std::abs(pin - 9.81));
    } else {
      pin_after = std::max(pin_after, std::abs(pin));
    }
  }
  EXPECT_LT(before, 1e-9);  // the y row carries the block's weight until 0.305 s
  EXPECT_EQ(after, 0.0);    // and nothing from then on
  EXPECT_LT(pin_before, 1e-9);
  EXPECT_EQ(pin_after, 0.0);
  // The block fell freely from 0.305 s on.
  EXPECT_NEAR(state.q(1), 1.0 - 0.5 * 9.81 * (0.7 - 0.305) * (0.7 - 0.305), 1e-9);
}

TEST_F(ReleaseTimeScene, ANegativeReleaseTimeIsAProblemAtItsPlace) {
  const std::string text = problems(
      R"scene(RigidBody2D { name = "block"; mass = 2; inertia = 0.1; Mesh { points = [[0, 0], [1, 0]] } }
CoordinateConstraint { body = "block"; coordinate = "y"; release_time = -1 }
)scene");
  EXPECT_NE(text.find("r.scene:4:"), std::string::npos) << text;
  EXPECT_NE(text.find("release_time"), std::string::npos) << text;
  EXPECT_NE(text.find("out of range"), std::string::npos) << text;
}

TEST_F(ReleaseTimeScene, EveryConstraintBlockDeclaresReleaseTimeAndNoOtherBlockDoes) {
  const BlockSpec& root = scene_schema();
  const char* const constraints[] = {"CoordinateConstraint",
                                     "VelocityConstraint",
                                     "BeamClamp",
                                     "RevoluteJoint",
                                     "DistanceConstraint",
                                     "PrismaticJoint",
                                     "Clamp",
                                     "PrescribedMotion",
                                     "PrescribedVelocity",
                                     "PointOnLine",
                                     "CableClamp",
                                     "SphericalJoint",
                                     "RevoluteJoint3D",
                                     "FixedJoint3D",
                                     "DistanceConstraint3D"};
  for (const char* name : constraints) {
    const BlockSpec* block = root.block(name);
    ASSERT_NE(block, nullptr) << name;
    EXPECT_NE(block->parameter("release_time"), nullptr) << name;
  }
  for (const char* name : {"RigidBody2D", "SpringDamper", "PointForce", "Sensor", "Gravity"}) {
    const BlockSpec* block = root.block(name);
    ASSERT_NE(block, nullptr) << name;
    EXPECT_EQ(block->parameter("release_time"), nullptr) << name;
  }
}

}  // namespace
}  // namespace fsi::scene
