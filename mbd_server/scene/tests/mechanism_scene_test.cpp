// Scene blocks of the 2D connectors, springs, time-dependent loads and their sensors: a scene
// with every block builds the expected model, its sensors read what the model says, and bad
// mechanisms (unknown names, bad expressions, redundant joints, a zero mass) are problems at
// their file:line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/static_analysis.hpp"
#include "fsi/scene/physics_checks.hpp"
#include "fsi/scene/scene.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

// A scene file of `body` plus what every scene needs, in a fresh folder.
class MechanismScene : public testing::FolderPerTest {
 protected:
  std::string write(const std::string& body) const {
    return write_coupled_scene(
               "m.scene", "SolverOptions { end_time = 1; Timeint { step_size = 1e-3 } }\n" + body)
        .string();
  }

  // The problems of a scene that must not build ("" if it builds).
  std::string problems(const std::string& body) const {
    return testing::message_thrown([&] { build_scene(write(body)); });
  }
};

const char* const kMechanism = R"scene(Gravity { acceleration = [0, -9.81] }
RigidBody2D { name = "frame"; mass = 2; inertia = 0.1; Mesh { points = [[0, 0], [1, 0]] } }
RigidBody2D { name = "slider"; mass = 1; inertia = 0.05 }
RigidBody2D { name = "lid"; mass = 0.5; inertia = 0.01; position = [0.2, 0.1] }
RigidBody2D { name = "flap"; mass = 0.3; inertia = 0.01; position = [0, 1] }
Clamp { name = "base"; body = "frame" }
PrismaticJoint { name = "rail"; body_a = "slider"; body_b = "frame"; axis = [1, 0] }
Clamp { name = "weld"; body = "lid"; to = "slider" }
RevoluteJoint { name = "hinge"; body_a = "flap"; point_b = [0, 1] }
RotationalSpringDamper { name = "coil"; body_a = "flap"; stiffness = 5; damping = 0.1; rest_angle = 0.2 }
NonlinearSpringDamper { name = "cubic"; body_a = "slider"; point_b = [-1, 0];
                        tension = "100*elongation + 1e4*elongation^3 + 2*rate"; rest_length = 0.8 }
SpringActor { name = "stop"; body_a = "slider"; point_b = [1, 0];
              characteristic = [[-0.1, -50], [0, 0], [0.1, 0]]; rest_length = 1 }
PointForce { name = "push"; body = "slider"; point = [0, 0.1]; force_x = "3*sin(t)"; force_y = "-t" }
Torque { name = "motor"; body = "flap"; torque = "0.5 + t" }
Sensor { name = "rail_normal"; type = "joint_force"; joint = "rail"; component = "y" }
Sensor { name = "rail_torque"; type = "joint_force"; joint = "rail"; component = "torque" }
Sensor { name = "hinge_x"; type = "joint_force"; joint = "hinge"; component = "x" }
Sensor { name = "coil_torque"; type = "spring_force"; element = "coil" }
Sensor { name = "cubic_tension"; type = "spring_force"; element = "cubic" }
Sensor { name = "stop_tension"; type = "spring_force"; element = "stop" }
Sensor { name = "kinetic"; type = "kinetic_energy" }
Sensor { name = "potential"; type = "potential_energy" }
)scene";

TEST_F(MechanismScene, EveryBlockBuildsAndItsSensorsReadTheModel) {
  Scene scene = build_scene(write(kMechanism));
  mbd::Model& model = scene.model;
  // Rows: base 3, rail 2, weld 3, hinge 2. Force elements: coil, cubic, stop, push, motor.
  EXPECT_EQ(model.constraint_count(), 10);
  EXPECT_EQ(model.force_element_count(), 5);
  ASSERT_EQ(scene.sensors.size(), 8u);
  EXPECT_EQ(scene.sensors[1].unit, "N m/m");
  EXPECT_EQ(scene.sensors[3].unit, "N m/m");
  EXPECT_EQ(scene.sensors[4].unit, "N/m");
  EXPECT_EQ(scene.sensors[6].unit, "J/m");
  mbd::State state = model.initial_state();
  // At t = 0: the cubic spring is stretched by 0.2 m: 100 * 0.2 + 1e4 * 0.008 = 100 N; the stop
  // is compressed by 0 m: 0 N; the coil twisted by -0.2 rad: torque 1 N m.
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[4], state), 100.0, 1e-9);
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[5], state), 0.0, 1e-12);
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[3], state), 1.0, 1e-12);
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[6], state), 0.0, 1e-15);
  // The rail carries the weight of the slider and the lid welded to it, 1.5 * 9.81 N/m; the flap
  // hangs at rest on its hinge at its centre of mass: no horizontal force.
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[0], state), 1.5 * 9.81, 1e-9);
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[2], state), 0.0, 1e-9);
  // Potential: gravity of the bodies above y = 0 (lid 0.5 * 9.81 * 0.1, flap 0.3 * 9.81 * 1), the
  // coil 5 * 0.04 / 2, the cubic spring 50 * 0.04 + 2500 * 0.0016.
  const double potential = 0.5 * 9.81 * 0.1 + 0.3 * 9.81 + 0.1 + 2.0 + 4.0;
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[7], state), potential, 1e-12);
  mbd::RadauIIA integrator(3);
  for (int n = 0; n < 50; ++n)
    integrator.step(model, state, 1e-3);
  for (const SensorSpec& sensor : scene.sensors) {
    EXPECT_TRUE(std::isfinite(structure_sensor_value(model, sensor, state))) << sensor.name;
  }
  // The slider stays on the rail and keeps its angle; the lid keeps its pose on the slider.
  const mbd::BodyId slider = model.find_body("slider");
  const mbd::BodyId lid = model.find_body("lid");
  EXPECT_NEAR(model.coordinate(state, slider, mbd::Coordinate::Y), 0.0, 1e-12);
  EXPECT_NEAR(model.coordinate(state, slider, mbd::Coordinate::Angle), 0.0, 1e-12);
  EXPECT_NEAR(model.coordinate(state, lid, mbd::Coordinate::X) -
                  model.coordinate(state, slider, mbd::Coordinate::X),
              0.2, 1e-12);
}

