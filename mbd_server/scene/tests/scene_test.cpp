#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>

#include "fsi/common/error.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/scene/fluid_region.hpp"
#include "fsi/scene/scene.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

using testing::build_error;
using testing::unit_box_stl;

namespace fs = std::filesystem;

TEST(Scene, BuildsTheCoarseStaticTank) {
  const Scene scene = build_scene(FSI_EXAMPLES_DIR "/static_tank/static_tank_coarse.scene");
  EXPECT_EQ(scene.model.body_count(), 2);
  // Two closed rectangles (4 vertices each, dynamic) and two walls (2 vertices each, static).
  EXPECT_EQ(scene.boundary.dynamic_vertex_count, 8u);
  EXPECT_EQ(scene.boundary.vertex_count, 12u);
  EXPECT_EQ(scene.boundary.segments.size(), 2u * (4 + 4 + 1 + 1));
  EXPECT_EQ(scene.model.constraint_count(), 6);
  EXPECT_EQ(scene.sensors.size(), 6u);
  const double h = 0.0016;
  const double d = h / 1.9;
  EXPECT_DOUBLE_EQ(scene.fluid.spacing, d);
  EXPECT_DOUBLE_EQ(scene.fluid.mass, 1000.0 * d * d);
  EXPECT_GT(scene.fluid.count(), 1800u);
  EXPECT_LT(scene.fluid.count(), 2200u);
  EXPECT_EQ(scene.solver.step_size, 1e-5);
  EXPECT_FALSE(scene.liggghts.script1_text.empty());
  bool found = false;
  for (const auto& [name, value] : scene.liggghts.variables) {
    if (name == "smoothinglength") {
      EXPECT_EQ(value, "0.0016");
      found = true;
    }
  }
  EXPECT_TRUE(found);
  // All particles inside the tank, at least one smoothing length from the walls.
  for (std::size_t i = 0; i < scene.fluid.count(); ++i) {
    EXPECT_GE(scene.fluid.positions[2 * i], h);
    EXPECT_LE(scene.fluid.positions[2 * i], 0.05 - h);
  }
}

TEST(Scene, AFluidBoxThatIsNotWholeCellsSaysHowMuchOfItTheWaterFills) {
  // The coarse tank's box is 0.0468 x 0.0308 m at d = 0.0016/1.9: 55.6 x 36.6 cells, filled with
  // 55 x 36 from the lower corner (a user's 0.465 m deep tank at d = 0.0175 m got 0.455 m).
  const std::string path = FSI_EXAMPLES_DIR "/static_tank/static_tank_coarse.scene";
  const std::string fill = fluid_box_fill(build_scene(path));
  EXPECT_NE(fill.find("the fluid box (x, y) 0.0468 x 0.0308 m holds 55 x 36 cells of 0.0008421 m: "
                      "the water fills 0.04632 x 0.03032 m, x 1.035 %, y 1.572 % short"),
            std::string::npos)
      << fill;
  // A fill height of whole spacings in y leaves only x short; whole in both: nothing to say.
  const std::string d = "(0.0016/1.9)";
  const std::string whole_y =
      fluid_box_fill(build_scene(path, {{"Geometry.fill_height", "36*" + d}}));
  EXPECT_NE(whole_y.find("x 1.035 % short"), std::string::npos) << whole_y;
  EXPECT_EQ(whole_y.find("y "), std::string::npos) << whole_y;
  EXPECT_EQ(fluid_box_fill(build_scene(path, {{"Geometry.fill_height", "36*" + d},
                                              {"Geometry.width", "55*" + d + " + 0.0032"}})),
            "");
}

TEST(Scene, OverridesReachTheBuiltScene) {
  const Scene scene =
      build_scene(FSI_EXAMPLES_DIR "/static_tank/static_tank_coarse.scene",
                  {{"Resolution.end_time", "0.01"}, {"Geometry.piston_mass", "0.2"}});
  EXPECT_EQ(scene.solver.end_time, 0.01);
  EXPECT_EQ(scene.model.body(scene.model.find_body("piston")).mass, 0.2);
}

TEST(Scene, TheWaterColumnKnowsItsHeightAndTheSettlingDragIsTheScenes) {
  const Scene automatic = build_scene(FSI_EXAMPLES_DIR "/water_column/water_column.scene");
  // 61 lattice rows of d = h/1.9 in the 0.13 m high region: H is their extent plus one d.
  EXPECT_NEAR(automatic.fluid.column_height, 61 * 0.004 / 1.9, 1e-12);
  EXPECT_FALSE(automatic.liggghts.settling_drag);  // absent: fsi-client derives it
  const Scene off = build_scene(FSI_EXAMPLES_DIR "/water_column/water_column.scene",
                                {{"LIGGGHTS.settling_drag", "0"}});
  ASSERT_TRUE(off.liggghts.settling_drag);
  EXPECT_EQ(*off.liggghts.settling_drag, 0.0);
  try {
    build_scene(FSI_EXAMPLES_DIR "/water_column/water_column.scene",
                {{"LIGGGHTS.settling_drag", "-1"}});
    FAIL() << "a negative drag accepted";
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find("settling_drag"), std::string::npos) << error.what();
  }
}

