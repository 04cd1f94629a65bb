// Springs and actors: force elements between two bodies (or a body and the ground), planar and
// spatial. A spring registers itself by name for spring_force sensors.

#include "runtime_expression.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

// Either end on a RigidBody2D or an AncfBeam2D ([s, eta] on a beam), or the ground.
std::vector<ParameterSpec> two_points(std::vector<ParameterSpec> more) {
  return planar_two_points(std::move(more), true);
}

// A block's `tension` as the model's law of (elongation, rate, t).
mbd::TensionFunction tension_law(SceneBuilder& builder, const View& f) {
  const RuntimeExpression law = builder.expression(f, "tension", {"elongation", "rate", "t"});
  return [law](double elongation, double rate, double t) { return law(elongation, rate, t); };
}

ParameterSpec rest_length_spec() {
  return number("rest_length", "m", "l0 (default: the initial distance)").at_least(0.0).optional();
}

// The keys of a spatial rotational spring, around its law's.
std::vector<ParameterSpec> spatial_rotational_spring(std::vector<ParameterSpec> law) {
  std::vector<ParameterSpec> keys = {
      element_name_spec(), text("body_a", "name of a RigidBody3D; the axis is fixed in it"),
      text("body_b", "name of a RigidBody3D; absent: the ground").optional(),
      vector("axis", 3, "", "the spring's axis in body_a's axes (need not be a unit vector)")
          .with_default({0.0, 0.0, 1.0})};
  for (ParameterSpec& key : law)
    keys.push_back(std::move(key));
  keys.push_back(number("rest_angle", "rad",
                        "the twist at which it is relaxed, from the initial configuration "
                        "(default 0: relaxed at the start)")
                     .optional());
  return keys;
}

