#include "scene_elements.hpp"

#include <Eigen/Dense>

#include "fsi/common/error.hpp"
#include "runtime_expression.hpp"

namespace fsi::scene::detail {
namespace {

// body_a/point_a and body_b/point_b (body_b absent: point_b is a point of the world), the same
// keys as RevoluteJoint and SpringDamper.
std::vector<ParameterSpec> two_points(std::vector<ParameterSpec> more) {
  std::vector<ParameterSpec> parameters = {
      element_name_spec(), text("body_a", "name of a RigidBody2D"),
      vector("point_a", 2, "m", "point on body_a, body coordinates").with_default({0.0, 0.0}),
      text("body_b", "name of a RigidBody2D; absent: the ground").optional(),
      vector("point_b", 2, "m", "point on body_b (body coordinates) or in the world")
          .with_default({0.0, 0.0})};
  parameters.insert(parameters.end(), more.begin(), more.end());
  return parameters;
}

ParameterSpec rest_length_spec() {
  return number("rest_length", "m", "l0 (default: the initial distance)").at_least(0.0).optional();
}

std::optional<double> optional_number(const View& element, std::string_view key) {
  if (!element.has(key)) return std::nullopt;
  return element.number(key);
}

}  // namespace

mbd::Coordinate coordinate_of(const std::string& text) {
  if (text == "x") return mbd::Coordinate::X;
  if (text == "y") return mbd::Coordinate::Y;
  return mbd::Coordinate::Angle;  // "angle" or "torque"
}

RuntimeExpression expression(const View& element, std::string_view key,
                             const std::vector<std::string>& variables) {
  try {
    return RuntimeExpression(element.string(key), variables);
  } catch (const Error& error) {
    throw Error(error.fault(), element.location(key).text(), error.remedy());
  }
}

ParameterSpec element_name_spec() {
  return text("name", "unique name for sensors and messages (default: kind and index)").optional();
}

std::vector<BlockSpec> element_block_specs() {
  return {
      block_spec("PrismaticJoint",
                 "point_b stays on the line through point_a along axis (body_a's frame) and the "
                 "relative rotation is locked: body_a slides along body_b (or the ground). 2 rows: "
                 "normal force, torque.",
                 two_points({vector("axis", 2, "", "sliding direction in body_a's frame")
                                 .with_default({1.0, 0.0})}))
          .as_list(),
      block_spec("Clamp",
                 "Fixes body at its initial position and angle relative to `to` (3 rows: x, y, "
                 "torque).",
                 {element_name_spec(), text("body", "name of the clamped RigidBody2D"),
                  text("to", "name of the holding RigidBody2D; absent: the ground").optional()})
          .as_list(),
      block_spec(
          "RotationalSpringDamper",
          "Torque on body_a -k (phi_a - phi_b - phi0) - c (omega_a - omega_b), the opposite on "
          "body_b (absent: the ground, phi_b = 0).",
          {element_name_spec(), text("body_a", "name of a RigidBody2D"),
           text("body_b", "name of a RigidBody2D; absent: the ground").optional(),
           number("stiffness", "N m/rad", "k (2D: per unit depth)").at_least(0.0),
           number("damping", "N m s/rad", "c").at_least(0.0).with_default(0.0),
           number("rest_angle", "rad", "phi0 (default: the initial relative angle)").optional()})
          .as_list(),
      block_spec("NonlinearSpringDamper",
                 "Spring-damper along the line of the two points with tension = f(elongation, "
                 "rate), a muParser expression (elongation = l - l0 [m], rate = dl/dt [m/s]).",
                 two_points({text("tension",
                                  "tension [N/m] in elongation and rate, e.g. "
                                  "\"1e4*elongation + 50*rate\""),
                             rest_length_spec()}))
          .as_list(),
      block_spec(
          "SpringActor",
          "Spring actor of thesis §6.5: tension piecewise linear in the elongation through the "
          "characteristic's [elongation, tension] rows (continued with the end slopes), plus "
          "damping.",
          two_points({matrix("characteristic", 2, "m, N/m",
                             "[elongation, tension] rows, elongations increasing (at least 2)"),
                      number("damping", "N s/m", "c").at_least(0.0).with_default(0.0),
                      rest_length_spec()}))
          .as_list(),
      block_spec("PointForce",
                 "A world-frame force at a body point, muParser expressions of the time t [s] "
                 "(evaluated at every stage time).",
                 {element_name_spec(), text("body", "name of a RigidBody2D"),
                  vector("point", 2, "m", "point of application, body coordinates")
                      .with_default({0.0, 0.0}),
                  text("force_x", "x component [N/m] in t").with_default("0"),
                  text("force_y", "y component [N/m] in t").with_default("0")})
          .as_list(),
      block_spec("PrescribedMotion",
                 "Drives a body coordinate along position(t) (position level, 1 row; a "
                 "joint_force sensor reads the drive's force or torque): muParser expressions of "
                 "the time t [s]. rate must be d position / dt; it is checked by differences at 11 "
                 "times over [0, end_time].",
                 {element_name_spec(), text("body", "name of a RigidBody2D"),
                  text("coordinate", "body coordinate").one_of({"x", "y", "angle"}),
                  text("position", "s(t) [m or rad], e.g. \"0.01*sin(20*t)\""),
                  text("rate", "ds/dt [m/s or rad/s], e.g. \"0.2*cos(20*t)\"")})
          .as_list(),
      block_spec("PrescribedVelocity",
                 "Prescribes the velocity of a body coordinate as a muParser expression of the "
                 "time t [s] (velocity level, 1 row; VelocityConstraint for a constant one).",
                 {element_name_spec(), text("body", "name of a RigidBody2D"),
                  text("coordinate", "body coordinate").one_of({"x", "y", "angle"}),
                  text("velocity", "velocity [m/s or rad/s] in t, e.g. \"0.1*t\"")})
          .as_list(),
      block_spec("Torque", "A torque on a body, a muParser expression of the time t [s].",
                 {element_name_spec(), text("body", "name of a RigidBody2D"),
                  text("torque", "torque [N m/m] in t")})
          .as_list(),
  };
}

void register_joint(ElementBuilder& builder, const View& element, NamedJoint joint) {
  if (!element.has("name")) return;
  const std::string& name = element.string("name");
  if (builder.names.joints.count(name) || builder.names.force_elements.count(name)) {
    builder.problem(element.location("name"), "a second element is named '" + name + "'",
                    "give every joint and force element its own name");
    return;
  }
  builder.names.joints.emplace(name, std::move(joint));
}

void register_force_element(ElementBuilder& builder, const View& element, int index,
                            bool rotational) {
  if (!element.has("name")) return;
  const std::string& name = element.string("name");
  if (builder.names.joints.count(name) || builder.names.force_elements.count(name)) {
    builder.problem(element.location("name"), "a second element is named '" + name + "'",
                    "give every joint and force element its own name");
    return;
  }
  builder.names.force_elements.emplace(name, index);
  builder.names.rotational.emplace(name, rotational);
}

void build_elements(const View& root, ElementBuilder& builder) {
  mbd::Model& model = builder.model;
  auto name_of = [](const View& element) {
    return element.has("name") ? element.string("name") : std::string();
  };
  for (const View& j : root.blocks("PrismaticJoint")) {
    builder.guard(j.location(), [&] {
      mbd::PrismaticJointSpec spec;
      spec.name = name_of(j);
      spec.a = builder.point(j, "a");
      spec.b = builder.point(j, "b");
      const auto axis = j.vector("axis");
      spec.axis = {axis[0], axis[1]};
      int row = 0;
      builder.placed(j, [&] { row = model.add_prismatic_joint(spec); });
      register_joint(builder, j, {row, 2, spec.a.body, "prismatic joint"});
    });
  }
  for (const View& c : root.blocks("Clamp")) {
    builder.guard(c.location(), [&] {
      mbd::ClampSpec spec;
      spec.name = name_of(c);
      spec.body = builder.find_body(c, "body");
      if (c.has("to")) spec.to = builder.find_body(c, "to");
      int row = 0;
      builder.placed(c, [&] { row = model.add_clamp(spec); });
      register_joint(builder, c, {row, 3, spec.body, "clamp"});
    });
  }
  for (const View& f : root.blocks("RotationalSpringDamper")) {
    builder.guard(f.location(), [&] {
      mbd::RotationalSpringDamperSpec spec;
      spec.name = name_of(f);
      spec.a = builder.find_body(f, "body_a");
      if (f.has("body_b")) spec.b = builder.find_body(f, "body_b");
      spec.stiffness = f.number("stiffness");
      spec.damping = f.number("damping");
      spec.rest_angle = optional_number(f, "rest_angle");
      int index = 0;
      builder.placed(f, [&] { index = model.add_rotational_spring_damper(spec); });
      register_force_element(builder, f, index, true);
    });
  }
  for (const View& f : root.blocks("NonlinearSpringDamper")) {
    builder.guard(f.location(), [&] {
      mbd::NonlinearSpringDamperSpec spec;
      spec.name = name_of(f);
      spec.a = builder.point(f, "a");
      spec.b = builder.point(f, "b");
      const RuntimeExpression law = expression(f, "tension", {"elongation", "rate"});
      spec.tension = [law](double elongation, double rate) { return law(elongation, rate); };
      spec.rest_length = optional_number(f, "rest_length");
      int index = 0;
      builder.placed(f, [&] { index = model.add_nonlinear_spring_damper(spec); });
      register_force_element(builder, f, index, false);
    });
  }
  for (const View& f : root.blocks("SpringActor")) {
    builder.guard(f.location(), [&] {
      mbd::SpringActorSpec spec;
      spec.name = name_of(f);
      spec.a = builder.point(f, "a");
      spec.b = builder.point(f, "b");
      for (const auto& row : f.matrix("characteristic"))
        spec.characteristic.emplace_back(row[0], row[1]);
      spec.damping = f.number("damping");
      spec.rest_length = optional_number(f, "rest_length");
      int index = 0;
      builder.placed(f, [&] { index = model.add_spring_actor(spec); });
      register_force_element(builder, f, index, false);
    });
  }
  for (const View& p : root.blocks("PointForce")) {
    builder.guard(p.location(), [&] {
      mbd::PointForceSpec spec;
      spec.name = name_of(p);
      const auto local = p.vector("point");
      spec.point = {builder.find_body(p, "body"), {local[0], local[1]}};
      const RuntimeExpression x = expression(p, "force_x", {"t"});
      const RuntimeExpression y = expression(p, "force_y", {"t"});
      spec.force = [x, y](double t) { return Eigen::Vector2d(x(t), y(t)); };
      builder.placed(p, [&] { model.add_point_force(spec); });
    });
  }
  for (const View& p : root.blocks("PrescribedMotion")) {
    builder.guard(p.location(), [&] {
      mbd::PrescribedMotionSpec spec;
      spec.name = name_of(p);
      spec.body = builder.find_body(p, "body");
      spec.coordinate = coordinate_of(p.string("coordinate"));
      const RuntimeExpression position = expression(p, "position", {"t"});
      const RuntimeExpression rate = expression(p, "rate", {"t"});
      spec.position = [position](double time) { return position(time); };
      spec.rate = [rate](double time) { return rate(time); };
      spec.check_times.clear();
      for (int k = 0; k <= 10; ++k)
        spec.check_times.push_back(builder.end_time * k / 10.0);
      int row = 0;
      builder.placed(p, [&] { row = model.add_prescribed_motion(spec); });
      register_joint(builder, p, {row, 1, spec.body, "prescribed motion"});
    });
  }
  for (const View& p : root.blocks("PrescribedVelocity")) {
    builder.guard(p.location(), [&] {
      const mbd::BodyId body = builder.find_body(p, "body");
      const RuntimeExpression velocity = expression(p, "velocity", {"t"});
      int row = 0;
      builder.placed(p, [&] {
        row = model.add_velocity_constraint(body, coordinate_of(p.string("coordinate")),
                                            [velocity](double time) { return velocity(time); });
      });
      register_joint(builder, p, {row, 1, body, "prescribed velocity"});
    });
  }
  for (const View& t : root.blocks("Torque")) {
    builder.guard(t.location(), [&] {
      mbd::TorqueSpec spec;
      spec.name = name_of(t);
      spec.body = builder.find_body(t, "body");
      const RuntimeExpression torque = expression(t, "torque", {"t"});
      spec.torque = [torque](double time) { return torque(time); };
      builder.placed(t, [&] { model.add_torque(spec); });
    });
  }
}

}  // namespace fsi::scene::detail
