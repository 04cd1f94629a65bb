// Scene blocks of the spatial (3D) multibody model: a scene with every block builds the expected
// model, meshes (a body's STL in its frame, a cable's tube) and sensors; the dynamic vertices come
// first and move with the bodies; mistakes are problems at their file:line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/scene/scene.hpp"
#include "fsi/scene/schema.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

class SpatialScene : public testing::FolderPerTest {
 protected:
  void SetUp() override {
    testing::FolderPerTest::SetUp();
    testing::FolderPerTest::write("box.stl", testing::unit_box_stl());
  }

  std::filesystem::path write(const std::string& body, int dimension = 3,
                              const std::string& coupling = "refinement_resolution = 0.002") const {
    return write_coupled_scene(
        "m.scene",
        "dimension = " + std::to_string(dimension) +
            "\nSolverOptions { end_time = 1; Timeint { step_size = 1e-3 } }\n" + body,
        coupling);
  }
};

const char* const kEveryBlock = R"scene(Gravity { acceleration = [0, 0, -9.81] }
RigidBody3D { name = "lid"; mass = 2; inertia = [0.2, 0.3, 0.4]; position = [1, 0, 0]
              axis = [0, 0, 1]; angle = pi/2
              Mesh { stl = "box.stl"; scale = 0.1; offset = [-0.05, -0.05, -0.05] } }
RigidBody3D { name = "knob"; mass = 0.1; inertia = [0.01, 0.01, 0.01]; position = [1, 0, 0.2] }
PointMass { name = "bob"; mass = 0.5; position = [2, 0, -1] }
AncfCable3D { name = "rope"; start = [2, 0, 0]; end = [2, 0, -1]; elements = 2
              axial_stiffness = 1e5; bending_stiffness = 1; mass_per_length = 0.2
              radius = 0.01; tube_sides = 6; tube_rings_per_element = 2 }
CableClamp { cable = "rope"; node = 0 }
SphericalJoint { name = "tie"; body_a = "bob"; body_b = "rope"; point_b = [1, 0, 0] }
RevoluteJoint3D { name = "hinge"; body_a = "lid"; point_b = [1, 0, 0]; axis = [0, 0, 1] }
FixedJoint3D { name = "weld"; body = "knob"; to = "lid" }
DistanceConstraint3D { name = "rod"; body_a = "knob"; point_a = [0.3, 0, 0]; point_b = [1.3, 1, 0.2] }
Ground { Mesh { stl = "box.stl"; offset = [0, 0, -3] } }
Sensor { name = "lid_z"; type = "position"; body = "lid"; component = "z" }
Sensor { name = "bob_vx"; type = "velocity"; body = "bob"; component = "x" }
Sensor { name = "rope_fz"; type = "fluid_force"; body = "rope"; component = "z" }
Sensor { name = "hinge_z"; type = "joint_force"; joint = "hinge"; component = "z" }
Sensor { name = "energy"; type = "potential_energy" }
)scene";