// A bar hinged at its left end and held level by a named CoordinateConstraint (a user's held gate,
// 2026-12-06: the constraint took no name, so its torque had no sensor): the hold carries the
// weight's moment m g L/2 about the hinge; the hinge none about its own point.
TEST_F(MechanismScene, AHeldBarsTorquesAboutItsHinge) {
  Scene scene = build_scene(write(R"scene(Gravity { acceleration = [0, -9.81] }
RigidBody2D { name = "bar"; mass = 2; inertia = 0.2; position = [0.5, 0]; Mesh { points = [[-0.5, 0], [0.5, 0]] } }
RevoluteJoint { name = "hinge"; body_a = "bar"; point_a = [-0.5, 0]; point_b = [0, 0] }
CoordinateConstraint { name = "hold"; body = "bar"; coordinate = "angle" }
Sensor { name = "hold_torque"; type = "joint_force"; joint = "hold"; component = "torque" }
Sensor { name = "hinge_torque"; type = "joint_force"; joint = "hinge"; component = "torque" }
Sensor { name = "hinge_own"; type = "joint_force"; joint = "hinge"; component = "torque"; about = [-0.5, 0] }
Sensor { name = "held_about_hinge"; type = "constraint_force"; body = "bar"; component = "torque"; about = [-0.5, 0] }
)scene"));
  const mbd::State state = scene.model.initial_state();
  const auto value = [&](std::size_t k) {
    return structure_sensor_value(scene.model, scene.sensors[k], state);
  };
  EXPECT_NEAR(value(0), 2 * 9.81 * 0.5, 1e-9);
  EXPECT_NEAR(value(1), -2 * 9.81 * 0.5, 1e-9);  // about the centre of mass
  EXPECT_NEAR(value(2), 0.0, 1e-9);
  EXPECT_NEAR(value(3), 2 * 9.81 * 0.5, 1e-9);
}

// A power take-off's absorbed power (a user's wave energy flap, 2026-12-06, integrated c omega^2
// by hand): the power sensor reads the rate of work of a named element on the bodies, Q . v.
TEST_F(MechanismScene, ADampersPowerIsMinusWhatItDissipates) {
  Scene scene = build_scene(write(R"scene(
RigidBody2D { name = "flap"; mass = 1; inertia = 0.5; angular_velocity = 2
              Mesh { points = [[0, 0], [0, 1]] } }
RigidBody2D { name = "slider"; mass = 1; inertia = 0.5; position = [2, 0]; velocity = [0.3, 0] }
RotationalSpringDamper { name = "pto"; body_a = "flap"; stiffness = 0; damping = 0.5 }
SpringDamper { name = "coil"; body_a = "slider"; point_b = [1, 0]; stiffness = 100; damping = 0 }
Sensor { name = "pto_torque"; type = "spring_force"; element = "pto" }
Sensor { name = "pto_power"; type = "power"; element = "pto" }
Sensor { name = "coil_power"; type = "power"; element = "coil" }
)scene"));
  const mbd::State state = scene.model.initial_state();
  const auto value = [&](std::size_t k) {
    return structure_sensor_value(scene.model, scene.sensors[k], state);
  };
  EXPECT_EQ(scene.sensors[0].unit, "N m/m");
  EXPECT_EQ(scene.sensors[1].unit, "W/m");
  EXPECT_NEAR(value(0), -0.5 * 2.0, 1e-12);
  EXPECT_NEAR(value(1), -0.5 * 2.0 * 2.0, 1e-12);
  // The spring at its rest length (the initial distance) does no work at this instant; stretched
  // by 0.1 m it pulls the slider back: -k e v = -100 * 0.1 * 0.3.
  EXPECT_NEAR(value(2), 0.0, 1e-12);
  mbd::State stretched = state;
  const mbd::BodyId slider = scene.model.find_body("slider");
  stretched.q(scene.model.coordinate_index(slider, mbd::Coordinate::X)) += 0.1;
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[2], stretched), -100.0 * 0.1 * 0.3,
              1e-9);
}

// A torsion spring with a user's law: a one-sided stop that pushes a flap back only once it has
// turned past its rest angle; the sensor reads the torque on body_a, the energy its integral.
TEST_F(MechanismScene, ANonlinearRotationalSpringDampersTorqueIsTheUsersLaw) {
  Scene scene = build_scene(write(R"scene(Geometry { k = 50 }
RigidBody2D { name = "flap"; mass = 0.3; inertia = 0.01; angle = 0.1
              Mesh { points = [[0, 0], [0.1, 0]] } }
RevoluteJoint { name = "hinge"; body_a = "flap" }
NonlinearRotationalSpringDamper { name = "stop"; body_a = "flap"; rest_angle = 0
    torque = "rotation > 0 ? Geometry.k*rotation^2*(1 + 2*rate) : 0" }
Sensor { name = "stop_torque"; type = "spring_force"; element = "stop" }
Sensor { name = "stop_power"; type = "power"; element = "stop" }
Sensor { name = "potential"; type = "potential_energy" }
)scene"));
  ASSERT_EQ(scene.sensors.size(), 3u);
  EXPECT_EQ(scene.sensors[0].unit, "N m/m");
  mbd::State state = scene.model.initial_state();
  const int angle =
      scene.model.coordinate_index(scene.model.find_body("flap"), mbd::Coordinate::Angle);
  state.v(angle) = 3.0;
  // Turned 0.1 rad past the stop at 3 rad/s: f = 50 * 0.01 * (1 + 2 * 3) = 3.5 N m; the torque on
  // the flap -3.5 N m, its power -3.5 * 3 W, the energy 50 * 0.1^3 / 3 (the law at zero rate).
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[0], state), -3.5, 1e-9);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[1], state), -10.5, 1e-8);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[2], state), 50.0 / 3.0 * 1e-3,
              1e-12);
  // Turned back before the stop: no torque.
  state.q(angle) = -0.1;
  EXPECT_EQ(structure_sensor_value(scene.model, scene.sensors[0], state), 0.0);
}

// Both user laws may name the time: a spring engaged at t = 0.5 s, a torsion spring whose rest
// angle turns (a servo), read at the state's time.
TEST_F(MechanismScene, SpringLawsMayDependOnTheTime) {
  Scene scene = build_scene(
      write(R"scene(RigidBody2D { name = "arm"; mass = 1; inertia = 0.1; position = [0.5, 0]
              Mesh { points = [[0, 0], [0.1, 0]] } }
RevoluteJoint { name = "hinge"; body_a = "arm"; point_a = [-0.5, 0]; point_b = [0, 0] }
NonlinearSpringDamper { name = "late"; body_a = "arm"; point_b = [0.5, -1]; rest_length = 0.5
                        tension = "t < 0.5 ? 0 : 200*elongation" }
NonlinearRotationalSpringDamper { name = "servo"; body_a = "arm"; rest_angle = 0
                                  torque = "20*(rotation - 0.3*sin(2*t))" }
Sensor { name = "late_tension"; type = "spring_force"; element = "late" }
Sensor { name = "servo_torque"; type = "spring_force"; element = "servo" }
Sensor { name = "potential"; type = "potential_energy" }
)scene"));
  mbd::State state = scene.model.initial_state();
  // The spring's points are 1 m apart: elongation 0.5 m.
  EXPECT_EQ(structure_sensor_value(scene.model, scene.sensors[0], state), 0.0);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[1], state), 0.0, 1e-15);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[2], state), 0.0, 1e-15);
  state.time = 0.75;
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[0], state), 100.0, 1e-9);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[1], state), 6.0 * std::sin(1.5),
              1e-9);
  // 200 * 0.5^2 / 2 and the integral of 20 (s - 0.3 sin 1.5) from 0 to 0 (no twist).
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[2], state), 25.0, 1e-9);
}

