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

}  // namespace
}  // namespace fsi::scene