std::vector<BlockSpec> spring_blocks() {
  return {
      block_spec("SpringDamper",
                 "Linear spring-damper between the two points: tension k (l - l0) + c dl/dt.",
                 two_points({number("stiffness", "N/m", "k (2D: per unit depth)").at_least(0.0),
                             number("damping", "N s/m", "c").at_least(0.0).with_default(0.0),
                             rest_length_spec()}))
          .as_list()
          .planar(),
      block_spec(
          "RotationalSpringDamper",
          "Torque on body_a -k (phi_a - phi_b - phi0) - c (omega_a - omega_b), the opposite on "
          "body_b (absent: the ground, phi_b = 0).",
          {element_name_spec(), text("body_a", "name of a RigidBody2D"),
           text("body_b", "name of a RigidBody2D; absent: the ground").optional(),
           number("stiffness", "N m/rad", "k (2D: per unit depth)").at_least(0.0),
           number("damping", "N m s/rad", "c").at_least(0.0).with_default(0.0),
           number("rest_angle", "rad", "phi0 (default: the initial relative angle)").optional()})
          .as_list()
          .planar(),
      block_spec(
          "NonlinearRotationalSpringDamper",
          with_scene_numbers(
              "Rotational spring-damper whose torque resisting the twist is f(rotation, rate, t), "
              "a muParser expression (rotation = phi_a - phi_b - phi0 [rad], rate = its rate "
              "[rad/s], t the time [s]): the torque on body_a is -f, on body_b +f."),
          {element_name_spec(), text("body_a", "name of a RigidBody2D"),
           text("body_b", "name of a RigidBody2D; absent: the ground").optional(),
           text("torque",
                "torque [N m/m] resisting the twist, in rotation, rate and t, e.g. "
                "\"(rotation < 0 ? 50*rotation : 2*rotation) + 0.1*rate\""),
           number("rest_angle", "rad", "phi0 (default: the initial relative angle)").optional()})
          .as_list()
          .planar(),
      block_spec("NonlinearSpringDamper",
                 with_scene_numbers("Spring-damper along the line of the two points with "
                                    "tension = f(elongation, rate, t), a muParser expression "
                                    "(elongation = l - l0 [m], rate = dl/dt [m/s], t the time "
                                    "[s])."),
                 two_points({text("tension",
                                  "tension [N/m] in elongation, rate and t, e.g. "
                                  "\"1e4*elongation + 50*rate\""),
                             rest_length_spec()}))
          .as_list()
          .planar(),
      block_spec(
          "SpringActor",
          "Spring actor of thesis §6.5: tension piecewise linear in the elongation through the "
          "characteristic's [elongation, tension] rows (continued with the end slopes), plus "
          "damping.",
          two_points({matrix("characteristic", 2, "m, N/m",
                             "[elongation, tension] rows, elongations increasing (at least 2)"),
                      number("damping", "N s/m", "c").at_least(0.0).with_default(0.0),
                      rest_length_spec()}))
          .as_list()
          .planar(),
      block_spec(
          "SpringDamper3D",
          "Linear spring-damper between the two points: tension k (l - l0) + c dl/dt "
          "(spring_force sensors read it by name).",
          spatial_two_points({number("stiffness", "N/m", "k").at_least(0.0),
                              number("damping", "N s/m", "c").at_least(0.0).with_default(0.0),
                              rest_length_spec()}))
          .as_list()
          .spatial(),
      block_spec("NonlinearSpringDamper3D",
                 with_scene_numbers("Spring-damper along the line of the two points with "
                                    "tension = f(elongation, rate, t), a muParser expression "
                                    "(elongation = l - l0 [m], rate = dl/dt [m/s], t the time "
                                    "[s]); spring_force sensors read the tension by name."),
                 spatial_two_points({text("tension",
                                          "tension [N] in elongation, rate and t, e.g. "
                                          "\"elongation > 0 ? 1e4*elongation : 0\" (a rope)"),
                                     rest_length_spec()}))
          .as_list()
          .spatial(),
      block_spec(
          "RotationalSpringDamper3D",
          "Rotational spring-damper about `axis` (body_a's axes): the torque on body_a is "
          "-k twist - c rate about the axis, on body_b the opposite (absent: the ground); twist = "
          "body_a's rotation relative to body_b about the axis from the initial configuration, "
          "less rest_angle (the hinge angle, beside a RevoluteJoint3D about the same axis), "
          "measured within +-170 degrees of the rest (a pure damper turns freely).",
          spatial_rotational_spring(
              {number("stiffness", "N m/rad", "k").at_least(0.0),
               number("damping", "N m s/rad", "c").at_least(0.0).with_default(0.0)}))
          .as_list()
          .spatial(),
      block_spec("NonlinearRotationalSpringDamper3D",
                 with_scene_numbers(
                     "Rotational spring-damper about `axis` whose torque resisting the twist is "
                     "f(rotation, rate, t), a muParser expression (rotation = the twist [rad] "
                     "as RotationalSpringDamper3D's, rate = its rate [rad/s], t the time [s]): "
                     "the torque on body_a is -f about the axis, on body_b +f."),
                 spatial_rotational_spring(
                     {text("torque",
                           "torque [N m] resisting the twist, in rotation, rate and t, e.g. "
                           "\"rotation > 0 ? 50*rotation : 0\" (a one-sided stop)")}))
          .as_list()
          .spatial(),
  };
}

void build_planar_springs(SceneBuilder& builder) {
  mbd::Model& model = builder.model;
  builder.each("SpringDamper", [&](const View& f) {
    mbd::SpringDamperSpec spec;
    spec.a = builder.point(f, "a");
    spec.b = builder.point(f, "b");
    spec.stiffness = f.number("stiffness");
    spec.damping = f.number("damping");
    spec.rest_length = optional_number(f, "rest_length");
    builder.placed(f, [&] { model.add_spring_damper(spec); });
    builder.register_force_element(f, model.force_element_count() - 1, false);
  });
  builder.each("RotationalSpringDamper", [&](const View& f) {
    mbd::RotationalSpringDamperSpec spec;
    spec.name = name_of(f);
    spec.a = builder.find_body(f, "body_a");
    if (f.has("body_b")) spec.b = builder.find_body(f, "body_b");
    spec.stiffness = f.number("stiffness");
    spec.damping = f.number("damping");
    spec.rest_angle = optional_number(f, "rest_angle");
    builder.add_force_element(
        f, [&] { return model.add_rotational_spring_damper(spec); }, true);
  });
}