// The settling's length in seconds: the same time at another step.
class SceneFiles : public testing::FolderPerTest {};

TEST_F(SceneFiles, TheEquilibrationInSecondsBecomesWholeSteps) {
  const std::string path =
      write_coupled_scene("e.scene",
                          "SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }\n"
                          "Ground { Mesh { points = [[0, 0], [1, 0]] } }\n")
          .string();
  const auto steps = [&](std::vector<Override> overrides) {
    overrides.push_back({"LIGGGHTS.equilibration_time", "0.25"});
    return build_scene(path, overrides).liggghts.equilibration_steps;
  };
  EXPECT_EQ(steps({}), 25000u);
  // 0.25 s / 3e-5 s = 8333.3: the next whole step, so the settling lasts at least the time.
  EXPECT_EQ(steps({{"SolverOptions.Timeint.step_size", "3e-5"}}), 8334u);
  const std::string both = testing::message_thrown([&] {
    steps({{"LIGGGHTS.equilibration_steps", "100"}});
  });
  EXPECT_NE(both.find("LIGGGHTS gives both equilibration_time and equilibration_steps"),
            std::string::npos)
      << both;
}

TEST(Scene, AHydrostaticRegionGivesEveryParticleItsDensity) {
  const Scene plain = build_scene(FSI_EXAMPLES_DIR "/water_column/water_column.scene");
  EXPECT_TRUE(plain.fluid.densities.empty());
  const Scene hydrostatic =
      build_scene(FSI_EXAMPLES_DIR "/water_column/water_column.scene",
                  {{"FluidRegion.hydrostatic", "1"}, {"FluidRegion.speed_of_sound", "20"}});
  ASSERT_EQ(hydrostatic.fluid.densities.size(), hydrostatic.fluid.count());
  double lowest_density = 1e9, highest_density = 0.0;
  for (const double density : hydrostatic.fluid.densities) {
    lowest_density = std::min(lowest_density, density);
    highest_density = std::max(highest_density, density);
  }
  // rho0 g H / (rho0 c^2) = 9.81 * 0.128 / 400 = 0.3 %: the bottom is that much denser.
  EXPECT_GT(lowest_density, 1000.0);
  EXPECT_NEAR(highest_density / 1000.0 - 1.0, 9.81 * 0.128 / 400.0, 2e-4);
  try {
    build_scene(FSI_EXAMPLES_DIR "/water_column/water_column.scene",
                {{"FluidRegion.hydrostatic", "1"}});
    FAIL() << "a hydrostatic region without speed of sound accepted";
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find("needs the speed of sound"), std::string::npos)
        << error.what();
  }
}

TEST(Scene, ReportsAllProblemsWithLocations) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_build_test";
  fs::create_directories(folder);
  std::ofstream(folder / "bad.scene") << R"(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 0 } }
RigidBody2D { name = "a"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
CoordinateConstraint { body = "b"; coordinate = "x" }
Sensor { name = "s"; type = "fluid_force"; body = "a"; component = "angle" }
LIGGGHTS { script1 = "missing.in"; script2 = "missing2.in" }
Coupling { refinement_resolution = 0.001 }
)";
  try {
    build_scene((folder / "bad.scene").string());
    FAIL() << "bad scene accepted";
  } catch (const fsi::Error& error) {
    const std::string text = error.what();
    // Schema problems come first (and alone): step_size out of range.
    EXPECT_NE(text.find("bad.scene:2:41"), std::string::npos) << text;
    EXPECT_NE(text.find("'SolverOptions.Timeint.step_size' = 0 s is out of range"),
              std::string::npos)
        << text;
  }
  std::ofstream(folder / "bad2.scene") << R"(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
RigidBody2D { name = "a"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
CoordinateConstraint { body = "b"; coordinate = "x" }
Sensor { name = "s"; type = "fluid_force"; body = "a"; component = "angle" }
LIGGGHTS { script1 = "missing.in"; script2 = "missing2.in" }
Coupling { refinement_resolution = 0.001 }
)";
  try {
    build_scene((folder / "bad2.scene").string());
    FAIL() << "bad scene accepted";
  } catch (const fsi::Error& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("4 problem(s)"), std::string::npos) << text;
    EXPECT_NE(text.find("bad2.scene:4:24: no body named 'b'"), std::string::npos) << text;
    EXPECT_NE(text.find("known bodies: a"), std::string::npos) << text;
    EXPECT_NE(text.find("a force sensor has components x, y or torque"), std::string::npos) << text;
    EXPECT_NE(text.find("missing.in' cannot be read"), std::string::npos) << text;
  }
  fs::remove_all(folder);
}

