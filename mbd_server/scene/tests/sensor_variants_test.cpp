// Sensors are declared variants with one path for planar and spatial scenes: the keys a type
// requires and forbids give the same problems in both dimensions, and the units follow the
// dimension (planar: per unit depth).
#include <gtest/gtest.h>

#include <string>

#include "fsi/common/error.hpp"
#include "fsi/scene/scene.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

// A folder per test and dimension: ctest runs them in parallel.
class SensorVariants : public testing::FolderPerTestOf<::testing::TestWithParam<int>> {
 protected:
  // A structure-only scene of one body and the given sensors, in the test's dimension.
  std::string build(const std::string& sensors, Scene* built = nullptr) {
    const bool spatial = GetParam() == 3;
    return mbd_only_outcome(
        "s.scene",
        "scene_language = 1\ndimension = " + std::to_string(GetParam()) +
            "\nSolverOptions { end_time = 1; Timeint { step_size = 1e-3 } }\n" +
            (spatial ? "PointMass { name = \"bob\"; mass = 1 }\n"
                     : "RigidBody2D { name = \"bob\"; mass = 1; inertia = 1 }\n") +
            sensors,
        built);
  }
};

TEST_P(SensorVariants, RequiredAndForbiddenKeysAreTheSameInBothDimensions) {
  const std::string text = build(
      "Sensor { name = \"energy\"; type = \"kinetic_energy\"; joint = \"j\" }\n"
      "Sensor { name = \"reaction\"; type = \"joint_force\"; component = \"x\" }\n"
      "Sensor { name = \"where\"; type = \"position\"; component = \"x\" }\n");
  EXPECT_NE(text.find("s.scene:5:52: a kinetic_energy sensor takes no joint; remove it"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("s.scene:6:10: sensor 'reaction' needs joint"), std::string::npos) << text;
  EXPECT_NE(text.find("s.scene:7:10: sensor 'where' needs body"), std::string::npos) << text;
}

TEST_P(SensorVariants, UnitsFollowTheDimension) {
  Scene scene;
  ASSERT_EQ(build("Sensor { name = \"height\"; type = \"position\"; body = \"bob\"; component = "
                  "\"y\" }\n"
                  "Sensor { name = \"push\"; type = \"fluid_force\"; body = \"bob\"; component = "
                  "\"x\" }\n"
                  "Sensor { name = \"energy\"; type = \"potential_energy\" }\n",
                  &scene),
            "(accepted)");
  ASSERT_EQ(scene.sensors.size(), 3u);
  const bool spatial = GetParam() == 3;
  EXPECT_EQ(scene.sensors[0].unit, "m");
  EXPECT_EQ(scene.sensors[0].axis, 1);
  EXPECT_EQ(scene.sensors[1].unit, spatial ? "N" : "N/m");
  EXPECT_EQ(scene.sensors[2].unit, spatial ? "J" : "J/m");
}

INSTANTIATE_TEST_SUITE_P(PlanarAndSpatial, SensorVariants, ::testing::Values(2, 3));

// A gate's moment about its hinge (two users asked, 2026-12-06: the torque was about the centre
// of mass only): `about` takes the torque about a body point, tau_P = tau_G + (r_G - r_P) x F.
class ForceAbout : public testing::FolderPerTest {};

TEST_F(ForceAbout, AForceSensorsTorqueAboutABodyPoint) {
  Scene scene;
  const std::string text = mbd_only_outcome("g.scene", R"scene(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-3 } }
RigidBody2D { name = "gate"; mass = 1; inertia = 1; position = [0, -0.5]
              Mesh { points = [[0, -0.5], [0, 0.5]] } }
Sensor { name = "tau_G"; type = "fluid_force"; body = "gate"; component = "torque" }
Sensor { name = "tau_hinge"; type = "fluid_force"; body = "gate"; component = "torque"; about = [0, 0.5] }
)scene",
                                            &scene);
  ASSERT_EQ(text, "(accepted)");
  // 10 N/m along x on the gate's lower end (vertex 0, 1 m below the hinge at the origin).
  std::vector<double> loads(2 * static_cast<std::size_t>(scene.model.marker_count()), 0.0);
  loads[0] = 10.0;
  scene.model.set_point_loads(loads);
  const mbd::State state = scene.model.initial_state();
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[0], state), 5.0, 1e-14);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[1], state), 10.0, 1e-14);
}

TEST_F(ForceAbout, AboutIsATorquesPointOfARigidBody) {
  const std::string text = mbd_only_outcome("g.scene", R"scene(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-3 } }
RigidBody2D { name = "gate"; mass = 1; inertia = 1 }
AncfBeam2D { name = "beam"; start = [0, 0]; end = [1, 0]; elements = 2; thickness = 0.01
             axial_stiffness = 1e6; bending_stiffness = 1; mass_per_length = 1 }
Sensor { name = "a"; type = "position"; body = "gate"; component = "x"; about = [0, 1] }
Sensor { name = "b"; type = "fluid_force"; body = "gate"; component = "x"; about = [0, 1] }
Sensor { name = "c"; type = "fluid_force"; body = "beam"; component = "torque"; about = [0, 1] }
)scene");
  EXPECT_NE(text.find("g.scene:6:73: about is for the torque of fluid_force, joint_force and "
                      "constraint_force sensors, not a position sensor"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("g.scene:7:76: about changes only the torque, and sensor 'b' reads "
                      "component x; write component = \"torque\""),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("g.scene:8:81: about needs a rigid body; sensor 'c' reads the ancf_beam"),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace fsi::scene