TEST_F(MechanismScene, ANonlinearRotationalSpringDampersMistakesAreProblemsAtTheirLines) {
  const std::string text = problems(
      R"scene(RigidBody2D { name = "flap"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
NonlinearRotationalSpringDamper { name = "a"; body_a = "flap"; torque = "5*angle" }
NonlinearRotationalSpringDamper { name = "b"; body_a = "flop"; torque = "5*rotation" }
NonlinearRotationalSpringDamper { name = "c"; body_a = "flap" }
)scene");
  EXPECT_NE(text.find("m.scene:4:"), std::string::npos) << text;  // angle is no variable
  EXPECT_NE(text.find("'angle'"), std::string::npos) << text;
  EXPECT_NE(text.find("m.scene:5:"), std::string::npos) << text;  // flop
  EXPECT_NE(text.find("m.scene:6:"), std::string::npos) << text;  // no torque
  EXPECT_NE(text.find("required parameter 'NonlinearRotationalSpringDamper[2].torque' is missing"),
            std::string::npos)
      << text;
  // Said once: the builder that reads the key does not report it again.
  EXPECT_EQ(text.find("is missing in block"), std::string::npos) << text;
  EXPECT_NE(text.find("3 problem(s)"), std::string::npos) << text;
}

// release_time belongs to constraint blocks; in a spring or a load it is an unknown key like any
// other (a user's fsi-server --check aborted on an assertion instead, 2026-12-06).
TEST_F(MechanismScene, AReleaseTimeOutsideAConstraintIsAnUnknownKey) {
  for (const std::string block :
       {"RotationalSpringDamper", "NonlinearSpringDamper", "SpringActor", "PointForce", "Torque"}) {
    std::string text = kMechanism;
    const std::size_t at = text.find(block + " { ");
    ASSERT_NE(at, std::string::npos) << block;
    text.insert(at + block.size() + 3, "release_time = 0.1; ");
    const std::string found = problems(text);
    EXPECT_NE(found.find("unknown parameter '" + block + ".release_time'"), std::string::npos)
        << block << ": " << found;
  }
}

TEST_F(MechanismScene, BadNamesAndExpressionsAreProblemsAtTheirLines) {
  const std::string text = problems(
      R"scene(RigidBody2D { name = "arm"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
PointForce { body = "arm"; force_x = "3*sin(time)" }
NonlinearSpringDamper { name = "s"; body_a = "arm"; point_b = [1, 1]; tension = "elongation +" }
Sensor { name = "a"; type = "spring_force"; element = "nothing" }
Sensor { name = "b"; type = "joint_force"; joint = "s" }
Sensor { name = "c"; type = "kinetic_energy"; body = "arm" }
RotationalSpringDamper { name = "s"; body_a = "arn"; stiffness = 1 }
)scene");
  EXPECT_NE(text.find("m.scene:4:"), std::string::npos) << text;  // force_x
  EXPECT_NE(text.find("3*sin(time)"), std::string::npos) << text;
  EXPECT_NE(text.find("m.scene:5:"), std::string::npos) << text;  // tension
  EXPECT_NE(text.find("no spring named 'nothing'"), std::string::npos) << text;
  EXPECT_NE(text.find("needs component"), std::string::npos) << text;
  EXPECT_NE(text.find("a kinetic_energy sensor takes no body"), std::string::npos) << text;
  EXPECT_NE(text.find("m.scene:9:"), std::string::npos) << text;  // body_a = "arn"
}

TEST_F(MechanismScene, ElementNamesAreUnique) {
  const std::string text = problems(
      R"scene(RigidBody2D { name = "arm"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
RevoluteJoint { name = "pin"; body_a = "arm" }
SpringDamper { name = "pin"; body_a = "arm"; point_b = [1, 1]; stiffness = 1 }
)scene");
  EXPECT_NE(text.find("m.scene:5:"), std::string::npos) << text;
  EXPECT_NE(text.find("a second element is named 'pin'"), std::string::npos) << text;
}

// A door clamped, pinned and held off its place: a redundant row and a residual.
const char* const kOverconstrainedDoor =
    R"scene(RigidBody2D { name = "door"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
Clamp { name = "frame"; body = "door" }
RevoluteJoint { name = "hinge"; body_a = "door" }
CoordinateConstraint { body = "door"; coordinate = "x"; value = 0.5 }
)scene";

TEST_F(MechanismScene, RedundantAndContradictoryJointsAreNamed) {
  const std::string text = problems(kOverconstrainedDoor);
  EXPECT_NE(text.find("revolute joint 'hinge' (x): redundant"), std::string::npos) << text;
  EXPECT_NE(text.find("coordinate constraint on door.x: position residual C = -0.5"),
            std::string::npos)
      << text;
}

// Issue 18: the engine finds a redundant or unsatisfied row; the scene names the block's line.
TEST_F(MechanismScene, RedundantJointIsAProblemAtItsLine) {
  const std::string text = problems(kOverconstrainedDoor);
  EXPECT_NE(text.find("m.scene:5:1: the initial state is inconsistent with the constraints: "
                      "revolute joint 'hinge' (x): redundant"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("m.scene:6:1: the initial state is inconsistent with the constraints: "
                      "coordinate constraint on door.x: position residual C = -0.5"),
            std::string::npos)
      << text;
}

TEST_F(MechanismScene, ZeroMassIsAProblemAtItsLine) {
  const std::string text = problems(
      "RigidBody2D { name = \"wheel\"; mass = 0; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } "
      "}\n");
  EXPECT_NE(text.find("m.scene:3:"), std::string::npos) << text;
  EXPECT_NE(text.find("'RigidBody2D.mass' = 0 kg/m is out of range"), std::string::npos) << text;
}

TEST_F(MechanismScene, PrescribedMotionsDriveCoordinatesAndAWrongRateIsAProblem) {
  const Scene scene =
      build_scene(write(R"scene(RigidBody2D { name = "table"; mass = 2; inertia = 0.1
              velocity = [0.2, 0]; Mesh { points = [[0, 0], [1, 0]] } }
RigidBody2D { name = "lift"; mass = 1; inertia = 0.1; position = [0, 1] }
PrescribedMotion { name = "shaker"; body = "table"; coordinate = "x"
                   position = "0.01*sin(20*t)"; rate = "0.2*cos(20*t)" }
CoordinateConstraint { body = "table"; coordinate = "y" }
CoordinateConstraint { body = "table"; coordinate = "angle" }
PrescribedVelocity { name = "ramp"; body = "lift"; coordinate = "y"; velocity = "0.1*t" }
CoordinateConstraint { body = "lift"; coordinate = "x" }
CoordinateConstraint { body = "lift"; coordinate = "angle" }
Sensor { name = "drive"; type = "joint_force"; joint = "shaker"; component = "x" }
)scene"));
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  mbd::State state = scene.model.initial_state();
  for (int i = 0; i < 100; ++i)
    integrator.step(scene.model, state, 1e-3);
  EXPECT_NEAR(state.q(0), 0.01 * std::sin(20.0 * 0.1), 1e-12);
  EXPECT_NEAR(state.q(4), 1.0 + 0.05 * 0.1 * 0.1, 1e-12);
  // The drive's force on the table is m x'' = -2 * 4 sin(20 t).
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[0], state),
              -8.0 * std::sin(20.0 * 0.1), 1e-3);
  const std::string text = problems(R"scene(RigidBody2D { name = "table"; mass = 2; inertia = 0.1
              Mesh { points = [[0, 0], [1, 0]] } }