// Multi-rate coupling: rows, snapshots and the end must fall on structure steps.
TEST(Scene, SubstepsMustDivideTheRunTheRowsAndTheSnapshots) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_substeps_test";
  fs::create_directories(folder);
  std::ofstream(folder / "a.in") << "# script 1\n";
  std::ofstream(folder / "b.in") << "# script 2\n";
  const std::string rest = R"(
LIGGGHTS { script1 = "a.in"; script2 = "b.in" }
Coupling { refinement_resolution = 0.001 }
)";
  std::ofstream(folder / "substeps.scene") << R"(scene_language = 1
SolverOptions { end_time = 1e-4; Timeint { step_size = 1e-5; substeps = 4 } }
Output { sensor_every_steps = 2; snapshot_every_steps = 6 }
RigidBody2D { name = "a"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
)" << rest;
  try {
    build_scene((folder / "substeps.scene").string());
    FAIL() << "substeps that divide nothing accepted";
  } catch (const fsi::Error& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("3 problem(s)"), std::string::npos) << text;
    EXPECT_NE(text.find("substeps.scene:2:"), std::string::npos) << text;
    EXPECT_NE(text.find("Output.sensor_every_steps = 2 is not a multiple of the substeps "
                        "(SolverOptions.Timeint.substeps = 4)"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("Output.snapshot_every_steps = 6 is not a multiple"), std::string::npos)
        << text;
    EXPECT_NE(text.find("the run's 10 steps (SolverOptions.end_time / step_size) are not a "
                        "multiple of the substeps"),
              std::string::npos)
        << text;
  }
  std::ofstream(folder / "good.scene") << R"(scene_language = 1
SolverOptions { end_time = 8e-5; Timeint { step_size = 1e-5; substeps = 4 } }
Output { sensor_every_steps = 4; snapshot_every_steps = 8 }
RigidBody2D { name = "a"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
)" << rest;
  const Scene scene = build_scene((folder / "good.scene").string());
  EXPECT_EQ(scene.solver.substeps, 4);
  EXPECT_EQ(scene.solver.integrator_description(true),
            "Radau IIA, 3 stages, 4 fluid steps per structure step");
  fs::remove_all(folder);
}

// Issue 6 acceptance: one file with six different mistakes; every one is reported in the same
// run, at its line and column, with a fix, and nothing else is reported.
TEST(Scene, ReportsSixDifferentMistakesAtOnceWithLineAndColumn) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_six_mistakes";
  fs::create_directories(folder);
  std::ofstream(folder / "ok.in1") << "# script 1\n";
  std::ofstream(folder / "six.scene") << R"(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
Output { sensor_every_step = 2 }
Geometry { width = 0.05; a = b + 1; b = 2*a }
Gravity { acceleration = -9.81 }
RigidBody2D { name = "box"; mass = Geometry.widht*2; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
RigidBody2D { name = "lid"; mass = 1; inertia = 1; Mesh { points = [[0, 1], [1, 1]] } }
CoordinateConstraint { body = "box"; coordinate = "x" }
Sensor { name = "lid_y"; type = "position"; body = "lid"; component = "y" }
FluidRegion { shape = "box"; lower = [0, 0]; upper = [0.05, 0.02]; spacing = 0.001
              density = 1000; random_displacement = 30 }
LIGGGHTS { script1 = "ok.in1"; script2 = "missing.in2" }
Coupling { refinement_resolution = 0.002 }
)";
  std::string text;
  try {
    build_scene((folder / "six.scene").string());
  } catch (const fsi::Error& error) {
    text = error.what();
  }
  fs::remove_all(folder);
  ASSERT_FALSE(text.empty()) << "the scene with six mistakes was accepted";
  const std::string file = (folder / "six.scene").string();
  // Each: where, what, how to fix.
  const std::vector<std::vector<std::string>> expected = {
      // 1. unknown key, with the nearest known one
      {file + ":3:10: unknown parameter 'Output.sensor_every_step'",
       "did you mean 'sensor_every_steps'?"},
      // 2. a cycle: a uses b, which is defined later and uses a
      {file + ":4:30: in 'Geometry.a': 'b' is defined later", "a cycle Geometry.a -> Geometry.b",
       "break the cycle"},
      // 3. wrong type: a number where a vector belongs
      {file + ":5:11: 'Gravity.acceleration' must be a vector, not a number",
       "e.g. acceleration = [x, y]"},
      // 4. an undefined reference (a typo), with the nearest defined name
      {file + ":6:36: in 'RigidBody2D[0].mass': block 'Geometry' has no parameter 'widht'",
       "did you mean 'Geometry.width'?"},
      // 5. a unit mistake caught by the range: 30 (%) where a fraction of d belongs
      {file + ":11:31: 'FluidRegion.random_displacement' = 30 is out of range", "choose a value"},
      // 6. a LIGGGHTS script that does not exist
      {file + ":12:32: LIGGGHTS script '", "missing.in2' cannot be read",
       "relative to the scene file"},
  };
  for (const auto& pieces : expected) {
    const std::size_t at = text.find(pieces.front());
    EXPECT_NE(at, std::string::npos) << pieces.front() << "\n" << text;
    if (at == std::string::npos) continue;
    const std::string line = text.substr(at, text.find('\n', at) - at);
    for (std::size_t i = 1; i < pieces.size(); ++i)
      EXPECT_NE(line.find(pieces[i]), std::string::npos) << pieces[i] << "\n" << line;
  }
  // Nothing else: no consequence of a mistake reported as a mistake of its own (the box, whose
  // mass is in error, is skipped, and so is its constraint).
  EXPECT_NE(text.find("6 problem(s) in the scene"), std::string::npos) << text;
  // In the order of the file.
  std::size_t previous = 0;
  for (const char* line : {":3:10:", ":4:30:", ":5:11:", ":6:36:", ":11:31:", ":12:32:"}) {
    const std::size_t at = text.find(line);
    EXPECT_GT(at, previous) << line;
    previous = at;
  }
}

