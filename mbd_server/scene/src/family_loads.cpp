// Loads: time-dependent forces and torques on bodies, muParser expressions of t.

#include "runtime_expression.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

std::vector<BlockSpec> load_blocks() {
  return {
      block_spec("PointForce",
                 with_scene_numbers(
                     "A world-frame force at a body point, muParser expressions of the time t [s] "
                     "(evaluated at every stage time)."),
                 {element_name_spec(), text("body", "name of a RigidBody2D or an AncfBeam2D"),
                  vector("point", 2, "m",
                         "point of application: body coordinates; [s, eta] on a beam (arc "
                         "length from its start, offset along the normal)")
                      .with_default({0.0, 0.0}),
                  text("force_x", "x component [N/m] in t").with_default("0"),
                  text("force_y", "y component [N/m] in t").with_default("0")})
          .as_list()
          .planar(),
      block_spec("Torque",
                 with_scene_numbers("A torque on a body, a muParser expression of the time t [s]."),
                 {element_name_spec(), text("body", "name of a RigidBody2D"),
                  text("torque", "torque [N m/m] in t")})
          .as_list()
          .planar(),
      block_spec(
          "PointForce3D",
          with_scene_numbers(
              "A world-frame force at a point of a spatial body, muParser expressions of the "
              "time t [s] (evaluated at every stage time)."),
          {element_name_spec(), text("body", "name of a spatial body"),
           spatial_point("", "point of application (as point_a of the joints)"),
           text("force_x", "x component [N] in t").with_default("0"),
           text("force_y", "y component [N] in t").with_default("0"),
           text("force_z", "z component [N] in t").with_default("0")})
          .as_list()
          .spatial(),
      block_spec(
          "Torque3D",
          with_scene_numbers(
              "A world-frame torque on a RigidBody3D, muParser expressions of the time t [s]."),
          {element_name_spec(), text("body", "name of a RigidBody3D"),
           text("torque_x", "x component [N m] in t").with_default("0"),
           text("torque_y", "y component [N m] in t").with_default("0"),
           text("torque_z", "z component [N m] in t").with_default("0")})
          .as_list()
          .spatial(),
  };
}

void build_planar_loads(SceneBuilder& builder) {
  builder.each("PointForce", [&](const View& p) {
    mbd::PointForceSpec spec;
    spec.name = name_of(p);
    const auto local = p.vector("point");
    spec.point = {builder.find_body(p, "body"), {local[0], local[1]}};
    const RuntimeExpression x = builder.expression(p, "force_x", {"t"});
    const RuntimeExpression y = builder.expression(p, "force_y", {"t"});
    spec.force = [x, y](double t) { return Eigen::Vector2d(x(t), y(t)); };
    builder.placed(p, [&] { builder.model.add_point_force(spec); });
  });
  builder.each("Torque", [&](const View& t) {
    mbd::TorqueSpec spec;
    spec.name = name_of(t);
    spec.body = builder.find_body(t, "body");
    const RuntimeExpression torque = builder.expression(t, "torque", {"t"});
    spec.torque = [torque](double time) { return torque(time); };
    builder.placed(t, [&] { builder.model.add_torque(spec); });
  });
}

// Three expressions of t named prefix_x, prefix_y, prefix_z.
std::function<Eigen::Vector3d(double)> vector_of_time(const SceneBuilder& builder,
                                                      const View& element,
                                                      const std::string& prefix) {
  const RuntimeExpression x = builder.expression(element, prefix + "_x", {"t"});
  const RuntimeExpression y = builder.expression(element, prefix + "_y", {"t"});
  const RuntimeExpression z = builder.expression(element, prefix + "_z", {"t"});
  return [x, y, z](double t) { return Eigen::Vector3d(x(t), y(t), z(t)); };
}

void build_spatial_loads(SceneBuilder& builder) {
  builder.each("PointForce3D", [&](const View& p) {
    mbd::SpatialPointForceSpec spec;
    spec.name = name_of(p);
    spec.point = {builder.find_body(p, "body"), vector3(p, "point")};
    spec.force = vector_of_time(builder, p, "force");
    builder.placed(p, [&] { builder.model.add_spatial_point_force(spec); });
  });
  builder.each("Torque3D", [&](const View& p) {
    mbd::SpatialTorqueSpec spec;
    spec.name = name_of(p);
    spec.body = builder.find_body(p, "body");
    spec.torque = vector_of_time(builder, p, "torque");
    builder.placed(p, [&] { builder.model.add_spatial_torque(spec); });
  });
}

}  // namespace

ElementFamily loads_family() {
  return {"loads", load_blocks, {build_planar_loads, build_spatial_loads}};
}

}  // namespace fsi::scene::detail