PrescribedMotion { name = "turn"; body = "table"; coordinate = "angle"; position = "0.3*t^2"; rate = "0.3*t" }
Sensor { name = "torque"; type = "joint_force"; joint = "turn"; component = "torque" }
)scene");
  EXPECT_NE(text.find("m.scene:5:1:"), std::string::npos) << text;
  EXPECT_NE(text.find("is not the derivative of the position"), std::string::npos) << text;
  // A rate wrong only for 0.51 < t < 0.59 s of a 1 s run, between the tenths once sampled (a
  // user's index-2 spin-up went wrong unseen when 11 samples missed such a window), is found.
  const std::string window = problems(R"scene(RigidBody2D { name = "table"; mass = 2; inertia = 0.1
              Mesh { points = [[0, 0], [1, 0]] } }
PrescribedMotion { name = "turn"; body = "table"; coordinate = "angle"; position = "0.3*t^2"
                   rate = "t > 0.51 && t < 0.59 ? 1.2*t : 0.6*t" }
)scene");
  EXPECT_NE(window.find("is not the derivative of the position"), std::string::npos) << window;
  // The sensor on the refused drive is skipped, not told that no joint has its name (a user's
  // slider crank, 2026-12-06).
  EXPECT_EQ(text.find("no joint named"), std::string::npos) << text;
  EXPECT_NE(text.find("1 problem(s)"), std::string::npos) << text;
  // A drive whose name itself is in error: its problem is reported, the scene's others too.
  const std::string unnamed = problems(R"scene(RigidBody2D { name = "table"; mass = 2; inertia = 0.1
              Mesh { points = [[0, 0], [1, 0]] } }
PrescribedMotion { name = 5; body = "table"; coordinate = "angle"; position = "0.3*t^2"; rate = "0.3*t" }
)scene");
  EXPECT_NE(unnamed.find("m.scene:5:"), std::string::npos) << unnamed;
}

// A runtime expression names the scene's numbers by their path, so a drive follows the parameter
// it is written from, also when --set changes it (the pump's piston and its Geometry.T).
TEST_F(MechanismScene, ExpressionsNameTheScenesNumbersAndFollowTheirOverrides) {
  const std::string path = write(R"scene(Geometry { A = 0.01; T = 0.5; k = 200 }
RigidBody2D { name = "table"; mass = 2; inertia = 0.1; Mesh { points = [[0, 0], [1, 0]] } }
RigidBody2D { name = "bob"; mass = 1; inertia = 0.1; position = [0, 1.1] }
PrescribedMotion { name = "shaker"; body = "table"; coordinate = "x"
                   position = "Geometry.A*(1 - cos(2*pi*t/Geometry.T))"
                   rate = "Geometry.A*2*pi/Geometry.T*sin(2*pi*t/Geometry.T)" }
CoordinateConstraint { body = "table"; coordinate = "y" }
CoordinateConstraint { body = "table"; coordinate = "angle" }
NonlinearSpringDamper { name = "spring"; body_a = "bob"; point_b = [0, 0]; rest_length = 1
                        tension = "Geometry.k*elongation + RigidBody2D[1].mass*rate" }
CoordinateConstraint { body = "bob"; coordinate = "x" }
CoordinateConstraint { body = "bob"; coordinate = "angle" }
)scene");
  for (const double period : {0.5, 0.2}) {
    const double k = period == 0.5 ? 200.0 : 300.0;
    const Scene scene =
        period == 0.5
            ? build_scene(path)
            : build_scene(path, {Override{"Geometry.T", "0.2"}, Override{"Geometry.k", "300"}});
    mbd::RadauIIA integrator(scene.solver.integrator_options());
    mbd::State state = scene.model.initial_state();
    for (int i = 0; i < 100; ++i)
      integrator.step(scene.model, state, 1e-3);
    EXPECT_NEAR(state.q(0), 0.01 * (1.0 - std::cos(2.0 * std::numbers::pi * 0.1 / period)), 1e-12)
        << "T = " << period;
    // The bob (m = 1 kg, no gravity) on the spring, e = y - 1 from 0.1 at rest: e'' + c e' + k e
    // = 0 with c = RigidBody2D[1].mass = 1 N s/m, underdamped.
    const double c = 1.0, t = 0.1, decay = 0.5 * c, omega = std::sqrt(k - decay * decay);
    const double e =
        0.1 * std::exp(-decay * t) * (std::cos(omega * t) + decay / omega * std::sin(omega * t));
    EXPECT_NEAR(state.q(4) - 1.0, e, 1e-7) << "k = " << k;
  }
}