TEST(Scene, ASceneMustStateItsLanguageVersion) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_version_test";
  fs::create_directories(folder);
  std::ofstream(folder / "s.in") << "# script\n";
  const std::string body = R"(SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
Ground { Mesh { points = [[0, 0], [1, 0]] } }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.002 }
)";
  auto error_of = [&](const std::string& text) {
    std::ofstream(folder / "v.scene") << text;
    return testing::message_thrown([&] { build_scene((folder / "v.scene").string()); });
  };
  EXPECT_EQ(error_of("% a comment first is fine\nscene_language = 1\n" + body), "");
  const std::string missing = error_of(body);
  EXPECT_NE(missing.find("v.scene:1:1: the scene does not state the scene language version"),
            std::string::npos)
      << missing;
  EXPECT_NE(missing.find("add the line 'scene_language = 1' at the top of the file"),
            std::string::npos)
      << missing;
  const std::string old = error_of("scene_language = 1\nSceneFormat { version = 1 }\n" + body);
  EXPECT_NE(old.find("v.scene:2:1: SceneFormat { version = N } is no longer read"),
            std::string::npos)
      << old;
  const std::string newer = error_of("scene_language = 2\n" + body);
  EXPECT_NE(newer.find("written for scene language version 2"), std::string::npos) << newer;
  fs::remove_all(folder);
}

TEST(Scene, APolygonFluidRegionWithAHole) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_polygon_test";
  fs::create_directories(folder);
  std::ofstream(folder / "s.in") << "# script\n";
  const std::string head = R"(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
Ground { Mesh { points = [[0, 0], [1, 0]] } }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.002 }
)";
  auto build = [&](const std::string& region) {
    std::ofstream(folder / "p.scene") << head << region;
    return build_scene((folder / "p.scene").string());
  };
  // An L (the unit square without [0.4, 1]^2) with the hole [0.1, 0.3]^2: 64 - 4 = 60 points.
  const Scene scene = build(R"(FluidRegion {
  shape = "polygon"; spacing = 0.1; density = 1000; velocity = [0.5, 0]
  points = [[0, 0], [1, 0], [1, 0.4], [0.4, 0.4], [0.4, 1], [0, 1]]
  Hole { points = [[0.1, 0.1], [0.3, 0.1], [0.3, 0.3], [0.1, 0.3]] }
}
)");
  EXPECT_EQ(scene.fluid.count(), 60u);
  EXPECT_DOUBLE_EQ(scene.fluid.mass, 1000 * 0.1 * 0.1);
  ASSERT_EQ(scene.fluid.velocities.size(), 120u);
  EXPECT_EQ(scene.fluid.velocities[0], 0.5);
  std::string message;
  try {
    build(
        "FluidRegion { shape = \"polygon\"; spacing = 0.1; density = 1000\n"
        "  lower = [0, 0]\n  points = [[0, 0], [1, 1], [1, 0], [0, 0.5]] }\n");
  } catch (const fsi::Error& error) {
    message = error.what();
  }
  EXPECT_NE(message.find("p.scene:7:3: 'lower' belongs to the other shape than 'polygon'"),
            std::string::npos)
      << message;
  try {
    build(
        "FluidRegion { shape = \"polygon\"; spacing = 0.1; density = 1000\n"
        "  points = [[0, 0], [1, 1], [1, 0], [0, 0.5]] }\n");
  } catch (const fsi::Error& error) {
    message = error.what();
  }
  EXPECT_NE(message.find("p.scene:7:3: the polygon: edges 0-1 and 2-3 cross"), std::string::npos)
      << message;
  fs::remove_all(folder);
}

