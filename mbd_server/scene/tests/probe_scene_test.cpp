// Probe blocks (docs/user-guide.md, "Probes"): each kind's declared keys become its definition in
// the scene's dimension, and a probe whose columns another probe or a sensor writes, a vector of
// the wrong length or an axis the dimension lacks are problems at their place.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/scene/scene.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

// A folder per test and dimension: ctest runs them in parallel.
class ProbeScene : public testing::FolderPerTestOf<::testing::TestWithParam<int>> {
 protected:
  // A structure-only scene with the given blocks in the test's dimension; "(accepted)" or the
  // problems.
  std::string build(const std::string& blocks, Scene* built = nullptr) {
    return mbd_only_outcome("p.scene",
                            "scene_language = 1\ndimension = " + std::to_string(GetParam()) +
                                "\nSolverOptions { end_time = 1; Timeint { step_size = 1e-3 } }\n" +
                                blocks,
                            built);
  }
  std::string point(double x, double y) const {
    return "[" + std::to_string(x) + ", " + std::to_string(y) + (GetParam() == 3 ? ", 0.5]" : "]");
  }
};

TEST_P(ProbeScene, EachKindBecomesItsDefinition) {
  Scene scene;
  const std::string text =
      build("PointProbe { name = \"gauge\"; point = " + point(0.1, 0.2) +
                " }\n"
                "FreeSurfaceProbe { name = \"level\"; bottom = " +
                point(0.3, 0.0) +
                "; length = 0.5 }\n"
                "FluidEnergyProbe { name = \"water\" }\n"
                "FrontProbe { name = \"surge\"; direction = \"decreasing\"; min_neighbours = 5 }\n",
            &scene);
  ASSERT_EQ(text, "(accepted)");
  const double z = GetParam() == 3 ? 0.5 : 0.0;
  // In the order of the kinds (their columns in sensors.csv too), each kind in file order.
  ASSERT_EQ(scene.probes.size(), 4u);
  EXPECT_TRUE(scene.probes[0] == probes::fluid_energy_probe("water", {0.0, 0.0, 0.0}));
  EXPECT_TRUE(scene.probes[1] == probes::point_probe("gauge", {0.1, 0.2, z}));
  EXPECT_TRUE(scene.probes[2] == probes::free_surface_probe("level", {0.3, 0.0, z}, 0.5, 200));
  EXPECT_TRUE(scene.probes[3] == probes::front_probe("surge", 0, -1, 5));
}

