// Planar joints: constraint rows between planar bodies and the ground. A joint registers its
// rows by name for joint_force sensors.

#include "runtime_expression.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

// The keys of RevoluteJoint and DistanceConstraint, whose points may lie on beams.
std::vector<ParameterSpec> beam_two_points(std::vector<ParameterSpec> more) {
  return planar_two_points(std::move(more), true);
}
std::vector<ParameterSpec> two_points(std::vector<ParameterSpec> more) {
  return planar_two_points(std::move(more), false);
}

std::vector<BlockSpec> planar_joint_blocks() {
  const ParameterSpec body_name = text("body", "name of a RigidBody2D");
  const ParameterSpec coordinate =
      text("coordinate", "body coordinate").one_of({"x", "y", "angle"});
  return releasable({
      block_spec(
          "CoordinateConstraint",
          "Holds a body coordinate at a value (position level; force from a Lagrange multiplier; "
          "a joint_force sensor on its name reads the holding force or torque).",
          {element_name_spec(), body_name, coordinate,
           number("value", "m or rad", "held value (default: the initial coordinate)").optional()})
          .as_list()
          .planar(),
      block_spec("VelocityConstraint",
                 "Prescribes the velocity of a body coordinate (velocity level, thesis §6.3 "
                 "piston; a joint_force sensor on its name reads the driving force or torque).",
                 {element_name_spec(), body_name, coordinate,
                  number("velocity", "m/s or rad/s", "prescribed constant velocity")})
          .as_list()
          .planar(),
      block_spec(
          "BeamClamp",
          "Clamps a node of an AncfBeam2D to the ground (or to the RigidBody2D `to`) at "
          "its initial position and slope direction (rows x, y, slope direction); slope = "
          "\"full\" also holds the slope's length (4 rows). A joint_force sensor on its name "
          "reads the force on the beam and the clamp's moment about the node (torque).",
          {element_name_spec(), text("beam", "name of an AncfBeam2D"),
           text("to", "name of the holding RigidBody2D; absent: the ground").optional(),
           integer("node", "node index: 0 at start, elements at end").at_least(0).with_default(0),
           text("slope",
                "direction: the axial stretch at the clamp stays free (Gerstmayr & "
                "Irschik); full: held too")
               .one_of({"direction", "full"})
               .with_default("direction")})
          .as_list()
          .planar(),
      block_spec("RevoluteJoint",
                 "Pins point_a of body_a to point_b (2 constraint rows, x then y).",
                 beam_two_points({}))
          .as_list()
          .planar(),
      block_spec(
          "DistanceConstraint",
          "A massless rod: |r_b - r_a| = length (1 row; lambda is the rod force, tension "
          "positive).",
          beam_two_points({number("length", "m", "rod length (default: the initial distance)")
                               .positive()
                               .optional()}))
          .as_list()
          .planar(),
      block_spec("PrismaticJoint",
                 "point_b stays on the line through point_a along axis (body_a's frame) and the "
                 "relative rotation is locked: body_a slides along body_b (or the ground). 2 rows: "
                 "normal force, torque.",
                 two_points({vector("axis", 2, "", "sliding direction in body_a's frame")
                                 .with_default({1.0, 0.0})}))
          .as_list()
          .planar(),
      block_spec("Clamp",
                 "Fixes body at its initial position and angle relative to `to` (3 rows: x, y, "
                 "torque).",
                 {element_name_spec(), text("body", "name of the clamped RigidBody2D"),
                  text("to", "name of the holding RigidBody2D; absent: the ground").optional()})
          .as_list()
          .planar(),
      block_spec(
          "PrescribedMotion",
          with_scene_numbers(
              "Drives a body coordinate along position(t) (position level, 1 row; a "
              "joint_force sensor reads the drive's force or torque): muParser expressions of "
              "the time t [s]. rate must be d position / dt; it is checked by differences at 11 "
              "times over [0, end_time]."),
          {element_name_spec(), text("body", "name of a RigidBody2D"),
           text("coordinate", "body coordinate").one_of({"x", "y", "angle"}),
           text("position", "s(t) [m or rad], e.g. \"0.01*sin(20*t)\""),
           text("rate", "ds/dt [m/s or rad/s], e.g. \"0.2*cos(20*t)\"")})
          .as_list()
          .planar(),
      block_spec("PrescribedVelocity",
                 with_scene_numbers(
                     "Prescribes the velocity of a body coordinate as a muParser expression of the "
                     "time t [s] (velocity level, 1 row; VelocityConstraint for a constant one). "
                     "The coordinate itself is not held: it drifts from the integral of the "
                     "velocity by the integrator's error (implicit Euler: about h/2 times the "
                     "velocity's change; Radau IIA 3: negligible), which the constraint drift of "
                     "run.json does not show; PrescribedMotion holds the position."),
                 {element_name_spec(), text("body", "name of a RigidBody2D"),
                  text("coordinate", "body coordinate").one_of({"x", "y", "angle"}),
                  text("velocity", "velocity [m/s or rad/s] in t, e.g. \"0.1*t\"")})
          .as_list()
          .planar(),
  });
}

void build_coordinate_constraints(SceneBuilder& builder) {
  builder.each("CoordinateConstraint", [&](const View& c) {
    const mbd::BodyId body = builder.find_body(c, "body");
    builder.add_joint(c,
                      [&] {
                        return builder.model.add_coordinate_constraint(
                            body, coordinate_of(c.string("coordinate")),
                            optional_number(c, "value"));
                      },
                      {.rows = 1, .body = body, .kind = "coordinate constraint"});
  });
  builder.each("VelocityConstraint", [&](const View& c) {
    const mbd::BodyId body = builder.find_body(c, "body");
    builder.add_joint(c,
                      [&] {
                        return builder.model.add_velocity_constraint(
                            body, coordinate_of(c.string("coordinate")), c.number("velocity"));
                      },
                      {.rows = 1, .body = body, .kind = "velocity constraint"});
  });
}

