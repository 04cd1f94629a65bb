// Rounded corners in scenes: a Mesh's and a fluid polygon's points may carry a radius as a third
// value (fsi/scene/rounded_corners.hpp); the geometry itself is tested in rounded_corners_test.
#include <gtest/gtest.h>

#include <cmath>

#include "fsi/scene/scene.hpp"
#include "fsi/scene/schema.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

using RoundedCornerScenes = testing::FolderPerTest;

const std::string kHead =
    "SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }\n"
    "Gravity { acceleration = [0, -10] }\n";

// A tank whose floor corners are quarter circles of 0.2 m: six pieces of 15 degrees each, so
// 2 + 2 x 7 points and 15 segments; its water fills the rounded outline, not the sharp one.
TEST_F(RoundedCornerScenes, AMeshAndAFluidPolygonRoundTheirCorners) {
  const std::string tank =
      "Ground { Mesh { points = [[0, 1], [0, 0, 0.2], [1, 0, 0.2], [1, 1]] } }\n";
  const std::string water = R"(FluidRegion {
  shape = "polygon"; spacing = 0.05; density = 1000
  points = [[0, 0, 0.2], [1, 0, 0.2], [1, 0.5], [0, 0.5]]
}
)";
  const Scene scene = build_scene(write_coupled_scene("tank.scene", kHead + tank + water).string());
  EXPECT_EQ(scene.boundary.segments.size() / 2, 15u);
  // Sharp: 20 x 10 lattice points. Each rounded corner leaves out the three cells whose centres
  // lie between the arc and the corner, (0.025, 0.025), (0.075, 0.025) and (0.025, 0.075) at the
  // left (0.247, 0.215 and 0.215 m from the arc's centre): the corner's cut, 0.2^2 (1 - 3 sin 15°)
  // = 0.00894 m^2, is 3.6 cells.
  EXPECT_EQ(scene.fluid.count(), 200u - 2 * 3);
  for (std::size_t i = 0; i < scene.fluid.count(); ++i) {
    const double x = scene.fluid.positions[2 * i], y = scene.fluid.positions[2 * i + 1];
    for (const double centre_x : {0.2, 0.8}) {
      const bool in_corner = y < 0.2 && (centre_x < 0.5 ? x < 0.2 : x > 0.8);
      if (in_corner) {
        EXPECT_LT(std::hypot(x - centre_x, y - 0.2), 0.2)
            << "particle (" << x << ", " << y << ") outside the arc";
      }
    }
  }
}

TEST_F(RoundedCornerScenes, ARadiusThatDoesNotFitIsAProblemAtItsPoints) {
  const auto outcome = [&](const std::string& mesh_points) {
    return mbd_only_outcome(
        "mesh.scene",
        "scene_language = 1\n" + kHead + "Ground { Mesh {\n  points = " + mesh_points + "\n} }\n");
  };
  EXPECT_EQ(outcome("[[0, 1], [0, 0, 0.5], [1, 0, 0.5], [1, 1]]"), "(accepted)");
  const std::string too_large = outcome("[[0, 1], [0, 0, 0.6], [1, 0, 0.6], [1, 1]]");
  EXPECT_NE(too_large.find("mesh.scene:5:3: the edge from point 1 (0, 0) to point 2 (1, 0) is 1 "
                           "m long, but the arcs rounding its corners take 1.2 m of it"),
            std::string::npos)
      << too_large;
  EXPECT_NE(too_large.find("make the radii at most 0.8333 times as large"), std::string::npos)
      << too_large;
  const std::string at_end = outcome("[[0, 1, 0.1], [0, 0], [1, 0]]");
  EXPECT_NE(at_end.find("point 0 (0, 1) has a corner radius (0.1 m), but it ends the open outline"),
            std::string::npos)
      << at_end;
  const std::string four = outcome("[[0, 1], [0, 0, 0.1, 2], [1, 0]]");
  EXPECT_NE(four.find("points' row 2 has 4 values, it needs 2 or 3"), std::string::npos) << four;
  // The reference page and --help-params say so.
  const std::string page = render_markdown(scene_schema());
  EXPECT_NE(page.find("2 or 3 values per row"), std::string::npos);
}

TEST_F(RoundedCornerScenes, AFluidPolygonsRadiusThatDoesNotFitNamesTheRing) {
  const std::string water = R"(Ground { Mesh { points = [[0, 0], [1, 0]] } }
FluidRegion {
  shape = "polygon"; spacing = 0.05; density = 1000
  points = [[0, 0], [1, 0], [1, 0.5], [0, 0.5]]
  Hole { points = [[0.4, 0.1], [0.6, 0.1, 0.3], [0.6, 0.3], [0.4, 0.3]] }
}
)";
  const std::string message = testing::message_thrown(
      [&] { build_scene(write_coupled_scene("hole.scene", kHead + water).string()); },
      "(accepted)");
  EXPECT_NE(message.find("hole 0, the edge from point 0 (0.4, 0.1) to point 1 (0.6, 0.1)"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace fsi::scene