TEST_F(SceneFiles, SeveralFluidRegionsEachWithItsOwnFreeSurface) {
  const std::string head =
      "SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }\n"
      "Gravity { acceleration = [0, -10] }\n"
      "Ground { Mesh { points = [[0, 0], [2, 0]] } }\n";
  auto build = [&](const std::string& regions) {
    return build_scene(write_coupled_scene("p.scene", head + regions).string());
  };
  auto error_of = [&](const std::string& regions) {
    return testing::message_thrown([&] { build(regions); }, "(accepted)");
  };
  // Upstream of a gate 1 m of water, downstream 0.3 m; they touch at x = 1 (no overlap).
  const std::string upstream =
      "FluidRegion { shape = \"box\"; lower = [0, 0]; upper = [1, 1]; spacing = 0.1\n"
      "  density = 1000; hydrostatic = 1; speed_of_sound = 20 }\n";
  const std::string downstream =
      "FluidRegion { shape = \"polygon\"; points = [[1, 0], [2, 0], [2, 0.3], [1, 0.3]]\n"
      "  spacing = 0.1; density = 1000; hydrostatic = 1; speed_of_sound = 20\n"
      "  velocity = [0.5, 0] }\n";
  const Scene scene = build(upstream + downstream);
  ASSERT_EQ(scene.fluid.count(), 100u + 30u);
  ASSERT_EQ(scene.fluid.densities.size(), scene.fluid.count());
  // The tallest column's height; each region's top row at its own surface (p = rho0 g d/2).
  EXPECT_NEAR(scene.fluid.column_height, 1.0, 1e-12);
  const TaitEquation tait{1000.0, 20.0, 7.0};
  for (std::size_t i = 0; i < scene.fluid.count(); ++i) {
    const double x = scene.fluid.positions[2 * i], y = scene.fluid.positions[2 * i + 1];
    const double top = x < 1.0 ? 1.0 : 0.3;
    EXPECT_NEAR(scene.fluid.densities[i], tait.density_at(1000.0 * 10.0 * (top - y)), 1e-9)
        << x << ", " << y;
    EXPECT_EQ(scene.fluid.velocities[2 * i], x < 1.0 ? 0.0 : 0.5);
  }
  // A region without hydrostatic beside one with: its particles at the density.
  const Scene mixed = build(upstream +
                            "FluidRegion { shape = \"box\"; lower = [1, 0]\n"
                            "  upper = [2, 0.3]; spacing = 0.1; density = 1000 }\n");
  ASSERT_EQ(mixed.fluid.densities.size(), 130u);
  EXPECT_EQ(mixed.fluid.densities.back(), 1000.0);
  EXPECT_GT(mixed.fluid.densities.front(), 1000.0);

  // One particle mass: another spacing is refused at its key.
  const std::string spacing =
      error_of(upstream +
               "FluidRegion { shape = \"box\"; lower = [1, 0]; upper = [2, 0.3]\n"
               "  spacing = 0.05; density = 1000 }\n");
  EXPECT_NE(spacing.find("p.scene:8:3: FluidRegion[1].spacing = 0.05 differs from 0.1 of the "
                         "first FluidRegion ("),
            std::string::npos)
      << spacing;
  EXPECT_NE(spacing.find("p.scene:5:1): the fluid has one particle mass"), std::string::npos)
      << spacing;
  // Overlapping regions would put two particles in one place.
  const std::string overlap =
      error_of(upstream +
               "FluidRegion { shape = \"box\"; lower = [0.5, 0]; upper = [2, 0.3]\n"
               "  spacing = 0.1; density = 1000 }\n");
  EXPECT_NE(overlap.find("p.scene:7:1: FluidRegion[1] overlaps an earlier FluidRegion: 15 of its "
                         "lattice points lie within d/2 of theirs, the first at (0.55, 0.05)"),
            std::string::npos)
      << overlap;
}

TEST(Scene, JointsSpringsAndTheLobattoTableau) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_joints_test";
  fs::create_directories(folder);
  std::ofstream(folder / "s.in") << "# script\n";
  std::ofstream(folder / "j.scene") << R"(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-3; tableau = "LobattoIIIA"; stages = 2 }
                Newton { max_contraction = 0.25; absolute_tolerance = 1e-12 } }
RigidBody2D { name = "arm"; mass = 1; inertia = 0.1; position = [0.5, 0]; Mesh { points = [[0, 0], [1, 0]] } }
RigidBody2D { name = "bob"; mass = 1; inertia = 0.1; position = [2, 0] }
RevoluteJoint { body_a = "arm"; point_a = [-0.5, 0]; point_b = [0, 0] }
DistanceConstraint { body_a = "arm"; point_a = [0.5, 0]; body_b = "bob"; point_b = [-0.5, 0] }
SpringDamper { body_a = "bob"; stiffness = 100; damping = 1; point_b = [2, 1] }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.002 }
)";
  const Scene scene = build_scene((folder / "j.scene").string());
  EXPECT_EQ(scene.model.constraint_count(), 3);  // revolute: 2 rows, rod: 1
  EXPECT_EQ(scene.solver.family, mbd::TableauFamily::LobattoIIIA);
  EXPECT_EQ(scene.solver.stages, 2);
  EXPECT_EQ(scene.solver.newton.max_contraction, 0.25);
  EXPECT_EQ(scene.solver.newton.absolute_tolerance, 1e-12);
  std::ofstream(folder / "j.scene") << R"(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-3; tableau = "LobattoIIIA"; stages = 1 } }