// Where a joint acts on an AncfBeam2D, as [s, eta] (a joint_force sensor's torque is about it).
std::optional<std::array<double, 2>> beam_point_of(const mbd::Model& model,
                                                   const mbd::BodyPointSpec& point) {
  if (point.body == mbd::kGround || !model.is_beam(point.body)) return std::nullopt;
  return std::array<double, 2>{point.local.x(), point.local.y()};
}

std::optional<std::array<double, 2>> beam_node_point(const mbd::Model& model, mbd::BodyId beam,
                                                     int node) {
  if (beam == mbd::kGround || !model.is_beam(beam)) return std::nullopt;  // add_beam_clamp says
  const mbd::AncfBeamSpec& spec = model.beam(beam);
  return std::array<double, 2>{node * (spec.end - spec.start).norm() / spec.element_count, 0.0};
}

void build_beam_clamps(SceneBuilder& builder) {
  builder.each("BeamClamp", [&](const View& c) {
    const mbd::BodyId beam = builder.find_body(c, "beam");
    const auto node = static_cast<int>(c.integer("node"));
    const auto slope =
        c.string("slope") == "full" ? mbd::BeamClamp::Full : mbd::BeamClamp::Direction;
    const mbd::BodyId to = c.has("to") ? builder.find_body(c, "to") : mbd::kGround;
    builder.add_joint(c, [&] { return builder.model.add_beam_clamp(beam, node, slope, to); },
                      {.rows = slope == mbd::BeamClamp::Full ? 4 : 3,
                       .body = beam,
                       .kind = "beam clamp",
                       .beam_point = beam_node_point(builder.model, beam, node)});
  });
}

void build_point_joints(SceneBuilder& builder) {
  mbd::Model& model = builder.model;
  builder.each("RevoluteJoint", [&](const View& j) {
    const auto a = builder.point(j, "a");
    const auto b = builder.point(j, "b");
    builder.add_joint(j, [&] { return model.add_revolute_joint(a, b, name_of(j)); },
                      {.rows = 2,
                       .body = a.body,
                       .kind = "revolute joint",
                       .beam_point = beam_point_of(builder.model, a)});
  });
  builder.each("DistanceConstraint", [&](const View& c) {
    const auto a = builder.point(c, "a");
    const auto b = builder.point(c, "b");
    const std::optional<double> length = optional_number(c, "length");
    builder.add_joint(c, [&] { return model.add_distance_constraint(a, b, length, name_of(c)); },
                      {.rows = 1,
                       .body = a.body,
                       .kind = "distance constraint",
                       .beam_point = beam_point_of(builder.model, a)});
  });
  builder.each("PrismaticJoint", [&](const View& j) {
    mbd::PrismaticJointSpec spec;
    spec.name = name_of(j);
    spec.a = builder.point(j, "a");
    spec.b = builder.point(j, "b");
    const auto axis = j.vector("axis");
    spec.axis = {axis[0], axis[1]};
    builder.add_joint(j, [&] { return model.add_prismatic_joint(spec); },
                      {.rows = 2, .body = spec.a.body, .kind = "prismatic joint"});
  });
  builder.each("Clamp", [&](const View& c) {
    mbd::ClampSpec spec;
    spec.name = name_of(c);
    spec.body = builder.find_body(c, "body");
    if (c.has("to")) spec.to = builder.find_body(c, "to");
    builder.add_joint(c, [&] { return model.add_clamp(spec); },
                      {.rows = 3, .body = spec.body, .kind = "clamp"});
  });
}

void build_prescribed_motions(SceneBuilder& builder) {
  builder.each("PrescribedMotion", [&](const View& p) {
    mbd::PrescribedMotionSpec spec;
    spec.name = name_of(p);
    spec.body = builder.find_body(p, "body");
    spec.coordinate = coordinate_of(p.string("coordinate"));
    const RuntimeExpression position = builder.expression(p, "position", {"t"});
    const RuntimeExpression rate = builder.expression(p, "rate", {"t"});
    spec.position = [position](double time) { return position(time); };
    spec.rate = [rate](double time) { return rate(time); };
    spec.check_times = prescribed_motion_check_times(builder.end_time);
    builder.add_joint(p, [&] { return builder.model.add_prescribed_motion(spec); },
                      {.rows = 1, .body = spec.body, .kind = "prescribed motion"});
  });
  builder.each("PrescribedVelocity", [&](const View& p) {
    const mbd::BodyId body = builder.find_body(p, "body");
    const RuntimeExpression velocity = builder.expression(p, "velocity", {"t"});
    builder.add_joint(p,
                      [&] {
                        return builder.model.add_velocity_constraint(
                            body, coordinate_of(p.string("coordinate")),
                            [velocity](double time) { return velocity(time); });
                      },
                      {.rows = 1, .body = body, .kind = "prescribed velocity"});
  });
}

}  // namespace

ElementFamily planar_joints_family() {
  // In the order of their rows (a joint_force sensor reads rows by index).
  return {"planar joints",
          planar_joint_blocks,
          {build_coordinate_constraints, build_beam_clamps, build_point_joints,
           build_prescribed_motions}};
}

}  // namespace fsi::scene::detail