TEST_F(MechanismScene, AnExpressionsNameThatIsNoNumberOfTheSceneIsAProblemAtItsLine) {
  const std::string text = problems(R"scene(Geometry { A = 0.01; P = [1, 2] }
RigidBody2D { name = "arm"; mass = 1; inertia = 1; Mesh { points = [[0, 0], [1, 0]] } }
PointForce { body = "arm"; force_x = "Geometry.AA*t" }
Torque { body = "arm"; torque = "Geometry.P*t" }
PointForce { body = "arm"; force_y = "RigidBody2D[0].name + t" }
RigidBody2D { name = "leg"; mass = 2; inertia = 1 }
Torque { body = "leg"; torque = "RigidBody2D.mass*t" }
)scene");
  EXPECT_NE(text.find("m.scene:5:"), std::string::npos) << text;
  EXPECT_NE(text.find("'Geometry.AA' is neither one of its variables nor a number of the scene "
                      "(did you mean 'Geometry.A'?)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("Geometry.T)"), std::string::npos) << text;  // the how names a path
  EXPECT_NE(text.find("m.scene:6:"), std::string::npos) << text;
  EXPECT_NE(text.find("'Geometry.P' is a vector: arithmetic needs numbers"), std::string::npos)
      << text;
  EXPECT_NE(text.find("m.scene:7:"), std::string::npos) << text;
  EXPECT_NE(text.find("'RigidBody2D[0].name' is a string"), std::string::npos) << text;
  EXPECT_NE(text.find("m.scene:9:"), std::string::npos) << text;
  EXPECT_NE(text.find("'RigidBody2D' in 'RigidBody2D.mass' is a list of 2 blocks: pick one, "
                      "RigidBody2D[0] ... RigidBody2D[1]"),
            std::string::npos)
      << text;
}

TEST_F(MechanismScene, TheIndexTwoFormIsChosenInTimeint) {
  const Scene scene = build_scene(write(R"scene(SolverOptions.Timeint.constraint_form = "index2"
RigidBody2D { name = "bob"; mass = 1; inertia = 0.1; position = [1, 0]
              Mesh { points = [[0, 0], [0.1, 0]] } }
DistanceConstraint { body_a = "bob" }
)scene"));
  EXPECT_EQ(scene.solver.constraint_form, mbd::ConstraintForm::Index2);
  EXPECT_EQ(scene.solver.integrator_options().constraint_form, mbd::ConstraintForm::Index2);
  EXPECT_EQ(scene.solver.integrator_description(), "Radau IIA, 3 stages, index-2 constraints");
}

// A beam's thickness places its surface mesh: the structure alone (--mbd-only) needs none, a
// coupled run is told to give it (or to say the fluid does not see the beam).
TEST_F(MechanismScene, ABeamNeedsAThicknessOnlyForTheFluid) {
  const std::string rod =
      "AncfBeam2D { name = \"rod\"; start = [0, 0]; end = [1, 0]; elements = 4\n"
      "             axial_stiffness = 1e7; bending_stiffness = 1e3; mass_per_length = 0.5 }\n"
      "BeamClamp { beam = \"rod\"; node = 0 }\n";
  const Scene alone = build_scene(write(rod), {}, SceneMode::MbdOnly);
  EXPECT_EQ(alone.model.body_count(), 1);
  EXPECT_TRUE(alone.boundary.segments.empty());
  EXPECT_NE(problems(rod).find("m.scene:3:1: AncfBeam2D 'rod' has no thickness: a coupled run "
                               "needs it for the beam's surface mesh (its faces at eta = "
                               "+-thickness/2), which the fluid sees; give thickness = h, or "
                               "face_points_per_element = 0 for a beam the fluid does not touch"),
            std::string::npos)
      << problems(rod);
  EXPECT_EQ(problems(rod).find("no surface mesh"), std::string::npos) << problems(rod);
}

// chord_deflection: a beam point's distance from the chord through the beam's end nodes, the
// same whatever rigid motion carries the bent beam; refused on a rigid body.
TEST_F(MechanismScene, ChordDeflectionIgnoresTheBeamsRigidMotion) {
  const std::string rod =
      "AncfBeam2D { name = \"rod\"; start = [0, 0]; end = [1, 0]; elements = 2; thickness = 0.01\n"
      "             axial_stiffness = 1e7; bending_stiffness = 1e3; mass_per_length = 0.5 }\n"
      "Sensor { name = \"bow\"; type = \"chord_deflection\"; body = \"rod\"; point = [0.5, 0] }\n";
  const Scene scene = build_scene(write(rod), {}, SceneMode::MbdOnly);
  const mbd::Model& model = scene.model;
  const mbd::BodyId beam = model.find_body("rod");
  ASSERT_EQ(scene.sensors.size(), 1u);
  EXPECT_EQ(scene.sensors[0].unit, "m");
  mbd::State state = model.initial_state();
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[0], state), 0.0, 1e-15);
  // Bow the middle node (the centre line at s = 0.5) by 0.1 to the left of start -> end, then
  // turn the whole beam by 0.7 rad about [0.3, -0.2].
  auto index = [&](int node, mbd::BeamNodeCoordinate c) {
    return model.beam_coordinate_index(beam, node, c);
  };
  state.q(index(1, mbd::BeamNodeCoordinate::Y)) = 0.1;
  const Eigen::Rotation2Dd turn(0.7);
  const Eigen::Vector2d centre(0.3, -0.2);
  for (int node = 0; node < 3; ++node) {
    const int x = index(node, mbd::BeamNodeCoordinate::X);
    const int sx = index(node, mbd::BeamNodeCoordinate::SlopeX);
    const Eigen::Vector2d r =
        centre + turn * (Eigen::Vector2d(state.q(x), state.q(x + 1)) - centre);
    const Eigen::Vector2d slope = turn * Eigen::Vector2d(state.q(sx), state.q(sx + 1));
    state.q.segment<2>(x) = r;
    state.q.segment<2>(sx) = slope;
  }
  EXPECT_NEAR(structure_sensor_value(model, scene.sensors[0], state), 0.1, 1e-14);
  EXPECT_NE(
      problems("RigidBody2D { name = \"bar\"; mass = 1; inertia = 1; Mesh { points = [[0, 0], "
               "[1, 0]] } }\nSensor { name = \"bow\"; type = \"chord_deflection\"; body = "
               "\"bar\"; point = [0.5, 0] }\n")
          .find("a chord_deflection sensor reads an AncfBeam2D, and 'bar' is a rigid_body_2d"),
      std::string::npos);
}

// frame: a position or velocity read in the axes of a moving rigid body (a baffle's tip in a
// rolling tank, a beam's tip in a spinning hub: two users had to rotate the world's values by
// hand). Checked against the definitions at an arbitrary state: d = p - r_f, R(phi_f)^T d,
// R^T (v - v_f - omega_f x d), angles less the frame's.
TEST_F(MechanismScene, ASensorReadsAPointInTheAxesOfAMovingBody) {
  const std::string scene = R"scene(
RigidBody2D { name = "tank"; mass = 2; inertia = 0.1; position = [1, 2] }
RigidBody2D { name = "bob"; mass = 1; inertia = 0.05; position = [1.5, 2.5] }
AncfBeam2D { name = "rod"; start = [1, 2]; end = [2, 2]; elements = 2; thickness = 0.01
             axial_stiffness = 1e7; bending_stiffness = 1e3; mass_per_length = 0.5 }
Sensor { name = "px"; type = "position"; body = "bob"; point = [0.1, 0.2]; component = "x"; frame = "tank" }
Sensor { name = "py"; type = "position"; body = "bob"; point = [0.1, 0.2]; component = "y"; frame = "tank" }
Sensor { name = "vx"; type = "velocity"; body = "bob"; point = [0.1, 0.2]; component = "x"; frame = "tank" }
Sensor { name = "vy"; type = "velocity"; body = "bob"; point = [0.1, 0.2]; component = "y"; frame = "tank" }
Sensor { name = "turn"; type = "position"; body = "bob"; component = "angle"; frame = "tank" }
Sensor { name = "spin"; type = "velocity"; body = "bob"; component = "angle"; frame = "tank" }
Sensor { name = "tip"; type = "position"; body = "rod"; point = [1, 0]; component = "y"; frame = "tank" }
)scene";
  const Scene built = build_scene(write(scene), {}, SceneMode::MbdOnly);
  const mbd::Model& model = built.model;
  ASSERT_EQ(built.sensors.size(), 7u);
  mbd::State state = model.initial_state();
  const mbd::BodyId tank = model.find_body("tank"), bob = model.find_body("bob");
  using C = mbd::Coordinate;
  auto set = [&](mbd::BodyId b, C c, double q, double v) {
    state.q(model.coordinate_index(b, c)) = q;
    state.v(model.coordinate_index(b, c)) = v;
  };
  set(tank, C::X, 0.3, 0.7);
  set(tank, C::Y, -0.4, -0.2);
  set(tank, C::Angle, 0.9, 1.3);
  set(bob, C::X, 1.1, -0.5);
  set(bob, C::Y, 0.6, 0.4);
  set(bob, C::Angle, -0.35, 2.1);
  const Eigen::Vector2d local(0.1, 0.2);
  const Eigen::Vector2d p = Eigen::Vector2d(1.1, 0.6) + Eigen::Rotation2Dd(-0.35) * local;
  const Eigen::Vector2d arm = Eigen::Rotation2Dd(-0.35) * local;
  const Eigen::Vector2d v = Eigen::Vector2d(-0.5, 0.4) + 2.1 * Eigen::Vector2d(-arm.y(), arm.x());
  const Eigen::Vector2d d = p - Eigen::Vector2d(0.3, -0.4);
  const Eigen::Vector2d in_tank = Eigen::Rotation2Dd(-0.9) * d;
  const Eigen::Vector2d rate = Eigen::Rotation2Dd(-0.9) * (v - Eigen::Vector2d(0.7, -0.2) -
                                                           1.3 * Eigen::Vector2d(-d.y(), d.x()));
  auto value = [&](int k) { return structure_sensor_value(model, built.sensors[k], state); };
  EXPECT_NEAR(value(0), in_tank.x(), 1e-14);
  EXPECT_NEAR(value(1), in_tank.y(), 1e-14);
  EXPECT_NEAR(value(2), rate.x(), 1e-14);
  EXPECT_NEAR(value(3), rate.y(), 1e-14);
  EXPECT_NEAR(value(4), -0.35 - 0.9, 1e-15);
  EXPECT_NEAR(value(5), 2.1 - 1.3, 1e-15);
  // The rate is the derivative of the position: a step of 1e-6 s along v.
  mbd::State later = state;
  later.q += 1e-6 * state.v;
  const double moved = structure_sensor_value(model, built.sensors[0], later) - value(0);
  EXPECT_NEAR(moved / 1e-6, value(2), 1e-5);
  // A beam's tip (undeformed: on the tank's x axis at the start) in the tank's axes.
  EXPECT_NEAR(structure_sensor_value(model, built.sensors[6], model.initial_state()), 0.0, 1e-14);
  // Refused: a beam as frame, a frame on a force sensor, a body's own centre.
  const std::string wrong = problems(
      "RigidBody2D { name = \"tank\"; mass = 2; inertia = 0.1; Mesh { points = [[0, 0], [1, 0]] } "
      "}\n"
      "AncfBeam2D { name = \"rod\"; start = [0, 0]; end = [1, 0]; elements = 2; thickness = 0.01\n"
      "  axial_stiffness = 1e7; bending_stiffness = 1e3; mass_per_length = 0.5 }\n"
      "Sensor { name = \"a\"; type = \"position\"; body = \"tank\"; component = \"x\"; frame = "
      "\"rod\" }\n"
      "Sensor { name = \"b\"; type = \"fluid_force\"; body = \"tank\"; component = \"x\"; frame = "
      "\"tank\" }\n"
      "Sensor { name = \"c\"; type = \"position\"; body = \"tank\"; component = \"x\"; frame = "
      "\"tank\" }\n");
  EXPECT_NE(wrong.find("frame 'rod' is an AncfBeam2D; a frame is a RigidBody2D"), std::string::npos)
      << wrong;
  EXPECT_NE(wrong.find("frame is for position and velocity sensors of 2D scenes, not a "
                       "fluid_force sensor"),
            std::string::npos)
      << wrong;
  EXPECT_NE(wrong.find("a body's centre of mass in its own frame does not move"), std::string::npos)
      << wrong;
}

