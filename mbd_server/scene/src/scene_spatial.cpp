#include "scene_spatial.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

#include "fsi/common/error.hpp"
#include "runtime_expression.hpp"

namespace fsi::scene::detail {
namespace {

// point_a / point_b of a two-point element, or `point` with an empty side.
ParameterSpec point_spec(const std::string& side, const std::string& where) {
  return vector(side.empty() ? std::string("point") : "point_" + side, 3, "m", where)
      .with_default({0.0, 0.0, 0.0});
}

// body_a/point_a and body_b/point_b of a spatial two-point element (body_b absent: the world).
std::vector<ParameterSpec> two_spatial_points(std::vector<ParameterSpec> more) {
  std::vector<ParameterSpec> parameters = {
      element_name_spec(), text("body_a", "name of a RigidBody3D, PointMass or AncfCable3D"),
      point_spec("a",
                 "point on body_a: body axes from the centre of mass; [s, 0, 0] on a cable; "
                 "[0, 0, 0] on a point mass"),
      text("body_b", "name of a spatial body; absent: the ground").optional(),
      point_spec("b", "point on body_b (as point_a) or in the world")};
  parameters.insert(parameters.end(), more.begin(), more.end());
  return parameters;
}

Eigen::Vector3d vector3(const View& element, std::string_view key) {
  const auto v = element.vector(key);
  return {v[0], v[1], v[2]};
}

std::string name_of(const View& element) {
  return element.has("name") ? element.string("name") : std::string();
}

}  // namespace

std::vector<BlockSpec> spatial_block_specs() {
  BlockSpec body_mesh = block_spec(
      "Mesh",
      "The triangles of an STL file fixed to the body (vertex = scale * STL point + offset, in the "
      "body axes from the centre of mass); they move with the body and feel the fluid.",
      {text("stl", "ASCII or binary STL file, relative to the scene"),
       number("scale", "", "the STL coordinates times this are metres")
           .above(0.0)
           .with_default(1.0),
       vector("offset", 3, "m", "added to every scaled STL point (body axes)")
           .with_default({0.0, 0.0, 0.0})});
  return {
      block_spec(
          "RigidBody3D",
          "A rigid body in space (natural coordinates: centre of mass and body axes, 12 "
          "coordinates with 6 orthonormality constraints; docs/theory.md). Its orientation is "
          "a rotation by `angle` about `axis` from the world axes.",
          {text("name", "unique name, used by joints and sensors"),
           number("mass", "kg", "mass").above(0.0),
           vector("inertia", 3, "kg m^2",
                  "principal moments about the body axes through the centre of mass (each less "
                  "than the sum of the other two)"),
           vector("position", 3, "m", "initial centre of mass").with_default({0.0, 0.0, 0.0}),
           vector("axis", 3, "", "rotation axis of the initial orientation")
               .with_default({0.0, 0.0, 1.0}),
           number("angle", "rad", "rotation angle of the initial orientation").with_default(0.0),
           vector("velocity", 3, "m/s", "initial velocity of the centre of mass")
               .with_default({0.0, 0.0, 0.0}),
           vector("angular_velocity", 3, "rad/s", "initial angular velocity (world axes)")
               .with_default({0.0, 0.0, 0.0})},
          {body_mesh.as_list()})
          .as_list(),
      block_spec("PointMass", "A point mass in space (3 coordinates); its one point is [0, 0, 0].",
                 {text("name", "unique name, used by joints and sensors"),
                  number("mass", "kg", "mass").above(0.0),
                  vector("position", 3, "m", "initial position").with_default({0.0, 0.0, 0.0}),
                  vector("velocity", 3, "m/s", "initial velocity").with_default({0.0, 0.0, 0.0})})
          .as_list(),
      block_spec(
          "AncfCable3D",
          "A spatial ANCF cable (Gerstmayr & Shabana 2006): straight and stress-free from start "
          "to end, at rest; 6 coordinates per node (position, slope); isotropic bending, no "
          "torsion. Its points are [s, 0, 0]. With radius > 0 it carries a closed tube mesh whose "
          "vertices follow the centre line (the fluid's force acts on the centre line).",
          {text("name", "unique name, used by clamps, joints and sensors"),
           vector("start", 3, "m", "first node (s = 0)"), vector("end", 3, "m", "last node"),
           integer("elements", "number of equal elements").at_least(1),
           number("axial_stiffness", "N", "EA").above(0.0),
           number("bending_stiffness", "N m^2", "EI").above(0.0),
           number("mass_per_length", "kg/m", "rho A").above(0.0),
           number("axial_damping", "N s", "N = EA eps + this * deps/dt")
               .at_least(0.0)
               .with_default(0.0),
           number("bending_damping", "N m^2 s", "M = EI kappa + this * dkappa/dt")
               .at_least(0.0)
               .with_default(0.0),
           number("radius", "m", "tube mesh radius (0: no mesh)").at_least(0.0).with_default(0.0),
           integer("tube_sides", "vertices around the tube").at_least(3).with_default(8),
           integer("tube_rings_per_element", "rings of vertices per element")
               .at_least(1)
               .with_default(4)})
          .as_list(),
      block_spec(
          "CableClamp",
          "Clamps a node of an AncfCable3D to the ground at its initial position and slope "
          "direction (5 rows: x, y, z, two slope rows; the axial stretch stays free).",
          {text("cable", "name of an AncfCable3D"),
           integer("node", "node index: 0 at start, elements at end").at_least(0).with_default(0)})
          .as_list(),
      block_spec("SphericalJoint", "Pins point_a of body_a to point_b (3 rows: x, y, z).",
                 two_spatial_points({}))
          .as_list(),
      block_spec(
          "RevoluteJoint3D",
          "A hinge: the points coincide and body_b turns relative to body_a about `axis` "
          "(in body_a's axes) only: 5 rows. Rigid bodies (or the ground as body_b).",
          two_spatial_points(
              {vector("axis", 3, "", "hinge axis in body_a's axes").with_default({0.0, 0.0, 1.0})}))
          .as_list(),
      block_spec("FixedJoint3D",
                 "Fixes `body` (a RigidBody3D) at its initial position and orientation relative "
                 "to `to` (6 rows; joint_force reads the force and torque it exerts on body).",
                 {element_name_spec(), text("body", "name of the fixed RigidBody3D"),
                  text("to", "name of the holding RigidBody3D; absent: the ground").optional()})
          .as_list(),
      block_spec(
          "SpringDamper3D",
          "Linear spring-damper between the two points: tension k (l - l0) + c dl/dt "
          "(spring_force sensors read it by name).",
          two_spatial_points({number("stiffness", "N/m", "k").at_least(0.0),
                              number("damping", "N s/m", "c").at_least(0.0).with_default(0.0),
                              number("rest_length", "m", "l0 (default: the initial distance)")
                                  .at_least(0.0)
                                  .optional()}))
          .as_list(),
      block_spec("PointForce3D",
                 "A world-frame force at a point of a spatial body, muParser expressions of the "
                 "time t [s] (evaluated at every stage time).",
                 {element_name_spec(), text("body", "name of a spatial body"),
                  point_spec("", "point of application (as point_a of the joints)"),
                  text("force_x", "x component [N] in t").with_default("0"),
                  text("force_y", "y component [N] in t").with_default("0"),
                  text("force_z", "z component [N] in t").with_default("0")})
          .as_list(),
      block_spec("Torque3D",
                 "A world-frame torque on a RigidBody3D, muParser expressions of the time t [s].",
                 {element_name_spec(), text("body", "name of a RigidBody3D"),
                  text("torque_x", "x component [N m] in t").with_default("0"),
                  text("torque_y", "y component [N m] in t").with_default("0"),
                  text("torque_z", "z component [N m] in t").with_default("0")})
          .as_list(),
      block_spec(
          "DistanceConstraint3D",
          "A massless rod between the two points (1 row; lambda is the rod force, tension "
          "positive).",
          two_spatial_points(
              {number("length", "m", "default: the initial distance").above(0.0).optional()}))
          .as_list(),
  };
}

std::vector<std::string> spatial_block_names() {
  std::vector<std::string> names;
  for (const BlockSpec& spec : spatial_block_specs())
    names.push_back(spec.name);
  return names;
}

void build_spatial_bodies(const View& root, SpatialBodyBuilder& builder) {
  mbd::Model& model = builder.model;
  // A body that fails is skipped by name, so that elements naming it are skipped too.
  auto begin_body = [&](const View& element) {
    const Parameter* name_given = element.raw().find("name");
    if (name_given && name_given->failed) builder.unnamed_body_skipped = true;
  };
  // The name goes on the skipped list as soon as it is read, and off it once the body exists:
  // a body that fails on any value skips the elements that name it.
  auto begin_named = [&](const View& element) {
    builder.skipped_bodies.push_back(element.string("name"));
  };
  auto add_body = [&](const View& element, auto&& add) {
    std::optional<mbd::BodyId> id;
    try {
      id = add();
    } catch (const Error& error) {
      builder.problem(element.location("name"), error.fault(), error.remedy());
      return id;
    }
    builder.skipped_bodies.pop_back();
    return id;
  };
  for (const View& body : root.blocks("RigidBody3D")) {
    begin_body(body);
    std::optional<mbd::BodyId> id;
    builder.guard(body.location(), [&] {
      mbd::RigidBody3DSpec spec;
      begin_named(body);
      spec.name = body.string("name");
      spec.mass = body.number("mass");
      spec.inertia = vector3(body, "inertia").asDiagonal();
      spec.position = vector3(body, "position");
      const Eigen::Vector3d axis = vector3(body, "axis");
      if (!(axis.norm() > 0.0)) {
        builder.problem(body.location("axis"), "the rotation axis is zero",
                        "give a non-zero axis, e.g. [0, 0, 1]");
        return;
      }
      spec.orientation = Eigen::AngleAxisd(body.number("angle"), axis.normalized()).matrix();
      spec.velocity = vector3(body, "velocity");
      spec.angular_velocity = vector3(body, "angular_velocity");
      id = add_body(body, [&] { return model.add_rigid_body_3d(spec); });
    });
    if (!id) continue;
    for (const View& mesh : body.blocks("Mesh")) {
      builder.guard(mesh.location(), [&] {
        const std::optional<TriangleMesh> surface = builder.read_stl(mesh, "stl");
        if (!surface) return;
        const double scale = mesh.number("scale");
        const Eigen::Vector3d offset = vector3(mesh, "offset");
        const auto first = static_cast<std::uint32_t>(model.marker_count());
        for (const Point3& vertex : surface->vertices) {
          model.add_spatial_marker(
              *id, Eigen::Vector3d(vertex[0], vertex[1], vertex[2]) * scale + offset);
        }
        for (const auto& triangle : surface->triangles) {
          for (std::uint32_t corner : triangle)
            builder.boundary.triangles.push_back(first + corner);
        }
      });
    }
  }
  for (const View& mass : root.blocks("PointMass")) {
    begin_body(mass);
    builder.guard(mass.location(), [&] {
      mbd::PointMassSpec spec;
      begin_named(mass);
      spec.name = mass.string("name");
      spec.mass = mass.number("mass");
      spec.position = vector3(mass, "position");
      spec.velocity = vector3(mass, "velocity");
      add_body(mass, [&] { return model.add_point_mass(spec); });
    });
  }
  for (const View& cable : root.blocks("AncfCable3D")) {
    begin_body(cable);
    builder.guard(cable.location(), [&] {
      mbd::AncfCableSpec spec;
      begin_named(cable);
      spec.name = cable.string("name");
      spec.start = vector3(cable, "start");
      spec.end = vector3(cable, "end");
      spec.element_count = static_cast<int>(cable.integer("elements"));
      spec.axial_stiffness = cable.number("axial_stiffness");
      spec.bending_stiffness = cable.number("bending_stiffness");
      spec.mass_per_length = cable.number("mass_per_length");
      spec.axial_damping = cable.number("axial_damping");
      spec.bending_damping = cable.number("bending_damping");
      const std::optional<mbd::BodyId> id =
          add_body(cable, [&] { return model.add_ancf_cable(spec); });
      const double radius = cable.number("radius");
      if (!id || radius == 0.0) return;
      // Rings of `sides` vertices at s_i = L i / rings, quads split into two triangles, and a
      // fan closing each end around a centre-line vertex.
      const auto sides = static_cast<std::uint32_t>(cable.integer("tube_sides"));
      const auto rings =
          static_cast<std::uint32_t>(spec.element_count * cable.integer("tube_rings_per_element"));
      const double length = (spec.end - spec.start).norm();
      const auto first = static_cast<std::uint32_t>(model.marker_count());
      for (std::uint32_t i = 0; i <= rings; ++i) {
        const double s = i == rings ? length : length * i / rings;
        for (std::uint32_t k = 0; k < sides; ++k)
          model.add_cable_surface_marker(*id, s, 2.0 * std::numbers::pi * k / sides, radius);
      }
      auto vertex = [&](std::uint32_t ring, std::uint32_t side) {
        return first + ring * sides + side % sides;
      };
      auto& triangles = builder.boundary.triangles;
      for (std::uint32_t i = 0; i < rings; ++i) {
        for (std::uint32_t k = 0; k < sides; ++k) {
          triangles.insert(triangles.end(), {vertex(i, k), vertex(i + 1, k), vertex(i + 1, k + 1)});
          triangles.insert(triangles.end(), {vertex(i, k), vertex(i + 1, k + 1), vertex(i, k + 1)});
        }
      }
      const auto start_centre =
          static_cast<std::uint32_t>(model.add_spatial_marker(*id, {0, 0, 0}));
      const auto end_centre =
          static_cast<std::uint32_t>(model.add_spatial_marker(*id, {length, 0.0, 0.0}));
      for (std::uint32_t k = 0; k < sides; ++k) {
        triangles.insert(triangles.end(), {start_centre, vertex(0, k + 1), vertex(0, k)});
        triangles.insert(triangles.end(), {end_centre, vertex(rings, k), vertex(rings, k + 1)});
      }
    });
  }
}

void build_spatial_connectors(const View& root, ElementBuilder& builder) {
  mbd::Model& model = builder.model;
  auto point = [&](const View& element, const std::string& side) {
    mbd::SpatialPointSpec spec;
    if (side == "a" || element.has("body_b"))
      spec.body = builder.find_body(element, "body_" + side);
    spec.local = vector3(element, "point_" + side);
    return spec;
  };
  for (const View& c : root.blocks("CableClamp")) {
    builder.guard(c.location(), [&] {
      const mbd::BodyId cable = builder.find_body(c, "cable");
      const auto node = static_cast<int>(c.integer("node"));
      builder.placed(c, [&] { model.add_cable_clamp(cable, node); });
    });
  }
  for (const View& j : root.blocks("SphericalJoint")) {
    builder.guard(j.location(), [&] {
      const auto a = point(j, "a");
      const auto b = point(j, "b");
      int row = 0;
      builder.placed(j, [&] { row = model.add_spherical_joint(a, b, name_of(j)); });
      register_joint(builder, j, {row, 3, a.body, "spherical joint"});
    });
  }
  for (const View& j : root.blocks("RevoluteJoint3D")) {
    builder.guard(j.location(), [&] {
      mbd::RevoluteJoint3DSpec spec;
      spec.name = name_of(j);
      spec.a = point(j, "a");
      spec.b = point(j, "b");
      spec.axis = vector3(j, "axis");
      int row = 0;
      builder.placed(j, [&] { row = model.add_revolute_joint_3d(spec); });
      register_joint(builder, j, {row, 5, spec.a.body, "revolute joint"});
    });
  }
  for (const View& j : root.blocks("FixedJoint3D")) {
    builder.guard(j.location(), [&] {
      mbd::FixedJoint3DSpec spec;
      spec.name = name_of(j);
      spec.body = builder.find_body(j, "body");
      if (j.has("to")) spec.to = builder.find_body(j, "to");
      int row = 0;
      builder.placed(j, [&] { row = model.add_fixed_joint_3d(spec); });
      register_joint(builder, j, {row, 6, spec.body, "fixed joint"});
    });
  }
  for (const View& f : root.blocks("SpringDamper3D")) {
    builder.guard(f.location(), [&] {
      mbd::SpatialSpringDamperSpec spec;
      spec.name = name_of(f);
      spec.a = point(f, "a");
      spec.b = point(f, "b");
      spec.stiffness = f.number("stiffness");
      spec.damping = f.number("damping");
      if (f.has("rest_length")) spec.rest_length = f.number("rest_length");
      int index = 0;
      builder.placed(f, [&] { index = model.add_spatial_spring_damper(spec); });
      register_force_element(builder, f, index, false);
    });
  }
  for (const View& p : root.blocks("PointForce3D")) {
    builder.guard(p.location(), [&] {
      mbd::SpatialPointForceSpec spec;
      spec.name = name_of(p);
      spec.point = {builder.find_body(p, "body"), vector3(p, "point")};
      const RuntimeExpression x = expression(p, "force_x", {"t"});
      const RuntimeExpression y = expression(p, "force_y", {"t"});
      const RuntimeExpression z = expression(p, "force_z", {"t"});
      spec.force = [x, y, z](double t) { return Eigen::Vector3d(x(t), y(t), z(t)); };
      builder.placed(p, [&] { model.add_spatial_point_force(spec); });
    });
  }
  for (const View& p : root.blocks("Torque3D")) {
    builder.guard(p.location(), [&] {
      mbd::SpatialTorqueSpec spec;
      spec.name = name_of(p);
      spec.body = builder.find_body(p, "body");
      const RuntimeExpression x = expression(p, "torque_x", {"t"});
      const RuntimeExpression y = expression(p, "torque_y", {"t"});
      const RuntimeExpression z = expression(p, "torque_z", {"t"});
      spec.torque = [x, y, z](double t) { return Eigen::Vector3d(x(t), y(t), z(t)); };
      builder.placed(p, [&] { model.add_spatial_torque(spec); });
    });
  }
  for (const View& c : root.blocks("DistanceConstraint3D")) {
    builder.guard(c.location(), [&] {
      const auto a = point(c, "a");
      const auto b = point(c, "b");
      std::optional<double> length;
      if (c.has("length")) length = c.number("length");
      int row = 0;
      builder.placed(
          c, [&] { row = model.add_spatial_distance_constraint(a, b, length, name_of(c)); });
      register_joint(builder, c, {row, 1, a.body, "distance constraint"});
    });
  }
}

}  // namespace fsi::scene::detail
