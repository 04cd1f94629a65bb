// Spatial joints: constraint rows between spatial bodies and the ground. A joint registers its
// rows by name for joint_force sensors.

#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

std::vector<BlockSpec> spatial_joint_blocks() {
  return releasable({
      block_spec(
          "CableClamp",
          "Clamps a node of an AncfCable3D to the ground at its initial position and slope "
          "direction (5 rows: x, y, z, two slope rows; the axial stretch stays free).",
          {text("cable", "name of an AncfCable3D"),
           integer("node", "node index: 0 at start, elements at end").at_least(0).with_default(0)})
          .as_list()
          .spatial(),
      block_spec("SphericalJoint", "Pins point_a of body_a to point_b (3 rows: x, y, z).",
                 spatial_two_points({}))
          .as_list()
          .spatial(),
      block_spec(
          "RevoluteJoint3D",
          "A hinge: the points coincide and body_b turns relative to body_a about `axis` "
          "(in body_a's axes) only: 5 rows. Rigid bodies (or the ground as body_b). With `rate` "
          "a drive (motor): a 6th row turns body_a relative to body_b about `axis` by rate * t "
          "from the initial configuration; a joint_force sensor's component torque reads the "
          "drive torque on body_a about the axis.",
          spatial_two_points(
              {vector("axis", 3, "", "hinge axis in body_a's axes").with_default({0.0, 0.0, 1.0}),
               number("rate", "rad/s",
                      "drive: body_a turns relative to body_b at this rate about `axis` "
                      "(right-handed; with the ground as body_b, body_a's angular velocity about "
                      "the axis); body_a's initial angular_velocity must agree (absent: a free "
                      "hinge)")
                   .optional()}))
          .as_list()
          .spatial(),
      block_spec(
          "PrismaticJoint3D",
          "A slider: point_b stays on the line through point_a along `axis` (in body_a's axes) "
          "and the relative orientation is locked: body_a slides along body_b (or the ground). "
          "RigidBody3D bodies; point_b must lie on that line initially. 5 rows: two normal "
          "forces, three orientation rows; joint_force reads the force and torque on body_a.",
          spatial_two_points({vector("axis", 3, "", "sliding direction in body_a's axes")
                                  .with_default({1.0, 0.0, 0.0})}))
          .as_list()
          .spatial(),
      block_spec("FixedJoint3D",
                 "Fixes `body` (a RigidBody3D) at its initial position and orientation relative "
                 "to `to` (6 rows; joint_force reads the force and torque it exerts on body).",
                 {element_name_spec(), text("body", "name of the fixed RigidBody3D"),
                  text("to", "name of the holding RigidBody3D; absent: the ground").optional()})
          .as_list()
          .spatial(),
      block_spec(
          "DistanceConstraint3D",
          "A massless rod between the two points (1 row; lambda is the rod force, tension "
          "positive).",
          spatial_two_points(
              {number("length", "m", "default: the initial distance").above(0.0).optional()}))
          .as_list()
          .spatial(),
  });
}

void build_spatial_joints(SceneBuilder& builder) {
  mbd::Model& model = builder.model;
  builder.each("CableClamp", [&](const View& c) {
    const mbd::BodyId cable = builder.find_body(c, "cable");
    const auto node = static_cast<int>(c.integer("node"));
    builder.placed(c, [&] { model.add_cable_clamp(cable, node); });
  });
  builder.each("SphericalJoint", [&](const View& j) {
    const auto a = builder.point3(j, "a");
    const auto b = builder.point3(j, "b");
    builder.add_joint(j, [&] { return model.add_spherical_joint(a, b, name_of(j)); },
                      {.rows = 3, .body = a.body, .kind = "spherical joint"});
  });
  builder.each("RevoluteJoint3D", [&](const View& j) {
    mbd::RevoluteJoint3DSpec spec;
    spec.name = name_of(j);
    spec.a = builder.point3(j, "a");
    spec.b = builder.point3(j, "b");
    spec.axis = vector3(j, "axis");
    spec.rate = optional_number(j, "rate");
    builder.add_joint(j, [&] { return model.add_revolute_joint_3d(spec); },
                      {.rows = spec.rate ? 6 : 5,
                       .body = spec.a.body,
                       .kind = "revolute joint",
                       .drive = spec.rate.has_value()});
  });
  builder.each("PrismaticJoint3D", [&](const View& j) {
    mbd::PrismaticJoint3DSpec spec;
    spec.name = name_of(j);
    spec.a = builder.point3(j, "a");
    spec.b = builder.point3(j, "b");
    spec.axis = vector3(j, "axis");
    builder.add_joint(j, [&] { return model.add_prismatic_joint_3d(spec); },
                      {.rows = 5, .body = spec.a.body, .kind = "prismatic joint"});
  });
  builder.each("FixedJoint3D", [&](const View& j) {
    mbd::FixedJoint3DSpec spec;
    spec.name = name_of(j);
    spec.body = builder.find_body(j, "body");
    if (j.has("to")) spec.to = builder.find_body(j, "to");
    builder.add_joint(j, [&] { return model.add_fixed_joint_3d(spec); },
                      {.rows = 6, .body = spec.body, .kind = "fixed joint"});
  });
  builder.each("DistanceConstraint3D", [&](const View& c) {
    const auto a = builder.point3(c, "a");
    const auto b = builder.point3(c, "b");
    const std::optional<double> length = optional_number(c, "length");
    builder.add_joint(
        c, [&] { return model.add_spatial_distance_constraint(a, b, length, name_of(c)); },
        {.rows = 1, .body = a.body, .kind = "distance constraint"});
  });
}

}  // namespace

ElementFamily spatial_joints_family() {
  return {"spatial joints", spatial_joint_blocks, {build_spatial_joints}};
}

}  // namespace fsi::scene::detail