// A beam stiff in tension spun up by its hub (Simo & Vu-Quoc's spin-up, 2026-12-06 trial): at a
// large step the beam turns so far within the step that no Newton matrix held through it
// converges; the step is then taken in full Newton, not failed (the caller used to split 275 of
// 300 such steps into substeps, dearer than full Newton). With the full-Newton rescue removed
// from RadauIIA::step_without_release, step() throws here.
TEST_F(MechanismScene, ASpinningStiffBeamTakesLargeStepsWhole) {
  const std::string spin = R"scene(
RigidBody2D { name = "hub"; mass = 1; inertia = 1 }
RevoluteJoint { body_a = "hub" }
PrescribedMotion { name = "drive"; body = "hub"; coordinate = "angle"
  position = "6/15*(t^2/2 + (15/(2*pi))^2*(cos(2*pi*t/15) - 1))"
  rate = "6/15*(t - 15/(2*pi)*sin(2*pi*t/15))" }
AncfBeam2D { name = "beam"; start = [0, 0]; end = [10, 0]; elements = 8
             axial_stiffness = 2.8e7; bending_stiffness = 1.4e4; mass_per_length = 1.2 }
BeamClamp { beam = "beam"; node = 0; to = "hub" }
)scene";
  const Scene scene = build_scene(write(spin), {}, SceneMode::MbdOnly);
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  mbd::State state = scene.model.initial_state();
  for (int step = 0; step < 80; ++step)  // to t = 8 s, past the deepest dip (6.8 s)
    ASSERT_NO_THROW(integrator.step(scene.model, state, 0.1)) << "t = " << state.time;
  EXPECT_NEAR(state.time, 8.0, 1e-12);
}

// IDA and adaptive Radau on an undamped beam: told before the run that their steps stay tiny
// (a user's spin-up: IDA 2.3 million steps, 284 s, against 1 500 fixed steps, 5 s).
TEST_F(MechanismScene, AnErrorControlledMethodOnAnUndampedBeamIsWarned) {
  auto check = [&](const std::string& method, const std::string& damping) {
    const std::string text =
        "SolverOptions { end_time = 1; Timeint { step_size = 1e-3; method = \"" + method +
        "\" } }\nAncfBeam2D { name = \"rod\"; start = [0, 0]; end = [1, 0]; elements = 2\n"
        "  axial_stiffness = 1e7; bending_stiffness = 1e3; mass_per_length = 0.5" +
        damping + " }\nBeamClamp { beam = \"rod\"; node = 0 }\n";
    std::ofstream(folder_ / "i.scene") << "scene_language = 1\n" << text;
    return integrator_check(build_scene((folder_ / "i.scene").string(), {}, SceneMode::MbdOnly));
  };
  const std::vector<Diagnostic> ida = check("ida", "");
  ASSERT_EQ(ida.size(), 1u);
  EXPECT_EQ(ida[0].check, "integration_method");
  EXPECT_NE(ida[0].message.find("SUNDIALS IDA follows every mode of the undamped beam(s) 'rod'"),
            std::string::npos)
      << ida[0].message;
  EXPECT_NE(ida[0].fix.find("use method = \"fixed\""), std::string::npos);
  EXPECT_EQ(check("adaptive", "").size(), 1u);
  EXPECT_TRUE(check("fixed", "").empty());
  EXPECT_TRUE(check("ida", "; bending_damping = 10; axial_damping = 1e4").empty());
}

