// The Assembly block: a parallelogram four-bar given with its coupler and rocker turned by
// 1e-3 rad builds only with the block, keeps the driving crank, and runs; bad driving names are
// problems at their line; an open loop is refused at the block naming its joints.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/scene/scene.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

class AssemblyScene : public testing::FolderPerTest {
 protected:
  std::filesystem::path write(const std::string& assembly, double rocker_length = 0.5) const {
    return write_coupled_scene("four_bar.scene",
                               "SolverOptions { end_time = 0.1; Timeint { step_size = 1e-3 } }\n" +
                                   assembly + "\n" + four_bar(rocker_length));
  }

  // Ground pivots (0, 0) and (1, 0), crank and rocker upright (0.5 m), coupler across at
  // y = 0.5: every body at angle 0 when closed. Coupler and rocker are given turned by +-1e-3.
  static std::string four_bar(double rocker_length) {
    const std::string half_rocker = std::to_string(rocker_length / 2.0);
    return R"(Gravity { acceleration = [0, -9.81] }
RigidBody2D { name = "crank"; mass = 1; inertia = 0.02; position = [0, 0.25];
              angular_velocity = 0.4; velocity = [-0.1, 0]
              Mesh { points = [[0, -0.25], [0, 0.25]] } }
RigidBody2D { name = "coupler"; mass = 2; inertia = 0.17; position = [0.5, 0.5]; angle = 1e-3 }
RigidBody2D { name = "rocker"; mass = 1; inertia = 0.02; position = [1, )" +
           half_rocker + R"(]; angle = -1e-3 }
RevoluteJoint { name = "O1"; body_a = "crank"; point_a = [0, -0.25]; point_b = [0, 0] }
RevoluteJoint { name = "A"; body_a = "crank"; point_a = [0, 0.25];
                body_b = "coupler"; point_b = [-0.5, 0] }
RevoluteJoint { name = "B"; body_a = "coupler"; point_a = [0.5, 0];
                body_b = "rocker"; point_b = [0, )" +
           half_rocker + R"(] }
RevoluteJoint { name = "O2"; body_a = "rocker"; point_a = [0, -)" +
           half_rocker + R"(]; point_b = [1, 0] }
)";
  }
};

TEST_F(AssemblyScene, WithoutTheBlockTheTurnedLinksAreRefused) {
  const std::string text = testing::build_error(write(""));
  EXPECT_NE(text.find("inconsistent with the constraints"), std::string::npos) << text;
  EXPECT_NE(testing::build_error(write("Assembly { enabled = 0 }"))
                .find("inconsistent with the constraints"),
            std::string::npos);
}

TEST_F(AssemblyScene, TheBlockClosesTheLoopKeepsTheCrankAndRuns) {
  Scene scene = build_scene(write("Assembly { driving = \"crank.angle, crank.x\" }").string());
  ASSERT_TRUE(scene.assembly.has_value());
  const mbd::Model& model = scene.model;
  mbd::State state = model.initial_state();  // checks |C| <= 1e-12 (1 + |q|)
  EXPECT_LE(scene.assembly->position_residual, 1e-12);
  const mbd::BodyId crank = model.find_body("crank");
  const mbd::BodyId coupler = model.find_body("coupler");
  const mbd::BodyId rocker = model.find_body("rocker");
  EXPECT_EQ(model.coordinate(state, crank, mbd::Coordinate::Angle), 0.0);
  EXPECT_EQ(model.velocity(state, crank, mbd::Coordinate::Angle), 0.4);
  EXPECT_EQ(model.velocity(state, crank, mbd::Coordinate::X), -0.1);
  EXPECT_NEAR(model.coordinate(state, coupler, mbd::Coordinate::Angle), 0.0, 1e-15);
  EXPECT_NEAR(model.coordinate(state, rocker, mbd::Coordinate::Angle), 0.0, 1e-15);
  EXPECT_NEAR(model.coordinate(state, rocker, mbd::Coordinate::Y), 0.25, 1e-15);
  // A parallelogram translates its coupler: every point moves like the crank's tip.
  EXPECT_NEAR(model.velocity(state, coupler, mbd::Coordinate::X), -0.2, 1e-15);
  EXPECT_NEAR(model.velocity(state, rocker, mbd::Coordinate::Angle), 0.4, 1e-15);
  ASSERT_EQ(scene.assembly->bodies.size(), 3u);
  EXPECT_EQ(scene.assembly->bodies[0].largest_position_change, 0.0);
  EXPECT_NEAR(scene.assembly->bodies[1].largest_position_change, 1e-3, 1e-12);
  EXPECT_EQ(scene.assembly->bodies[1].position_coordinate, "coordinate angle");
  const std::vector<std::string> lines = scene.assembly->lines();
  EXPECT_NE(lines[2].find("body 'coupler': position by 0.001 (coordinate angle)"),
            std::string::npos)
      << lines[2];

  mbd::RadauIIA integrator(3);
  for (int n = 0; n < 100; ++n)
    integrator.step(model, state, 1e-3);
  EXPECT_LE(mbd::position_constraint_drift(model, state), 1e-12);
  EXPECT_GT(std::abs(model.coordinate(state, crank, mbd::Coordinate::Angle)), 0.01);
}

TEST_F(AssemblyScene, BadDrivingNamesAreProblemsAtTheKey) {
  const std::string text = testing::build_error(
      write("Assembly {\n  driving = \"crank.angle, crank.phi, nobody.x, crank, crank.angle\"\n}"));
  EXPECT_NE(text.find("four_bar.scene:4:"), std::string::npos) << text;
  EXPECT_NE(text.find("a rigid_body_2d has no coordinate 'phi'"), std::string::npos) << text;
  EXPECT_NE(text.find("no body named 'nobody'"), std::string::npos) << text;
  EXPECT_NE(text.find("'crank' is not of the form body.coordinate"), std::string::npos) << text;
  EXPECT_NE(text.find("'crank.angle' is named twice"), std::string::npos) << text;
}

TEST_F(AssemblyScene, AnOpenLoopIsRefusedAtTheBlockNamingItsJoints) {
  // With the crank held upright, B must lie 1 m from A = (0, 0.5), which is 1.118 m from the
  // rocker's pivot: a rocker of 0.05 m cannot reach.
  const std::string text =
      testing::build_error(write("\n\nAssembly { driving = \"crank.angle\" }", 0.05));
  EXPECT_NE(text.find("four_bar.scene:5:1"), std::string::npos) << text;
  EXPECT_NE(text.find("cannot be closed"), std::string::npos) << text;
  EXPECT_NE(text.find("revolute joint 'B'"), std::string::npos) << text;
  EXPECT_NE(text.find("the loop misses by"), std::string::npos) << text;
}

}  // namespace
}  // namespace fsi::scene