TEST_F(SpatialScene, EveryBlockBuildsTheModelMeshesAndSensors) {
  const Scene scene = build_scene(write(kEveryBlock).string());
  const mbd::Model& model = scene.model;
  ASSERT_EQ(model.body_count(), 4);
  EXPECT_EQ(model.body_kind(0), "rigid_body_3d");
  EXPECT_EQ(model.body_kind(2), "point_mass");
  EXPECT_EQ(model.body_kind(3), "ancf_cable");
  EXPECT_EQ(model.coordinate_count(), 12 + 12 + 3 + 18);
  // 6 + 6 orthonormality, cable clamp 5, spherical 3, revolute 5, fixed 6, rod 1.
  EXPECT_EQ(model.constraint_count(), 12 + 5 + 3 + 5 + 6 + 1);
  // Dynamic vertices: the lid's 8 box corners, then the tube: 5 rings of 6 and 2 end centres.
  const std::size_t tube = 5 * 6 + 2;
  EXPECT_EQ(scene.boundary.dynamic_vertex_count, 8 + tube);
  EXPECT_EQ(static_cast<std::size_t>(model.marker_count()), 8 + tube);
  EXPECT_EQ(scene.boundary.vertex_count, 8 + tube + 8);
  EXPECT_EQ(scene.boundary.element_count(), 12 + (2 * 4 * 6 + 2 * 6) + 12);
  // The ground's triangles index the static vertices after the dynamic ones.
  for (std::size_t k = 3 * (12 + 60); k < scene.boundary.triangles.size(); ++k)
    EXPECT_GE(scene.boundary.triangles[k], 8 + tube);

  const mbd::State state = model.initial_state();
  std::vector<double> positions, velocities;
  boundary_state(scene.boundary, model, state, positions, velocities);
  ASSERT_EQ(positions.size(), 3 * scene.boundary.vertex_count);
  // Vertex 1 is the STL's second distinct point, corner (0, 1, 0): 0.1 (0, 1, 0) - 0.05 =
  // (-0.05, 0.05, -0.05) in the lid's frame, turned by 90 degrees about z, at (1, 0, 0).
  EXPECT_NEAR(positions[3 * 1 + 0], 1.0 - 0.05, 1e-12);
  EXPECT_NEAR(positions[3 * 1 + 1], -0.05, 1e-12);
  EXPECT_NEAR(positions[3 * 1 + 2], -0.05, 1e-12);
  // Tube vertices lie at the radius around the vertical rope; the ground box is where it was put.
  const double dx = positions[3 * 8 + 0] - 2.0, dy = positions[3 * 8 + 1];
  EXPECT_NEAR(std::hypot(dx, dy), 0.01, 1e-12);
  EXPECT_NEAR(positions[3 * (8 + tube + 7) + 2], -2.0, 1e-12);

  // Each element belongs to the body of its vertices: the lid's 12 triangles, the rope's tube,
  // the ground's box, in the order they come.
  const std::vector<BodyElements> parts = elements_by_body(scene.boundary, model);
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(model.body_name(parts[0].body), "lid");
  EXPECT_EQ(parts[0].elements.size(), 3u * 12);
  EXPECT_EQ(model.body_name(parts[1].body), "rope");
  EXPECT_EQ(parts[1].elements.size(), 3u * (2 * 4 * 6 + 2 * 6));
  EXPECT_EQ(parts[2].body, mbd::kGround);
  EXPECT_EQ(parts[2].elements.size(), 3u * 12);
  for (std::size_t k = 0; k < parts[1].elements.size(); ++k)
    EXPECT_EQ(vertex_body(scene.boundary, model, parts[1].elements[k]), parts[1].body);
  EXPECT_EQ(vertex_body(scene.boundary, model, static_cast<std::uint32_t>(8 + tube)), mbd::kGround);

  ASSERT_EQ(scene.sensors.size(), 5u);
  EXPECT_EQ(scene.sensors[0].unit, "m");
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[0], state), 0.0, 1e-15);
  EXPECT_EQ(scene.sensors[3].rows, 5);
  // The hinge holds the lid and (through the weld) the knob: its z force carries their weight.
  EXPECT_GT(structure_sensor_value(model, scene.sensors[3], state), 0.0);

  // The coupled step's integrator runs the model.
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  mbd::State moving = state;
  for (int i = 0; i < 5; ++i)
    integrator.step(model, moving, 1e-3);
  EXPECT_LT(position_constraint_drift(model, moving), 1e-10);
}