TEST_F(MechanismScene, ABeamClampedToABodyTurnsWithIt) {
  const char* const blade = R"scene(
AncfBeam2D { name = "blade"; start = [0, 0]; end = [1, 0]; elements = 4; thickness = 0.01
             axial_stiffness = 1e7; bending_stiffness = 1e3; mass_per_length = 0.5 }
BeamClamp { beam = "blade"; to = "hub"; slope = "full" }
RevoluteJoint { body_a = "hub" }
)scene";
  const Scene scene =
      build_scene(write(std::string(R"scene(RigidBody2D { name = "hub"; mass = 1; inertia = 0.1
              Mesh { points = [[0, 0], [0.1, 0]] } }
Torque { body = "hub"; torque = "0.5" })scene") +
                        blade));
  const mbd::Model& model = scene.model;
  EXPECT_EQ(model.constraint_count(), 4 + 2);
  EXPECT_NE(model.constraint_description(0).find("to 'hub'"), std::string::npos);
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  mbd::State state = model.initial_state();
  for (int i = 0; i < 200; ++i)
    integrator.step(model, state, 1e-3);
  const double hub = model.coordinate(state, 0, mbd::Coordinate::Angle);
  const int sx = model.beam_coordinate_index(1, 0, mbd::BeamNodeCoordinate::SlopeX);
  const double root = std::atan2(state.q(sx + 1), state.q(sx));
  EXPECT_GT(hub, 0.01);
  EXPECT_NEAR(root, hub, 1e-10);
  // A hub that turns while the blade is at rest: the clamp's rate is named.
  const std::string text =
      problems(std::string(R"scene(RigidBody2D { name = "hub"; mass = 1; inertia = 0.1
              angular_velocity = 2; Mesh { points = [[0, 0], [0.1, 0]] } })scene") +
               blade);
  EXPECT_NE(text.find("beam clamp on blade node 0 to 'hub'"), std::string::npos) << text;
  EXPECT_NE(text.find("velocity residual"), std::string::npos) << text;
}

TEST_F(MechanismScene, ANamedBeamClampReadsTheForceAndTheMomentItHoldsTheBeamWith) {
  // A stiff horizontal cantilever under its own weight (mu g = 4.905 N/m over L = 1 m): the
  // clamp holds it with mu g L = 4.905 N/m upwards and mu g L^2 / 2 = 2.4525 N m/m
  // counter-clockwise about its node (the weight's moment about the clamp, the other way).
  Scene scene = build_scene(write(R"scene(Gravity { acceleration = [0, -9.81] }
AncfBeam2D { name = "arm"; start = [0, 0]; end = [1, 0]; elements = 4; thickness = 0.01
             axial_stiffness = 1e9; bending_stiffness = 1e6; mass_per_length = 0.5 }
BeamClamp { name = "root"; beam = "arm"; node = 0 }
Sensor { name = "root_x"; type = "joint_force"; joint = "root"; component = "x" }
Sensor { name = "root_y"; type = "joint_force"; joint = "root"; component = "y" }
Sensor { name = "root_moment"; type = "joint_force"; joint = "root"; component = "torque" }
)scene"));
  ASSERT_EQ(scene.sensors.size(), 3u);
  EXPECT_EQ(scene.sensors[2].unit, "N m/m");
  const mbd::StaticResult result = mbd::solve_static(scene.model, scene.model.initial_state());
  const double weight = 0.5 * 9.81;
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[0], result.state), 0.0, 1e-9);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[1], result.state), weight, 1e-9);
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[2], result.state), 0.5 * weight,
              1e-9);
}