RigidBody2D { name = "arm"; mass = 1; inertia = 0.1; Mesh { points = [[0, 0], [1, 0]] } }
RevoluteJoint { body_a = "arn" }
SpringDamper { body_a = "arm"; stiffness = -1 }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.002 }
)";
  std::string message;
  try {
    build_scene((folder / "j.scene").string());
  } catch (const fsi::Error& error) {
    message = error.what();
  }
  EXPECT_NE(message.find("Lobatto IIIA has 2 or 3 stages"), std::string::npos) << message;
  EXPECT_NE(message.find("j.scene:4:17: no body named 'arn'"), std::string::npos)
      << message;  // body_a = "arn"
  EXPECT_NE(message.find("'SpringDamper.stiffness' = -1 N/m is out of range"), std::string::npos)
      << message;
  fs::remove_all(folder);
}

TEST(Scene, AnAncfBeamWithClampJointAndAMeshOnBothFaces) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_beam_test";
  fs::create_directories(folder);
  std::ofstream(folder / "s.in") << "# script\n";
  std::ofstream(folder / "b.scene") << R"(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
AncfBeam2D { name = "valve"; start = [0, 0]; end = [0, 0.1]; elements = 4; thickness = 0.004
             axial_stiffness = 2e6; bending_stiffness = 2.7; mass_per_length = 8;
             face_points_per_element = 2; bending_damping = 1e-3 }
RigidBody2D { name = "tip"; mass = 0.01; inertia = 1e-6; position = [0, 0.1] }
BeamClamp { beam = "valve" }
RevoluteJoint { body_a = "valve"; point_a = [0.1, 0]; body_b = "tip" }
Sensor { name = "fx"; type = "fluid_force"; body = "valve"; component = "x" }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.002 }
)";
  const Scene scene = build_scene((folder / "b.scene").string());
  const mbd::Model& model = scene.model;
  ASSERT_EQ(model.body_count(), 2);
  const mbd::BodyId valve = model.find_body("valve");
  EXPECT_TRUE(model.is_beam(valve));
  EXPECT_EQ(model.beam(valve).bending_damping, 1e-3);
  EXPECT_EQ(model.beam(valve).axial_damping, 0.0);
  EXPECT_EQ(model.coordinate_count(), 4 * 5 + 3);
  EXPECT_EQ(model.constraint_count(), 3 + 2);  // clamp (direction), revolute
  // Closed outline: 9 points on each face, all dynamic, one segment per vertex.
  EXPECT_EQ(scene.boundary.dynamic_vertex_count, 18u);
  EXPECT_EQ(scene.boundary.vertex_count, 18u);
  EXPECT_EQ(scene.boundary.segments.size(), 2u * 18);
  const mbd::State state = model.initial_state();
  // The beam runs along +y: its left normal is -x. Upper face first (s = 0 .. L), then back.
  EXPECT_NEAR(marker_position(model, state, 0).x(), -0.002, 1e-15);
  EXPECT_NEAR(marker_position(model, state, 8).y(), 0.1, 1e-15);
  EXPECT_NEAR(marker_position(model, state, 9).x(), 0.002, 1e-15);
  EXPECT_NEAR(marker_position(model, state, 17).y(), 0.0, 1e-15);
  ASSERT_EQ(scene.sensors.size(), 1u);
  EXPECT_EQ(scene.sensors[0].body, valve);

  std::ofstream(folder / "b.scene") << R"(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
AncfBeam2D { name = "valve"; start = [0, 0]; end = [0, 0.1]; elements = 0; thickness = 0.004
             axial_stiffness = 2e6; bending_stiffness = 2.7; mass_per_length = 8 }
AncfBeam2D { name = "reed"; start = [1, 0]; end = [1, 0.1]; elements = 2; thickness = 0.004
             axial_stiffness = 2e6; bending_stiffness = 2.7; mass_per_length = 8 }
RigidBody2D { name = "block"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
BeamClamp { beam = "block" }
BeamClamp { beam = "reed"; node = 3 }
Sensor { name = "y"; type = "position"; body = "reed"; component = "y" }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.002 }
)";
  std::string message;
  try {
    build_scene((folder / "b.scene").string());
  } catch (const fsi::Error& error) {
    message = error.what();
  }
  EXPECT_NE(message.find("b.scene:3:62: 'AncfBeam2D[0].elements' = 0 is out of range"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("b.scene:8:1: a beam clamp needs an ANCF beam"), std::string::npos)
      << message;
  EXPECT_NE(message.find("b.scene:9:1: a beam clamp refers to node 3"), std::string::npos)
      << message;
  EXPECT_NE(message.find("b.scene:10:22: a position sensor reads rigid-body coordinates"),
            std::string::npos)
      << message;
  fs::remove_all(folder);
}

