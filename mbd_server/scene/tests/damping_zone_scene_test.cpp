// DampingZone blocks (family_damping.cpp): what they build, the LIGGGHTS commands fsi-server
// appends to script 2 for them, and the zones refused at their keys.
#include <gtest/gtest.h>

#include "test_files.hpp"

namespace fsi::scene {
namespace {

class DampingZones : public testing::FolderPerTest {
 protected:
  const std::string head_ =
      "SolverOptions { end_time = 1; Timeint { step_size = 1e-4 } }\n"
      "Ground { Mesh { points = [[0, 0], [5, 0]] } }\n";
  Scene build(const std::string& zones) {
    return build_scene(write_coupled_scene("p.scene", head_ + zones).string());
  }
  std::string error_of(const std::string& zones) {
    return testing::message_thrown([&] { build(zones); }, "(accepted)");
  }
};

TEST_F(DampingZones, EachZoneBecomesARegionAndADragGrowingTowardItsStrongSide) {
  const Scene scene = build(
      "DampingZone { lower = [3, -0.1]; upper = [5, 1]; rate = 20; grows_toward = \"x+\" }\n"
      "DampingZone { lower = [-1, -0.1]; upper = [0.5, 1]; rate = 5; grows_toward = \"x-\" }\n"
      "DampingZone { lower = [0, 0.8]; upper = [5, 1]; rate = 2; grows_toward = \"uniform\" }\n");
  ASSERT_EQ(scene.damping_zones.size(), 3u);
  EXPECT_EQ(scene.damping_zones[0].axis, 0);
  EXPECT_TRUE(scene.damping_zones[0].toward_upper);
  EXPECT_FALSE(scene.damping_zones[1].toward_upper);
  EXPECT_EQ(scene.damping_zones[2].axis, -1);
  const std::string commands = damping_zone_commands(scene.damping_zones, 2);
  // s = (x - 3) / 2 toward +x; s = (0.5 - x) / 1.5 toward -x; 1 when uniform. 2D: every z.
  for (const char* line : {
           "region fsi_damping_0 block 3 5 -0.1 1 -1e10 1e10 units box\n",
           "variable fsi_damping_0_c atom -20*mass*((x-(3))/2)^2\n",
           "variable fsi_damping_0_fx atom v_fsi_damping_0_c*vx\n",
           "variable fsi_damping_0_fy atom v_fsi_damping_0_c*vy\n",
           "fix fsi_damping_0 all addforce v_fsi_damping_0_fx v_fsi_damping_0_fy 0.0 region "
           "fsi_damping_0\n",
           "variable fsi_damping_1_c atom -5*mass*(((0.5)-x)/1.5)^2\n",
           "variable fsi_damping_2_c atom -2*mass*1.0\n",
           "fix fsi_damping_2 all addforce v_fsi_damping_2_fx v_fsi_damping_2_fy 0.0 region "
           "fsi_damping_2\n",
       }) {
    EXPECT_NE(commands.find(line), std::string::npos) << line << "\nin\n" << commands;
  }
  EXPECT_NE(commands.find("# fsi-server: DampingZone "), std::string::npos) << commands;
  EXPECT_EQ(damping_zone_commands({}, 2), "");
  // What the client gets as script 2: the scene's own (here "# script\n"), then the zones.
  EXPECT_EQ(script2_sent(scene), "# script\n" + commands);
  EXPECT_EQ(script2_sent(build("")), "# script\n");
}

TEST_F(DampingZones, ThreeDimensionalZonesDragEveryComponent) {
  DampingZone zone;
  zone.lower = {0.0, 0.0, -1.0};
  zone.upper = {1.0, 2.0, 0.5};
  zone.rate = 3.0;
  zone.axis = 2;
  zone.toward_upper = false;
  const std::string commands = damping_zone_commands({zone}, 3);
  EXPECT_NE(commands.find("region fsi_damping_0 block 0 1 0 2 -1 0.5 units box\n"),
            std::string::npos)
      << commands;
  EXPECT_NE(commands.find("-3*mass*(((0.5)-z)/1.5)^2\n"), std::string::npos) << commands;
  EXPECT_NE(commands.find("addforce v_fsi_damping_0_fx v_fsi_damping_0_fy v_fsi_damping_0_fz "
                          "region fsi_damping_0\n"),
            std::string::npos)
      << commands;
}

TEST_F(DampingZones, ZonesThatCannotWorkAreRefusedAtTheirKeys) {
  const std::string empty =
      error_of("DampingZone { lower = [3, 1]; upper = [5, 1]; rate = 2; grows_toward = \"x+\" }\n");
  EXPECT_NE(empty.find("p.scene:4:31: the DampingZone's upper y = 1 is not above its lower y = 1 "
                       "(an empty box)"),
            std::string::npos)
      << empty;
  const std::string no_z =
      error_of("DampingZone { lower = [3, 0]; upper = [5, 1]; rate = 2; grows_toward = \"z+\" }\n");
  EXPECT_NE(no_z.find("grows_toward = \"z+\" in a 2D scene (no z axis)"), std::string::npos)
      << no_z;
  // rate dt = 2e4 * 1e-4 = 2 > 1: the drag would turn velocities around.
  const std::string fast = error_of(
      "DampingZone { lower = [3, 0]; upper = [5, 1]; rate = 2e4; grows_toward = \"x+\" }\n");
  EXPECT_NE(fast.find("would reverse the particles' velocities every step"), std::string::npos)
      << fast;
  EXPECT_NE(fast.find("lower the rate to at most 10000"), std::string::npos) << fast;
  const std::string typo = error_of(
      "DampingZone { lower = [3, 0]; upper = [5, 1]; rate = 2; grows_toward = \"right\" }\n");
  EXPECT_NE(typo.find("grows_toward"), std::string::npos) << typo;
  const std::string negative = error_of(
      "DampingZone { lower = [3, 0]; upper = [5, 1]; rate = -2; grows_toward = \"x+\" }\n");
  EXPECT_NE(negative.find("rate"), std::string::npos) << negative;
}

}  // namespace
}  // namespace fsi::scene