TEST_F(MechanismScene, ABeamPointReadsItsCrossSectionsAngle) {
  // A cantilever under its own weight w = mu g: theta(x) = -w (x^3 - 3 L x^2 + 3 L^2 x) / (6 EI)
  // (small deflection; cubic elements give the nodal slopes exactly): 0 at the clamp, -w L^3 /
  // (6 EI) at the tip, 7/8 of it at mid-span. A rigid body's point still has no angle.
  Scene scene = build_scene(write(R"scene(Gravity { acceleration = [0, -9.81] }
AncfBeam2D { name = "arm"; start = [0, 0]; end = [1, 0]; elements = 4; thickness = 0.01
             axial_stiffness = 1e9; bending_stiffness = 1e3; mass_per_length = 0.5 }
BeamClamp { name = "root"; beam = "arm"; node = 0 }
Sensor { name = "root_angle"; type = "position"; body = "arm"; point = [0, 0]; component = "angle" }
Sensor { name = "mid_angle"; type = "position"; body = "arm"; point = [0.5, 0]; component = "angle" }
Sensor { name = "tip_angle"; type = "position"; body = "arm"; point = [1, 0]; component = "angle" }
Sensor { name = "tip_turn"; type = "velocity"; body = "arm"; point = [1, 0]; component = "angle" }
)scene"));
  ASSERT_EQ(scene.sensors.size(), 4u);
  EXPECT_EQ(scene.sensors[2].unit, "rad");
  const mbd::StaticResult result = mbd::solve_static(scene.model, scene.model.initial_state());
  const auto value = [&](int k) {
    return structure_sensor_value(scene.model, scene.sensors[k], result.state);
  };
  const double tip = -0.5 * 9.81 / (6.0 * 1e3);
  EXPECT_NEAR(value(0), 0.0, 1e-12);
  EXPECT_NEAR(value(1), 0.875 * tip, 1e-3 * std::abs(tip));
  EXPECT_NEAR(value(2), tip, 1e-3 * std::abs(tip));
  EXPECT_EQ(value(3), 0.0);  // at rest
  const std::string text = problems(R"scene(
RigidBody2D { name = "lid"; mass = 1; inertia = 1 }
Sensor { name = "corner"; type = "position"; body = "lid"; point = [0.1, 0]; component = "angle" }
)scene");
  EXPECT_NE(text.find("a point of a rigid body has components x and y, no angle of its own"),
            std::string::npos)
      << text;
}

TEST_F(MechanismScene, APinOnABeamReadsItsShareOfAStaticallyIndeterminateLoad) {
  // A propped cantilever: clamped at x = 0, pinned at x = L, under its own weight w = mu g. The
  // beam theory shares the load 5/8 : 3/8 and the clamp holds the moment w L^2 / 8 (not the
  // cantilever's w L^2 / 2): the pin's share is what the structure's stiffness decides, and a
  // pin holds no moment about its own point. Cubic ANCF elements give the nodal values of the
  // Euler-Bernoulli solution exactly; the stiff beam keeps the deflection linear.
  Scene scene = build_scene(write(R"scene(Gravity { acceleration = [0, -9.81] }
AncfBeam2D { name = "arm"; start = [0, 0]; end = [1, 0]; elements = 4; thickness = 0.01
             axial_stiffness = 1e9; bending_stiffness = 1e6; mass_per_length = 0.5 }
BeamClamp { name = "root"; beam = "arm"; node = 0 }
RevoluteJoint { name = "prop"; body_a = "arm"; point_a = [1, 0]; point_b = [1, 0] }
Sensor { name = "root_y"; type = "joint_force"; joint = "root"; component = "y" }
Sensor { name = "root_moment"; type = "joint_force"; joint = "root"; component = "torque" }
Sensor { name = "prop_x"; type = "joint_force"; joint = "prop"; component = "x" }
Sensor { name = "prop_y"; type = "joint_force"; joint = "prop"; component = "y" }
Sensor { name = "prop_moment"; type = "joint_force"; joint = "prop"; component = "torque" }
)scene"));
  ASSERT_EQ(scene.sensors.size(), 5u);
  const mbd::StaticResult result = mbd::solve_static(scene.model, scene.model.initial_state());
  const auto value = [&](int k) {
    return structure_sensor_value(scene.model, scene.sensors[k], result.state);
  };
  const double weight = 0.5 * 9.81;
  EXPECT_NEAR(value(0), 5.0 / 8.0 * weight, 1e-6 * weight);
  EXPECT_NEAR(value(1), weight / 8.0, 1e-6 * weight);
  EXPECT_NEAR(value(2), 0.0, 1e-6 * weight);  // the sag's axial tension: ~ EA (w')^2
  EXPECT_NEAR(value(3), 3.0 / 8.0 * weight, 1e-6 * weight);
  EXPECT_NEAR(value(4), 0.0, 1e-9 * weight);
}

// The strain energy of a loaded beam at rest is half the work of its loads (Clapeyron): for the
// beam under its weight, starting at y = 0, half the gravity potential it lost.
TEST_F(MechanismScene, ABeamsStrainEnergyIsHalfTheWorkOfItsLoadsAtRest) {
  Scene scene = build_scene(write(R"scene(Gravity { acceleration = [0, -9.81] }
AncfBeam2D { name = "arm"; start = [0, 0]; end = [1, 0]; elements = 4; thickness = 0.01
             axial_stiffness = 1e5; bending_stiffness = 100; mass_per_length = 0.5 }
BeamClamp { name = "root"; beam = "arm"; node = 0 }
RevoluteJoint { name = "prop"; body_a = "arm"; point_a = [1, 0]; point_b = [1, 0] }
Sensor { name = "gravity"; type = "potential_energy" }
Sensor { name = "strain"; type = "strain_energy" }
)scene"));
  ASSERT_EQ(scene.sensors.size(), 2u);
  EXPECT_EQ(scene.sensors[1].unit, "J/m");
  const mbd::State start = scene.model.initial_state();
  EXPECT_NEAR(structure_sensor_value(scene.model, scene.sensors[1], start), 0.0, 1e-20);
  const mbd::StaticResult result = mbd::solve_static(scene.model, start);
  const double potential = structure_sensor_value(scene.model, scene.sensors[0], result.state);
  const double strain = structure_sensor_value(scene.model, scene.sensors[1], result.state);
  // The propped cantilever's sag: w^2 L^5 / (640 EI) of strain energy (beam theory; four cubic
  // elements of the quartic deflection hold a little less). EA L^2 / EI = 1e3: at 1e5 the
  // elements lock membrane-wise by 0.3 %, at 1e7 by 10 % (docs/validation.md, the elastica).
  const double w = 0.5 * 9.81;
  EXPECT_NEAR(strain, w * w / (640.0 * 100.0), 5e-3 * strain);
  EXPECT_NEAR(strain, -0.5 * potential, 1e-4 * strain);
}

// A beam that the Assembly block has to set moving (its end pinned to a crank that starts
// turning) gets the velocity of least kinetic energy, not a rigid motion: warned at the block
// with the fix (start at rest, spin up). A crank that starts at rest is not warned.
TEST_F(MechanismScene, AnAssembledBeamVelocityIsWarnedAsAStrike) {
  const auto scene_with = [&](const std::string& rate) {
    return build_scene(write(R"scene(RigidBody2D { name = "crank"; mass = 1; inertia = 0.01
             position = [0, 0]; angular_velocity = )scene" +
                             rate + R"scene( }
RevoluteJoint { name = "pivot"; body_a = "crank"; point_b = [0, 0] }
PrescribedMotion { name = "drive"; body = "crank"; coordinate = "angle"
                   position = ")scene" +
                             rate + R"scene(*t"; rate = ")scene" + rate + R"scene(" }
AncfBeam2D { name = "rod"; start = [0.15, 0]; end = [0.45, 0]; elements = 4; thickness = 0.008
             axial_stiffness = 1e7; bending_stiffness = 70; mass_per_length = 0.5 }
RevoluteJoint { name = "pin"; body_a = "rod"; point_a = [0, 0]; body_b = "crank"; point_b = [0.15, 0] }
Assembly { }
)scene"));
  };
  const std::vector<Diagnostic> struck = integrator_check(scene_with("150"));
  ASSERT_EQ(struck.size(), 1u);
  EXPECT_EQ(struck.front().check, "assembly_velocity");
  EXPECT_NE(struck.front().message.find("the initial assembly gave beam 'rod' the velocity its "
                                        "joints need at the least kinetic energy (a change of up "
                                        "to "),
            std::string::npos)
      << struck.front().message;
  EXPECT_NE(struck.front().message.find("in its coordinate node 0 slope"), std::string::npos)
      << struck.front().message;
  EXPECT_NE(struck.front().fix.find("give the beam the rigid motion its joints need (AncfBeam2D "
                                    "velocity of its start and angular_velocity about it)"),
            std::string::npos)
      << struck.front().fix;
  EXPECT_NE(struck.front().fix.find("start the mechanism at rest"), std::string::npos);
  EXPECT_NE(struck.front().location.text().find("m.scene:11:1"), std::string::npos)
      << struck.front().location.text();
  EXPECT_TRUE(integrator_check(scene_with("0")).empty());
}

// A beam given a rigid initial motion (velocity of its start, angular velocity about it) moves
// every point rigidly: v = v0 + w z x (r - start), its cross-sections turn at w, and nothing
// strains (a user's connecting rod could only start at rest, 2026-12-06).
TEST_F(MechanismScene, ABeamStartsInTheRigidMotionItIsGiven) {
  Scene scene = build_scene(
      write(R"scene(AncfBeam2D { name = "rod"; start = [0, 0]; end = [1, 0]; elements = 4
             thickness = 0.01; axial_stiffness = 1e6; bending_stiffness = 10; mass_per_length = 1
             velocity = [1, 2]; angular_velocity = 3 }
Sensor { name = "vx"; type = "velocity"; body = "rod"; point = [0.3, 0]; component = "x" }
Sensor { name = "vy"; type = "velocity"; body = "rod"; point = [0.3, 0]; component = "y" }
Sensor { name = "turning"; type = "velocity"; body = "rod"; point = [0.3, 0]; component = "angle" }
Sensor { name = "strain"; type = "strain_energy" }
Sensor { name = "motion"; type = "kinetic_energy" }
)scene"));
  mbd::State state = scene.model.initial_state();
  const auto value = [&](int k) {
    return structure_sensor_value(scene.model, scene.sensors[k], state);
  };
  EXPECT_NEAR(value(0), 1.0, 1e-12);
  EXPECT_NEAR(value(1), 2.0 + 3.0 * 0.3, 1e-12);
  EXPECT_NEAR(value(2), 3.0, 1e-12);
  // Translation (1/2 m |v_c|^2, v_c = (1, 2) + 3 (0, 0.5)) and rotation about the centre
  // (1/2 m L^2/12 w^2).
  const double kinetic = 0.5 * (1.0 + 3.5 * 3.5) + 0.5 * (1.0 / 12.0) * 9.0;
  EXPECT_NEAR(value(4), kinetic, 1e-9 * kinetic);
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  for (int i = 0; i < 100; ++i)
    integrator.step(scene.model, state, 1e-3);
  // After 0.1 s of free flight only the centrifugal stretch strains it: w^2 m L^2 / EA ~ 1e-5.
  EXPECT_LT(value(3), 1e-6 * kinetic);
  EXPECT_NEAR(value(2), 3.0, 1e-4);
}

}  // namespace
}  // namespace fsi::scene