TEST_F(SpatialScene, SensorsOfPointsAndTorques) {
  Scene scene = build_scene(write(std::string(kEveryBlock) + R"scene(
Sensor { name = "rope_end_z"; type = "position"; body = "rope"; point = [1, 0, 0]; component = "z" }
Sensor { name = "lid_corner_y"; type = "position"; body = "lid"; point = [0.05, 0, 0]; component = "y" }
Sensor { name = "lid_torque_z"; type = "fluid_force"; body = "lid"; component = "torque_z" }
Sensor { name = "weld_torque_x"; type = "joint_force"; joint = "weld"; component = "torque_x" }
SpringDamper3D { name = "coil"; body_a = "bob"; point_b = [2, 0, -1.5]; stiffness = 100; rest_length = 0.4 }
Sensor { name = "coil_tension"; type = "spring_force"; element = "coil" }
)scene")
                                .string());
  mbd::Model& model = scene.model;
  const mbd::State state = model.initial_state();
  ASSERT_EQ(scene.sensors.size(), 10u);
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[9], state), 100.0 * (0.5 - 0.4), 1e-12);
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[5], state), -1.0, 1e-15);
  // The lid is turned by 90 degrees about z: its body x axis points along world y.
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[6], state), 0.05, 1e-15);
  EXPECT_EQ(scene.sensors[7].axis, 5);
  EXPECT_EQ(scene.sensors[7].unit, "N m");
  // A vertex load on the lid's corner 1 at (0.95, -0.05, -0.05): torque about the centre.
  std::vector<double> loads(3 * static_cast<std::size_t>(model.marker_count()), 0.0);
  loads[3 * 1 + 0] = 2.0;
  model.set_point_loads(loads);
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[7], state), 0.05 * 2.0, 1e-15);
  EXPECT_EQ(scene.sensors[8].axis, 3);
  // The same in a planar scene: a point of a beam and of a rigid body.
  const Scene planar = build_scene(write(R"scene(
RigidBody2D { name = "plate"; mass = 1; inertia = 1; angle = pi/2; Mesh { points = [[0, 0], [1, 0]] } }
AncfBeam2D { name = "beam"; start = [0, 0]; end = [2, 0]; elements = 2; thickness = 0.01
             axial_stiffness = 1e6; bending_stiffness = 1; mass_per_length = 1 }
Sensor { name = "corner_y"; type = "position"; body = "plate"; point = [0.5, 0]; component = "y" }
Sensor { name = "face_y"; type = "position"; body = "beam"; point = [1.5, 0.005]; component = "y" }
Sensor { name = "face_vx"; type = "velocity"; body = "beam"; point = [1.5, 0.005]; component = "x" }
)scene",
                                         2)
                                       .string());
  const mbd::State planar_state = planar.model.initial_state();
  EXPECT_NEAR(structure_sensor_value(planar.model, planar.sensors[0], planar_state), 0.5, 1e-15);
  EXPECT_NEAR(structure_sensor_value(planar.model, planar.sensors[1], planar_state), 0.005, 1e-15);
  EXPECT_NEAR(structure_sensor_value(planar.model, planar.sensors[2], planar_state), 0.0, 1e-15);
}

// A NonlinearSpringDamper3D's tension is the user's law at the elongation, rate and time; its
// mistakes are problems at their lines.
TEST_F(SpatialScene, ANonlinearSpatialSpringsTensionIsTheUsersLaw) {
  Scene scene = build_scene(write(R"scene(
PointMass { name = "bob"; mass = 0.5; position = [2, 0, -1]; velocity = [0, 0, -3] }
NonlinearSpringDamper3D { name = "rope"; body_a = "bob"; point_b = [2, 0, -1.5]; rest_length = 0.4
                          tension = "elongation > 0 ? 100*elongation + 2*rate + 5*t : 0" }
Sensor { name = "rope_tension"; type = "spring_force"; element = "rope" }
Ground { Mesh { stl = "box.stl"; offset = [0, 0, -3] } }
)scene")
                                .string());
  mbd::Model& model = scene.model;
  mbd::State state = model.initial_state();
  ASSERT_EQ(scene.sensors.size(), 1u);
  // Elongation 0.5 - 0.4 m; bob (point a) moves at 3 m/s towards point b: the rate is -3 m/s.
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[0], state), 100.0 * 0.1 - 6.0, 1e-12);
  state.time = 0.5;
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[0], state), 100.0 * 0.1 - 6.0 + 2.5,
              1e-12);

  const std::string text = testing::build_error(write(R"scene(
PointMass { name = "bob"; mass = 0.5; position = [2, 0, -1] }
NonlinearSpringDamper3D { name = "a"; body_a = "bob"; tension = "100*stretch" }
NonlinearSpringDamper3D { name = "b"; body_a = "bob"; point_b = [1, 0, 0] }
NonlinearSpringDamper3D { name = "c"; body_a = "bob"; point_b = [2, 0, -1]; tension = "elongation" }
)scene"));
  for (const char* expected :
       {"m.scene:6:", "stretch", "m.scene:7:", "'NonlinearSpringDamper3D[1].tension' is missing",
        "m.scene:8:", "coincide initially"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
  }
  const std::string planar = testing::build_error(write(R"scene(
RigidBody2D { name = "plate"; mass = 1; inertia = 1 }
NonlinearSpringDamper3D { body_a = "plate"; tension = "elongation" }
)scene",
                                                        2));
  EXPECT_NE(planar.find("m.scene:6:1: NonlinearSpringDamper3D is a spatial (3D) element"),
            std::string::npos)
      << planar;
}