TEST_P(ProbeScene, ProblemsAreReportedAtTheirPlace) {
  const std::string text = build(
      "Sensor { name = \"gauge_vx\"; type = \"kinetic_energy\" }\n"
      "PointProbe { name = \"gauge\"; point = [1, 2, 3, 4] }\n"
      "PointProbe { name = \"gauge\"; point = " +
      point(0.0, 0.0) +
      " }\n"
      "FluidEnergyProbe { name = \"e\" }\n"
      "FluidEnergyProbe { name = \"e\" }\n"
      "FreeSurfaceProbe { name = \"s\"; bottom = " +
      point(0.0, 0.0) + "; length = 0; samples = 1 }\n");
  EXPECT_NE(text.find("p.scene:5:30: 'point' has 4 components, the scene has dimension = " +
                      std::to_string(GetParam())),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("p.scene:6:14: probe 'gauge' writes the column 'gauge_vx', which a sensor "
                      "or another probe writes already; rename the probe"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("p.scene:8:20: probe 'e' writes the column 'e_kinetic'"), std::string::npos)
      << text;
  EXPECT_NE(text.find("'FreeSurfaceProbe.length' = 0 m is out of range"), std::string::npos)
      << text;
  EXPECT_NE(text.find("'FreeSurfaceProbe.samples' = 1 is out of range"), std::string::npos) << text;
}

TEST_P(ProbeScene, AFluxSectionFitsTheDimension) {
  Scene scene;
  const bool spatial = GetParam() == 3;
  const std::string good = spatial ? "[[0, 0, 0], [0, 1, 0], [0, 1, 1]]" : "[[0, 0], [0, 1]]";
  ASSERT_EQ(build("FluxProbe { name = \"q\"; points = " + good + " }\n", &scene), "(accepted)");
  ASSERT_EQ(scene.probes.size(), 1u);
  EXPECT_TRUE(scene.probes[0] ==
              probes::flux_probe(
                  "q",
                  spatial ? std::vector<std::array<double, 3>>{{0, 0, 0}, {0, 1, 0}, {0, 1, 1}}
                          : std::vector<std::array<double, 3>>{{0, 0, 0}, {0, 1, 0}},
                  40));
  const std::string bad =
      spatial ? "[[0, 0, 0], [0, 1, 0], [0, 2, 0]]" : "[[0, 0], [0, 1], [1, 1]]";
  const std::string text = build("FluxProbe { name = \"q\"; points = " + bad + " }\n");
  EXPECT_NE(
      text.find(spatial ? "p.scene:4:25: flux probe 'q' has no area (its points are in line); "
                          "give three or more corners of a planar polygon"
                        : "p.scene:4:25: flux probe 'q' needs a segment of 2 points; give "
                          "the segment's two distinct points"),
      std::string::npos)
      << text;
}

TEST_P(ProbeScene, AFrontAlongZNeedsThreeDimensions) {
  const std::string text = build("FrontProbe { name = \"up\"; axis = \"z\" }\n");
  if (GetParam() == 3) {
    EXPECT_EQ(text, "(accepted)");
  } else {
    EXPECT_NE(text.find("p.scene:4:27: axis z needs a 3D scene (dimension = 2 here); write x or y"),
              std::string::npos)
        << text;
  }
}

// A wall pressure probe names whose mesh it reads (a body's or the ground's): the scene turns the
// name into that mesh's element ranges of the boundary mesh, and refuses an unknown name and a
// patch that reaches none of the mesh's elements, naming what to write instead.
class WallPressureScene : public testing::FolderPerTestOf<::testing::Test> {
 protected:
  std::string build(const std::string& probes, Scene* built = nullptr) {
    return mbd_only_outcome(
        "w.scene",
        "scene_language = 1\n"
        "SolverOptions { end_time = 1; Timeint { step_size = 1e-3 } }\n"
        "RigidBody2D { name = \"plate\"; mass = 1; inertia = 1; position = [0.5, 0.5]\n"
        "  Mesh { points = [[-0.1, 0], [0.1, 0]] } }\n"
        "Ground { Mesh { points = [[0, 1], [0, 0], [1, 0], [1, 1]] } }\n" +
            probes,
        built);
  }
};

TEST_F(WallPressureScene, TheMeshNameBecomesItsElementRanges) {
  Scene scene;
  ASSERT_EQ(build("WallPressureProbe { name = \"left\"; mesh = \"ground\"; centre = [0, 0.4]; "
                  "radius = 0.05; fluid_side = [1, 0] }\n"
                  "WallPressureProbe { name = \"top\"; mesh = \"plate\"; centre = [0.5, 0.5]; "
                  "radius = 0.01; fluid_side = [0, 1] }\n",
                  &scene),
            "(accepted)");
  // The plate's segment comes first (bodies are built before the ground), then the ground's 3.
  ASSERT_EQ(scene.probes.size(), 2u);
  EXPECT_TRUE(scene.probes[0] == probes::wall_pressure_probe("left", {0.0, 0.4, 0.0}, 0.05,
                                                             {1.0, 0.0, 0.0}, {{1u, 4u}}));
  EXPECT_TRUE(scene.probes[1] == probes::wall_pressure_probe("top", {0.5, 0.5, 0.0}, 0.01,
                                                             {0.0, 1.0, 0.0}, {{0u, 1u}}));
}

TEST_F(WallPressureScene, AnUnknownMeshAndAPatchOffTheMeshAreProblems) {
  const std::string text = build(
      "WallPressureProbe { name = \"a\"; mesh = \"tank\"; centre = [0, 0.4]; radius = 0.05; "
      "fluid_side = [1, 0] }\n"
      "WallPressureProbe { name = \"b\"; mesh = \"plate\"; centre = [0, 0.4]; radius = 0.05; "
      "fluid_side = [1, 0] }\n"
      "WallPressureProbe { name = \"c\"; mesh = \"ground\"; centre = [0, 0.4]; radius = 0.05; "
      "fluid_side = [0, 0] }\n");
  EXPECT_NE(text.find("w.scene:6:33: wall pressure probe 'a': 'tank' has no mesh; write mesh = "
                      "one of \"plate\", \"ground\""),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("wall pressure probe 'b': its patch (radius 0.05 m) reaches no element of "
                      "the mesh of 'plate' in the initial configuration; the nearest element of "
                      "its mesh lies 0.412311 m from the centre; put the centre on the mesh"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("wall pressure probe 'c' has no fluid side"), std::string::npos) << text;
}

// A named Ground block's meshes are a mesh of their own for a probe (a transducer on one wall of
// a tank whose floor its patch also reaches); the name must tell the block from the others.
TEST_F(WallPressureScene, ANamedGroundIsAMeshOfItsOwn) {
  const std::string tank =
      "scene_language = 1\n"
      "SolverOptions { end_time = 1; Timeint { step_size = 1e-3 } }\n"
      "RigidBody2D { name = \"plate\"; mass = 1; inertia = 1; position = [0.5, 0.5]\n"
      "  Mesh { points = [[-0.1, 0], [0.1, 0]] } }\n"
      "Ground { Mesh { points = [[0, 1], [0, 0], [1, 0]] } }\n"
      "Ground { name = \"end\"; Mesh { points = [[1, 0], [1, 1]] } }\n";
  Scene scene;
  ASSERT_EQ(mbd_only_outcome("n.scene",
                             tank + "WallPressureProbe { name = \"p\"; mesh = \"end\"; "
                                    "centre = [1, 0.01]; radius = 0.05; fluid_side = [-1, 0] }\n"
                                    "WallPressureProbe { name = \"all\"; mesh = \"ground\"; "
                                    "centre = [1, 0.01]; radius = 0.05; fluid_side = [-1, 0] }\n",
                             &scene),
            "(accepted)");
  // The plate's segment is element 0, the first Ground's two are 1 and 2, the end wall is 3.
  ASSERT_EQ(scene.probes.size(), 2u);
  EXPECT_TRUE(scene.probes[0] == probes::wall_pressure_probe("p", {1.0, 0.01, 0.0}, 0.05,
                                                             {-1.0, 0.0, 0.0}, {{3u, 4u}}));
  EXPECT_TRUE(scene.probes[1] == probes::wall_pressure_probe("all", {1.0, 0.01, 0.0}, 0.05,
                                                             {-1.0, 0.0, 0.0}, {{1u, 4u}}));
  // The end wall's patch must lie on the end wall; the unknown name lists the named Ground.
  std::string text = mbd_only_outcome(
      "n.scene", tank +
                     "WallPressureProbe { name = \"q\"; mesh = \"end\"; centre = [0, 0.5]; "
                     "radius = 0.05; fluid_side = [1, 0] }\n"
                     "WallPressureProbe { name = \"r\"; mesh = \"ends\"; centre = [1, 0.5]; "
                     "radius = 0.05; fluid_side = [-1, 0] }\n");
  EXPECT_NE(text.find("wall pressure probe 'q': its patch (radius 0.05 m) reaches no element of "
                      "the mesh of 'end' in the initial configuration; the nearest element of "
                      "its mesh lies 1 m from the centre"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("'ends' has no mesh; write mesh = one of \"plate\", \"ground\", \"end\""),
            std::string::npos)
      << text;
  // A name a probe could not tell apart: "ground", a body's, another Ground's.
  text = mbd_only_outcome("n.scene",
                          tank +
                              "Ground { name = \"ground\"; Mesh { points = [[2, 0], [3, 0]] } }\n"
                              "Ground { name = \"plate\"; Mesh { points = [[2, 0], [3, 0]] } }\n"
                              "Ground { name = \"end\"; Mesh { points = [[2, 0], [3, 0]] } }\n");
  EXPECT_NE(text.find("n.scene:7:10: Ground 'ground': \"ground\" names every Ground mesh at once; "
                      "give this Ground block another name"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("n.scene:8:10: Ground 'plate': a body has this name"), std::string::npos)
      << text;
  EXPECT_NE(text.find("n.scene:9:10: Ground 'end': another Ground has this name"),
            std::string::npos)
      << text;
}

// The probe reads the elements that face its fluid side (to within 45 degrees): a patch that
// reaches its mesh only where it faces another way (a fluid side along a floor) is refused with
// the fluid side to write; a patch at a corner that also reaches a facing element is accepted.
TEST_F(WallPressureScene, APatchThatFacesNoneOfItsElementsIsAProblem) {
  const std::string text = build(
      "WallPressureProbe { name = \"floor\"; mesh = \"ground\"; centre = [0.5, 0]; "
      "radius = 0.05; fluid_side = [1, 0] }\n");
  EXPECT_NE(text.find("w.scene:6:88: wall pressure probe 'floor': its patch (radius 0.05 m) "
                      "reaches elements of the mesh of 'ground' only where they face another way "
                      "than fluid_side [1, 0, 0] (more than 45 degrees off), and it reads only "
                      "the elements that face it; the nearest element facing it lies 0.5 m from "
                      "the centre; give fluid_side as the direction from this wall into the fluid"),
            std::string::npos)
      << text;
  EXPECT_EQ(build("WallPressureProbe { name = \"corner\"; mesh = \"ground\"; centre = [0, 0.02]; "
                  "radius = 0.05; fluid_side = [1, 0] }\n"
                  "WallPressureProbe { name = \"floor\"; mesh = \"ground\"; centre = [0.5, 0]; "
                  "radius = 0.05; fluid_side = [0, 1] }\n"),
            "(accepted)");
}

INSTANTIATE_TEST_SUITE_P(BothDimensions, ProbeScene, ::testing::Values(2, 3));

// A probe with `body` moves with that rigid body (protocol 1.4): declared where the body starts,
// placed by the body's translation and rotation.
TEST_F(WallPressureScene, AProbeWithABodyIsPlacedWhereTheBodyTookIt) {
  Scene scene;
  ASSERT_EQ(build("PointProbe { name = \"rider\"; point = [0.6, 0.5]; body = \"plate\" }\n"
                  "PointProbe { name = \"fixed\"; point = [0.6, 0.5] }\n"
                  "WallPressureProbe { name = \"under\"; mesh = \"plate\"; centre = [0.55, 0.5]; "
                  "radius = 0.02; fluid_side = [0, -1]; body = \"plate\" }\n",
                  &scene),
            "(accepted)");
  ASSERT_EQ(scene.attached_probes.size(), 2u);
  EXPECT_EQ(scene.probes[scene.attached_probes[0].probe].name, "rider");
  EXPECT_EQ(scene.probes[scene.attached_probes[1].probe].name, "under");
  // Where it starts, every probe is as declared.
  const std::vector<probes::ProbeDefinition> at_start =
      placed_probes(scene, scene.model.initial_configuration());
  EXPECT_EQ(at_start[0], scene.probes[scene.attached_probes[0].probe]);
  // The plate moved to (1.5, 0.25) and turned by 90 degrees: its point 0.1 m along its x axis
  // is at (1.5, 0.35), the wall's fluid side [0, -1] is [1, 0].
  mbd::State moved = scene.model.initial_configuration();
  moved.q(0) = 1.5;
  moved.q(1) = 0.25;
  moved.q(2) = std::acos(-1.0) / 2.0;
  const std::vector<probes::ProbeDefinition> placed = placed_probes(scene, moved);
  ASSERT_EQ(placed.size(), 2u);
  const std::vector<double>& point = placed[0].parameters;
  EXPECT_NEAR(point[0], 1.5, 1e-12);
  EXPECT_NEAR(point[1], 0.35, 1e-12);
  const std::vector<double>& wall = placed[1].parameters;
  EXPECT_NEAR(wall[0], 1.5, 1e-12);  // the patch's centre, 0.05 m along the plate
  EXPECT_NEAR(wall[1], 0.30, 1e-12);
  EXPECT_NEAR(wall[4], 1.0, 1e-12);  // the fluid side turned with the plate
  EXPECT_NEAR(wall[5], 0.0, 1e-12);
  EXPECT_EQ(wall[7], scene.probes[scene.attached_probes[1].probe].parameters[7]);  // elements
}

TEST_F(WallPressureScene, AProbeMovesWithANamedBodyOnly) {
  const std::string text = build(
      "PointProbe { name = \"a\"; point = [0.6, 0.5]; body = \"ground\" }\n"
      "PointProbe { name = \"b\"; point = [0.6, 0.5]; body = \"plank\" }\n");
  EXPECT_NE(text.find("w.scene:6:46: no body named 'ground'; known bodies: plate"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("w.scene:7:46: no body named 'plank'"), std::string::npos) << text;
}

class MovingProbeScene : public testing::FolderPerTest {};

TEST_F(MovingProbeScene, InThreeDimensionsAProbeTurnsWithItsBody) {
  Scene scene;
  ASSERT_EQ(
      mbd_only_outcome("p3.scene",
                       "scene_language = 1\ndimension = 3\n"
                       "SolverOptions { end_time = 1; Timeint { step_size = 1e-3 } }\n"
                       "RigidBody3D { name = \"lid\"; mass = 2; inertia = [0.2, 0.3, 0.4]; "
                       "position = [1, 0, 0] }\n"
                       "PointProbe { name = \"rider\"; point = [1.1, 0, 0.2]; body = \"lid\" }\n",
                       &scene),
      "(accepted)");
  ASSERT_EQ(scene.attached_probes.size(), 1u);
  // The lid moved to (2, 0, 0) and turned by 90 degrees about z: its axes e1 = y, e2 = -x, e3 = z
  // (natural coordinates r, e1, e2, e3). Its point (0.1, 0, 0.2) off the centre is at (2, 0.1,
  // 0.2).
  mbd::State moved = scene.model.initial_configuration();
  const double q[12] = {2, 0, 0, 0, 1, 0, -1, 0, 0, 0, 0, 1};
  for (int k = 0; k < 12; ++k)
    moved.q(k) = q[k];
  const std::vector<probes::ProbeDefinition> placed = placed_probes(scene, moved);
  const std::vector<double>& point = placed[0].parameters;
  EXPECT_NEAR(point[0], 2.0, 1e-12);
  EXPECT_NEAR(point[1], 0.1, 1e-12);
  EXPECT_NEAR(point[2], 0.2, 1e-12);
}

}  // namespace
}  // namespace fsi::scene