TEST(Scene, SchemaDocumentsEveryBlock) {
  const std::string markdown = render_markdown(scene_schema());
  for (const char* block : {"SolverOptions", "RigidBody2D", "RigidBody2D.Mesh", "AncfBeam2D",
                            "BeamClamp", "CoordinateConstraint", "VelocityConstraint", "Sensor",
                            "FluidRegion", "LIGGGHTS", "Coupling"}) {
    EXPECT_NE(markdown.find(std::string("## `") + block + "`"), std::string::npos) << block;
  }
}

// The closed unit box [0, 1]^3 as ASCII STL, 12 triangles, outward normals.
TEST(Scene, ThreeDimensionalSceneWithAnStlGroundAndABoxOfFluid) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_3d_test";
  fs::create_directories(folder);
  std::ofstream(folder / "s.in") << "# script\n";
  std::ofstream(folder / "box.stl") << unit_box_stl();
  std::ofstream(folder / "b.scene") << R"(scene_language = 1
dimension = 3
SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
Gravity { acceleration = [0, 0, -9.81] }
Ground { Mesh { stl = "box.stl"; scale = 0.5; offset = [1, 2, 3] } }
Sensor { name = "fz"; type = "total_fluid_force"; component = "z" }
FluidRegion { shape = "box"; lower = [1, 2, 3]; upper = [1.5, 2.5, 3.2]; spacing = 0.1
              density = 1000; velocity = [0, 0, -1] }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.2 }
)";
  const Scene scene = build_scene((folder / "b.scene").string());
  EXPECT_EQ(scene.dimension, 3);
  EXPECT_EQ(scene.gravity[2], -9.81);
  EXPECT_EQ(scene.boundary.dimension, 3);
  EXPECT_EQ(scene.boundary.vertex_count, 8u);
  EXPECT_EQ(scene.boundary.dynamic_vertex_count, 0u);
  EXPECT_EQ(scene.boundary.element_count(), 12u);
  EXPECT_TRUE(scene.boundary.segments.empty());
  ASSERT_EQ(scene.boundary.static_positions.size(), 24u);
  double high[3] = {0, 0, 0};
  for (std::size_t i = 0; i < 24; ++i)
    high[i % 3] = std::max(high[i % 3], scene.boundary.static_positions[i]);
  EXPECT_DOUBLE_EQ(high[0], 1.5);  // 0.5 * 1 + 1
  EXPECT_DOUBLE_EQ(high[1], 2.5);
  EXPECT_DOUBLE_EQ(high[2], 3.5);
  EXPECT_EQ(scene.model.body_count(), 0);
  EXPECT_EQ(scene.fluid.dimension, 3);
  EXPECT_EQ(scene.fluid.count(), 5u * 5u * 2u);
  EXPECT_DOUBLE_EQ(scene.fluid.mass, 1000 * 0.1 * 0.1 * 0.1);
  ASSERT_EQ(scene.fluid.velocities.size(), 150u);
  EXPECT_EQ(scene.fluid.velocities[2], -1.0);
  ASSERT_EQ(scene.sensors.size(), 1u);
  EXPECT_EQ(scene.sensors[0].axis, 2);
  EXPECT_EQ(scene.sensors[0].unit, "N");
  fs::remove_all(folder);
}

TEST(Scene, ThreeDimensionalFluidFromAClosedStl) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_3d_stl_test";
  fs::create_directories(folder);
  std::ofstream(folder / "s.in") << "# script\n";
  std::ofstream(folder / "box.stl") << unit_box_stl();
  std::ofstream(folder / "f.scene") << R"(scene_language = 1
dimension = 3
SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
Ground { Mesh { stl = "box.stl"; scale = 2; offset = [-0.5, -0.5, -0.5] } }
FluidRegion { shape = "stl"; stl = "box.stl"; spacing = 0.25; density = 1000 }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.2 }
)";
  const Scene scene = build_scene((folder / "f.scene").string());
  EXPECT_EQ(scene.fluid.count(), 64u);
  EXPECT_EQ(scene.fluid.positions.size(), 192u);
  EXPECT_DOUBLE_EQ(scene.fluid.mass, 1000 * 0.25 * 0.25 * 0.25);
  EXPECT_EQ(scene.fluid.velocities.size(), 192u);
  fs::remove_all(folder);
}

TEST(Scene, AStructureOnlySceneInACoupledRunIsToldOfMbdOnlyOnceABlock) {
  // A user's cantilever without LIGGGHTS and Coupling, checked without --mbd-only: one problem
  // per missing block, with the way out, not also every key the absent blocks would hold.
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_structure_only_test";
  fs::create_directories(folder);
  std::ofstream(folder / "beam.scene") << R"(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 0.01 } }
AncfBeam2D { name = "b"; start = [0, 0]; end = [1, 0]; elements = 2; thickness = 0.01
             axial_stiffness = 1e5; bending_stiffness = 1; mass_per_length = 1 }
BeamClamp { beam = "b"; node = 0 }
)";
  const std::string text = build_error(folder / "beam.scene");
  EXPECT_NE(text.find("2 problem(s)"), std::string::npos) << text;
  for (const char* block : {"LIGGGHTS", "Coupling"}) {
    EXPECT_NE(text.find("required block '" + std::string(block) + "' is missing (The"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("run the structure alone with fsi-server --mbd-only (fsi-run always "
                        "couples), which needs no " +
                        std::string(block) + " block"),
              std::string::npos)
        << text;
  }
  EXPECT_EQ(text.find("is missing in block"), std::string::npos) << text;
  EXPECT_NO_THROW(build_scene((folder / "beam.scene").string(), {}, SceneMode::MbdOnly));
  fs::remove_all(folder);
}