TEST_F(SpatialScene, TimeDependentLoadsSpinARotor) {
  // A rotor on a hinge about z, driven by a torque 0.4 t about z: J omega' = 0.4 t, so
  // omega(1 s) = 0.2 / J_z; a point force pushes a free point mass along x: m x'' = 3.
  const Scene scene = build_scene(write(R"scene(
RigidBody3D { name = "rotor"; mass = 2; inertia = [0.3, 0.3, 0.5]
              Mesh { stl = "box.stl"; scale = 0.1 } }
RevoluteJoint3D { body_a = "rotor"; axis = [0, 0, 1] }
Torque3D { name = "motor"; body = "rotor"; torque_z = "0.4*t" }
PointMass { name = "puck"; mass = 0.5; position = [3, 0, 0] }
PointForce3D { body = "puck"; force_x = "3" }
)scene")
                                      .string());
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  mbd::State state = scene.model.initial_state();
  for (int i = 0; i < 1000; ++i)
    integrator.step(scene.model, state, 1e-3);
  EXPECT_NEAR(angular_velocity(scene.model, state, 0).z(), 0.2 / 0.5, 1e-9);
  EXPECT_NEAR(state.q(12), 3.0 + 0.5 * 6.0, 1e-9);  // x = 3 + (3/0.5) t^2 / 2
  const std::string text = testing::build_error(write(R"scene(
RigidBody3D { name = "rotor"; mass = 2; inertia = [0.3, 0.3, 0.5]; Mesh { stl = "box.stl" } }
Torque3D { body = "rotor"; torque_z = "0.4*q" }
)scene"));
  EXPECT_NE(text.find("m.scene:6:28: the expression \"0.4*q\" is invalid"), std::string::npos)
      << text;
}

// A block on a PrismaticJoint3D down a 45 degree incline slides at g / sqrt(2); the joint's
// normal force on it is m g / sqrt(2) along the incline's normal, so its z component is m g / 2.
TEST_F(SpatialScene, APrismaticJoint3DHoldsTheBlockOnItsLine) {
  const Scene scene = build_scene(write(R"scene(
Gravity { acceleration = [0, 0, -9.81] }
RigidBody3D { name = "block"; mass = 2; inertia = [0.3, 0.4, 0.5]; position = [0, 0, 1]
              Mesh { stl = "box.stl"; scale = 0.1 } }
PrismaticJoint3D { name = "rail"; body_a = "block"; point_b = [1, 0, 0]; axis = [1, 0, -1] }
Sensor { name = "rail_z"; type = "joint_force"; joint = "rail"; component = "z" }
Sensor { name = "rail_ty"; type = "joint_force"; joint = "rail"; component = "torque_y" }
)scene")
                                      .string());
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  mbd::State state = scene.model.initial_state();
  for (int i = 0; i < 500; ++i)
    integrator.step(scene.model, state, 1e-3);
  const double s = 9.81 / std::sqrt(2.0) * 0.25 / 2.0;  // along the incline at t = 0.5 s
  EXPECT_NEAR(state.q(0), s / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(state.q(1), 0.0, 1e-12);
  EXPECT_NEAR(state.q(2), 1.0 - s / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[0], state), 2.0 * 9.81 / 2.0, 1e-6);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[1], state), 0.0, 1e-6);
  const std::string text = testing::build_error(write(R"scene(
RigidBody3D { name = "block"; mass = 2; inertia = [0.3, 0.4, 0.5]; Mesh { stl = "box.stl" } }
PrismaticJoint3D { body_a = "block"; point_b = [1, 0.5, 0] }
PrismaticJoint3D { body_a = "block"; axis = [0, 0, 0] }
)scene"));
  EXPECT_NE(text.find("m.scene:6:1: "), std::string::npos) << text;
  EXPECT_NE(text.find("off the sliding line"), std::string::npos) << text;
  EXPECT_NE(text.find("m.scene:7:1: "), std::string::npos) << text;
  EXPECT_NE(text.find("the axis must be a finite, non-zero vector"), std::string::npos) << text;
}