void build_planar_actors(SceneBuilder& builder) {
  mbd::Model& model = builder.model;
  builder.each("NonlinearSpringDamper", [&](const View& f) {
    mbd::NonlinearSpringDamperSpec spec;
    spec.name = name_of(f);
    spec.a = builder.point(f, "a");
    spec.b = builder.point(f, "b");
    spec.tension = tension_law(builder, f);
    spec.rest_length = optional_number(f, "rest_length");
    builder.add_force_element(
        f, [&] { return model.add_nonlinear_spring_damper(spec); }, false);
  });
  builder.each("NonlinearRotationalSpringDamper", [&](const View& f) {
    mbd::NonlinearRotationalSpringDamperSpec spec;
    spec.name = name_of(f);
    spec.a = builder.find_body(f, "body_a");
    if (f.has("body_b")) spec.b = builder.find_body(f, "body_b");
    const RuntimeExpression law = builder.expression(f, "torque", {"rotation", "rate", "t"});
    spec.torque = [law](double rotation, double rate, double t) { return law(rotation, rate, t); };
    spec.rest_angle = optional_number(f, "rest_angle");
    builder.add_force_element(
        f, [&] { return model.add_nonlinear_rotational_spring_damper(spec); }, true);
  });
  builder.each("SpringActor", [&](const View& f) {
    mbd::SpringActorSpec spec;
    spec.name = name_of(f);
    spec.a = builder.point(f, "a");
    spec.b = builder.point(f, "b");
    for (const auto& row : f.matrix("characteristic"))
      spec.characteristic.emplace_back(row[0], row[1]);
    spec.damping = f.number("damping");
    spec.rest_length = optional_number(f, "rest_length");
    builder.add_force_element(
        f, [&] { return model.add_spring_actor(spec); }, false);
  });
}

// The bodies, axis and rest angle of a spatial rotational spring.
mbd::SpatialRotationalSpringDamperSpec spatial_rotational_ends(SceneBuilder& builder,
                                                               const View& f) {
  mbd::SpatialRotationalSpringDamperSpec spec;
  spec.name = name_of(f);
  spec.a = builder.find_body(f, "body_a");
  if (f.has("body_b")) spec.b = builder.find_body(f, "body_b");
  spec.axis = vector3(f, "axis");
  spec.rest_angle = optional_number(f, "rest_angle");
  return spec;
}

void build_spatial_springs(SceneBuilder& builder) {
  builder.each("SpringDamper3D", [&](const View& f) {
    mbd::SpatialSpringDamperSpec spec;
    spec.name = name_of(f);
    spec.a = builder.point3(f, "a");
    spec.b = builder.point3(f, "b");
    spec.stiffness = f.number("stiffness");
    spec.damping = f.number("damping");
    spec.rest_length = optional_number(f, "rest_length");
    builder.add_force_element(
        f, [&] { return builder.model.add_spatial_spring_damper(spec); }, false);
  });
  builder.each("NonlinearSpringDamper3D", [&](const View& f) {
    mbd::SpatialNonlinearSpringDamperSpec spec;
    spec.name = name_of(f);
    spec.a = builder.point3(f, "a");
    spec.b = builder.point3(f, "b");
    spec.tension = tension_law(builder, f);
    spec.rest_length = optional_number(f, "rest_length");
    builder.add_force_element(
        f, [&] { return builder.model.add_spatial_nonlinear_spring_damper(spec); }, false);
  });
  builder.each("RotationalSpringDamper3D", [&](const View& f) {
    mbd::SpatialRotationalSpringDamperSpec spec = spatial_rotational_ends(builder, f);
    spec.stiffness = f.number("stiffness");
    spec.damping = f.number("damping");
    builder.add_force_element(
        f, [&] { return builder.model.add_spatial_rotational_spring_damper(spec); }, true);
  });
  builder.each("NonlinearRotationalSpringDamper3D", [&](const View& f) {
    mbd::SpatialRotationalSpringDamperSpec spec = spatial_rotational_ends(builder, f);
    const RuntimeExpression law = builder.expression(f, "torque", {"rotation", "rate", "t"});
    spec.torque = [law](double rotation, double rate, double t) { return law(rotation, rate, t); };
    builder.add_force_element(
        f, [&] { return builder.model.add_spatial_rotational_spring_damper(spec); }, true);
  });
}

}  // namespace

ElementFamily springs_family() {
  // In the order of the model's force elements (a spring_force sensor reads one by index).
  return {"springs and actors",
          spring_blocks,
          {build_planar_springs, build_planar_actors, build_spatial_springs}};
}

}  // namespace fsi::scene::detail