// Every 3D mistake at its place, all in one run: planar bodies and joints, vectors of the wrong
// length, a missing STL, an open STL for the fluid, a 2D-only shape and component.
TEST(Scene, ThreeDimensionalMistakesAreReportedTogether) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_3d_bad_test";
  fs::create_directories(folder);
  std::ofstream(folder / "s.in") << "# script\n";
  std::ofstream(folder / "open.stl") << unit_box_stl(true);
  std::ofstream(folder / "bad.scene") << R"(scene_language = 1
dimension = 3
SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
Gravity { acceleration = [0, -9.81] }
RigidBody2D { name = "a"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
RevoluteJoint { body_a = "a" }
Ground { Mesh { stl = "nowhere.stl" } }
Ground { Mesh { points = [[0, 0], [1, 0]] } }
Sensor { name = "f"; type = "total_fluid_force"; component = "torque" }
FluidRegion { shape = "stl"; stl = "open.stl"; spacing = 0.1; density = 1000; velocity = [1, 0] }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.2 }
AncfBeam2D { name = "b"; start = [0, 0]; end = [1, 0]; elements = 2; thickness = 0.01; axial_stiffness = 1; bending_stiffness = 1; mass_per_length = 1 }
PrismaticJoint { body_a = "a"; axis = [1, 0] }
)";
  const std::string text = build_error(folder / "bad.scene");
  EXPECT_NE(text.find("bad.scene:13:1: AncfBeam2D is a planar (2D) element"), std::string::npos)
      << text;
  EXPECT_NE(text.find("bad.scene:14:1: PrismaticJoint is a planar (2D) element"), std::string::npos)
      << text;
  for (const char* expected :
       {"bad.scene:4:11: 'acceleration' has 2 components, the scene has dimension = 3",
        "bad.scene:5:1: RigidBody2D is a planar (2D) element: planar bodies and their joints "
        "need dimension = 2",
        "bad.scene:6:1: RevoluteJoint is a planar (2D) element", "bad.scene:7:17: STL file",
        "nowhere.stl' does not exist",
        "bad.scene:8:17: a 3D Ground mesh is read from an STL file, not from points",
        "bad.scene:9:", "a 3D total_fluid_force sensor has components x, y or z", "bad.scene:10:",
        "'velocity' has 2 components, the scene has dimension = 3", "write velocity = [x, y, z]"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
  }
  // The open surface once the velocity is right.
  std::ofstream(folder / "open.scene") << R"(scene_language = 1
dimension = 3
SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
Ground { Mesh { stl = "open.stl" } }
FluidRegion { shape = "stl"; stl = "open.stl"; spacing = 0.1; density = 1000 }
Sensor { name = "f"; type = "position"; body = "x"; component = "z" }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.2 }
)";
  const std::string open = build_error(folder / "open.scene");
  EXPECT_NE(open.find("open.scene:5:30: the STL surface does not enclose a volume"),
            std::string::npos)
      << open;
  EXPECT_NE(open.find("open.scene:6:"), std::string::npos) << open;
  EXPECT_NE(open.find("no body named 'x'"), std::string::npos) << open;
  fs::remove_all(folder);
}

TEST(Scene, ThreeDimensionalInputInATwoDimensionalScene) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_2d_with_3d_test";
  fs::create_directories(folder);
  std::ofstream(folder / "s.in") << "# script\n";
  std::ofstream(folder / "box.stl") << unit_box_stl();
  std::ofstream(folder / "bad.scene") << R"(scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }
Ground { Mesh { stl = "box.stl" } }
Ground { Mesh { points = [[0, 0], [1, 0]] } }
Sensor { name = "f"; type = "total_fluid_force"; component = "z" }
FluidRegion { shape = "box"; lower = [0, 0, 0]; upper = [1, 1, 1]; spacing = 0.1; density = 1 }
LIGGGHTS { script1 = "s.in"; script2 = "s.in" }
Coupling { refinement_resolution = 0.2 }
)";
  const std::string text = build_error(folder / "bad.scene");
  for (const char* expected :
       {"bad.scene:3:17: STL meshes need a 3D scene (dimension = 2 here)",
        "bad.scene:5:", "component z needs a 3D scene (dimension = 2 here)", "bad.scene:6:",
        "'lower' has 3 components, the scene has dimension = 2", "'upper' has 3 components"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
  }
  fs::remove_all(folder);
}

}  // namespace
}  // namespace fsi::scene