TEST_F(SpatialScene, DrivenRevoluteJointTurnsTheRotorAndReportsItsTorque) {
  // rate = 5 rad/s about z against a load torque of 0.3 N m about z: after 0.2 s the rotor has
  // turned by 1 rad, spins at 5 rad/s, and the drive torque on it is -0.3 N m.
  const Scene scene = build_scene(write(R"scene(
RigidBody3D { name = "rotor"; mass = 2; inertia = [0.3, 0.4, 0.5]; angular_velocity = [0, 0, 5]
              Mesh { stl = "box.stl"; scale = 0.1 } }
RevoluteJoint3D { name = "motor"; body_a = "rotor"; axis = [0, 0, 1]; rate = 5 }
Torque3D { name = "load"; body = "rotor"; torque_z = "0.3" }
Sensor { name = "drive"; type = "joint_force"; joint = "motor"; component = "torque" }
Sensor { name = "motor_tz"; type = "joint_force"; joint = "motor"; component = "torque_z" }
)scene")
                                      .string());
  ASSERT_EQ(scene.model.constraint_count(), 6 + 6);
  EXPECT_EQ(scene.sensors[0].unit, "N m");
  EXPECT_EQ(scene.sensors[0].rows, 6);
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  mbd::State state = scene.model.initial_state();
  for (int i = 0; i < 200; ++i)
    integrator.step(scene.model, state, 1e-3);
  const Eigen::Matrix3d turned = orientation(scene.model, state, 0);
  const double angle = std::atan2(turned(1, 0), turned(0, 0));
  EXPECT_NEAR(angle, 5.0 * state.time, 1e-12);
  EXPECT_NEAR(angular_velocity(scene.model, state, 0).z(), 5.0, 1e-8);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[0], state), -0.3, 1e-6);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[1], state), -0.3, 1e-6);

  // A non-finite rate, a drive torque of an undriven joint, a rate on a point mass's joint.
  const std::string text = testing::build_error(write(R"scene(
RigidBody3D { name = "rotor"; mass = 2; inertia = [0.3, 0.4, 0.5] }
PointMass { name = "bob"; mass = 1 }
RevoluteJoint3D { name = "spin"; body_a = "rotor"; rate = 1/0 }
RevoluteJoint3D { name = "free"; body_a = "rotor"; point_b = [0, 0, 1] }
Sensor { name = "t"; type = "joint_force"; joint = "free"; component = "torque" }
RevoluteJoint3D { name = "pm"; body_a = "bob"; rate = 2 }
)scene"));
  for (const char* expected :
       {"m.scene:7:", "evaluates to infinity", "m.scene:9:", "joint 'free' has no drive",
        "give the joint a rate", "m.scene:10:", "not a rigid body"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
  }
  // The key is declared once: --help and docs/parameters.md render it with its unit.
  const std::string help = render_help(scene_schema());
  EXPECT_NE(help.find("RevoluteJoint3D.rate  number [rad/s]  (optional)"), std::string::npos);
  EXPECT_NE(render_markdown(scene_schema()).find("| `rate` | number | rad/s |"), std::string::npos);
}

TEST_F(SpatialScene, RotationalSpringsHoldAFlapAndTheirSensorsReadTorqueAndPower) {
  // A flap hinged about x, swinging against a linear coil (k = 4, c = 0.2) and a one-sided stop
  // (50 rotation beyond 0): the spring_force sensors read -k theta - c theta' and the stop's
  // torque, the power sensor their product with the rate, the potential energy their energies.
  const Scene scene = build_scene(write(R"scene(
RigidBody3D { name = "flap"; mass = 2; inertia = [0.3, 0.4, 0.5]; angular_velocity = [1.5, 0, 0]
              Mesh { stl = "box.stl"; scale = 0.1 } }
RevoluteJoint3D { name = "hinge"; body_a = "flap"; axis = [1, 0, 0] }
RotationalSpringDamper3D { name = "coil"; body_a = "flap"; axis = [2, 0, 0]; stiffness = 4; damping = 0.2 }
NonlinearRotationalSpringDamper3D { name = "stop"; body_a = "flap"; axis = [1, 0, 0]
                                    torque = "rotation > 0 ? 50*rotation : 0" }
Sensor { name = "coil_torque"; type = "spring_force"; element = "coil" }
Sensor { name = "stop_torque"; type = "spring_force"; element = "stop" }
Sensor { name = "coil_power"; type = "power"; element = "coil" }
Sensor { name = "energy_p"; type = "potential_energy" }
)scene")
                                      .string());
  ASSERT_EQ(scene.sensors.size(), 4u);
  EXPECT_EQ(scene.sensors[0].unit, "N m");
  EXPECT_EQ(scene.sensors[2].unit, "W");
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  mbd::State state = scene.model.initial_state();
  for (int i = 0; i < 100; ++i)
    integrator.step(scene.model, state, 1e-3);
  const Eigen::Matrix3d turned = orientation(scene.model, state, 0);
  const double theta = std::atan2(turned(2, 1), turned(1, 1));
  const double rate = angular_velocity(scene.model, state, 0).x();
  EXPECT_GT(theta, 0.05);  // swung into the stop
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[0], state),
              -4.0 * theta - 0.2 * rate, 1e-9);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[1], state), -50.0 * theta, 1e-6);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[2], state),
              (-4.0 * theta - 0.2 * rate) * rate, 1e-9);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[3], state),
              0.5 * 4.0 * theta * theta + 0.5 * 50.0 * theta * theta, 1e-6);

  // Mistakes at their lines: a point mass, a law in an unknown variable, k beside a law (a
  // schema problem: the nonlinear block has no stiffness), a planar scene.
  const std::string text = testing::build_error(write(R"scene(
RigidBody3D { name = "flap"; mass = 2; inertia = [0.3, 0.4, 0.5] }
PointMass { name = "bob"; mass = 1 }
RotationalSpringDamper3D { name = "a"; body_a = "bob"; stiffness = 1 }
NonlinearRotationalSpringDamper3D { name = "b"; body_a = "flap"; torque = "5*angle" }
NonlinearRotationalSpringDamper3D { name = "c"; body_a = "flap"; torque = "rotation"; stiffness = 2 }
RotationalSpringDamper3D { name = "d"; body_a = "flap"; axis = [0, 0, 0]; stiffness = 1 }
Sensor { name = "s"; type = "spring_force"; element = "nothing" }
)scene"));
  for (const char* expected :
       {"m.scene:7:", "'bob' is not a rigid body", "m.scene:8:", "'angle' is neither",
        "m.scene:9:", "unknown parameter 'NonlinearRotationalSpringDamper3D[1].stiffness'",
        "m.scene:10:", "finite, non-zero vector",
        "m.scene:11:", "(Nonlinear)RotationalSpringDamper3D block"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
  }
  const std::string planar = testing::build_error(write(R"scene(
RigidBody2D { name = "plate"; mass = 1; inertia = 1 }
RotationalSpringDamper3D { body_a = "plate"; stiffness = 1 }
)scene",
                                                        2));
  EXPECT_NE(planar.find("m.scene:6:1: RotationalSpringDamper3D is a spatial (3D) element"),
            std::string::npos)
      << planar;
  const std::string help = render_help(scene_schema());
  EXPECT_NE(help.find("RotationalSpringDamper3D.axis"), std::string::npos);
  EXPECT_NE(help.find("NonlinearRotationalSpringDamper3D.torque"), std::string::npos);
}

TEST_F(SpatialScene, MistakesAreProblemsAtTheirPlace) {
  const std::string text = testing::build_error(write(R"scene(
RigidBody3D { name = "flat"; mass = 1; inertia = [1, 1, 2] }
AncfCable3D { name = "rope"; start = [0, 0, 0]; end = [1, 0, 0]; elements = 1
              axial_stiffness = 1; bending_stiffness = 1; mass_per_length = 1; radius = 0.1 }
RevoluteJoint3D { body_a = "rope" }
SphericalJoint { body_a = "nobody" }
Sensor { name = "p"; type = "position"; body = "rope"; component = "x" }
Sensor { name = "q"; type = "position"; body = "rope"; component = "angle" }
Sensor { name = "c"; type = "constraint_force"; body = "rope"; component = "x" }
RigidBody2D { name = "planar"; mass = 1; inertia = 1 }
Sensor { name = "off"; type = "position"; body = "rope"; point = [0.5, 0.1, 0]; component = "x" }
Sensor { name = "vt"; type = "velocity"; body = "flat"; component = "torque_x" }
RigidBody3D { name = "broken"; mass = 1; inertia = [1, 1, 1]; position = [1, 2] }
Sensor { name = "b"; type = "position"; body = "broken"; component = "x" }
Ground { Mesh { stl = "box.stl" } }
)scene"));
  for (const char* expected : {"m.scene:5:",
                               "less than the sum of the other two",
                               "m.scene:8:",
                               "not a rigid body",
                               "m.scene:9:",
                               "no body named 'nobody'",
                               "m.scene:10:",
                               "is an AncfCable3D",
                               "m.scene:11:",
                               "has components x, y or z",
                               "m.scene:12:",
                               "has no 3D form yet",
                               "m.scene:13:1: RigidBody2D is a planar (2D) element",
                               "spatial counterpart among",
                               "RigidBody3D",
                               "PrismaticJoint3D",
                               "NonlinearSpringDamper3D",
                               "m.scene:14:",
                               "off the centre line",
                               "m.scene:15:",
                               "a 3D velocity sensor has components x, y or z"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
  }
  // And the spatial blocks in a planar scene.
  const std::string planar = testing::build_error(write(R"scene(
PointMass { name = "m"; mass = 1 }
Ground { Mesh { points = [[0, 0], [1, 0]] } }
)scene",
                                                        2));
  EXPECT_NE(planar.find("m.scene:5:1: PointMass is a spatial (3D) element: it needs dimension = 3"),
            std::string::npos)
      << planar;
}

// Thesis Table 5.1's four refinement options of 3D triangles are the scene's choice; the session
// sends the choice with the mesh and the fix refines by it (sph_client's
// LiggghtsDriver.TheMeshRefinementOptionReachesTheFix).
TEST_F(SpatialScene, RefinementOptionIsTheScenesChoice) {
  const std::string ground = "Ground { Mesh { stl = \"box.stl\" } }\n";
  EXPECT_EQ(build_scene(write(ground).string()).boundary.refinement_option, 1) << "the default";
  for (int option = 0; option <= 3; ++option) {
    const Scene scene = build_scene(
        write(ground, 3,
              "refinement_resolution = 0.002; refinement_option = " + std::to_string(option))
            .string());
    EXPECT_EQ(scene.boundary.refinement_option, option);
  }
  const std::string beyond = testing::build_error(
      write(ground, 3, "refinement_resolution = 0.002; refinement_option = 4"));
  EXPECT_NE(beyond.find("m.scene:6:"), std::string::npos) << beyond;
  EXPECT_NE(beyond.find("refinement_option"), std::string::npos) << beyond;
  // 2D segments are bisected at every step: another option there is a mistake, said at its line.
  const std::string planar =
      testing::build_error(write("Ground { Mesh { points = [[0, 0], [1, 0]] } }\n", 2,
                                 "refinement_resolution = 0.002; refinement_option = 2"));
  EXPECT_NE(planar.find("m.scene:6:"), std::string::npos) << planar;
  EXPECT_NE(planar.find("refinement_option 2 is for 3D triangle meshes"), std::string::npos)
      << planar;
}

}  // namespace
}  // namespace fsi::scene
