// Spatial bodies: RigidBody3D (with STL meshes in its body frame), PointMass, AncfCable3D (with a
// tube mesh). Their markers are the dynamic boundary vertices of a 3D scene.

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

std::vector<BlockSpec> spatial_body_blocks() {
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
          .as_list()
          .spatial(),
      block_spec("PointMass", "A point mass in space (3 coordinates); its one point is [0, 0, 0].",
                 {text("name", "unique name, used by joints and sensors"),
                  number("mass", "kg", "mass").above(0.0),
                  vector("position", 3, "m", "initial position").with_default({0.0, 0.0, 0.0}),
                  vector("velocity", 3, "m/s", "initial velocity").with_default({0.0, 0.0, 0.0})})
          .as_list()
          .spatial(),
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
          .as_list()
          .spatial(),
  };
}

void build_rigid_body_3d(SceneBuilder& builder, const View& body) {
  mbd::Model& model = builder.model;
  const std::optional<mbd::BodyId> id = builder.add_body(body, [&]() -> std::optional<mbd::BodyId> {
    mbd::RigidBody3DSpec spec;
    spec.name = body.string("name");
    spec.mass = body.number("mass");
    spec.inertia = vector3(body, "inertia").asDiagonal();
    spec.position = vector3(body, "position");
    const Eigen::Vector3d axis = vector3(body, "axis");
    if (!(axis.norm() > 0.0)) {
      builder.problem(body.location("axis"), "the rotation axis is zero",
                      "give a non-zero axis, e.g. [0, 0, 1]");
      return std::nullopt;
    }
    spec.orientation = Eigen::AngleAxisd(body.number("angle"), axis.normalized()).matrix();
    spec.velocity = vector3(body, "velocity");
    spec.angular_velocity = vector3(body, "angular_velocity");
    return model.add_rigid_body_3d(spec);
  });
  if (!id) return;
  for (const View& mesh : body.blocks("Mesh")) {
    builder.guard(mesh.location(), [&] {
      const std::optional<TriangleMesh> surface = builder.read_stl(mesh, "stl");
      if (!surface) return;
      const double scale = mesh.number("scale");
      const Eigen::Vector3d offset = vector3(mesh, "offset");
      const auto first = static_cast<std::uint32_t>(model.marker_count());
      for (const Point3& vertex : surface->vertices) {
        model.add_spatial_marker(*id,
                                 Eigen::Vector3d(vertex[0], vertex[1], vertex[2]) * scale + offset);
      }
      for (const auto& triangle : surface->triangles) {
        for (std::uint32_t corner : triangle)
          builder.scene.boundary.triangles.push_back(first + corner);
      }
    });
  }
}

void build_point_mass(SceneBuilder& builder, const View& mass) {
  builder.add_body(mass, [&] {
    mbd::PointMassSpec spec;
    spec.name = mass.string("name");
    spec.mass = mass.number("mass");
    spec.position = vector3(mass, "position");
    spec.velocity = vector3(mass, "velocity");
    return std::optional<mbd::BodyId>(builder.model.add_point_mass(spec));
  });
}

// Rings of `sides` vertices at s_i = L i / rings, quads split into two triangles, and a fan
// closing each end around a centre-line vertex.
void add_cable_tube(SceneBuilder& builder, mbd::BodyId cable, const View& block,
                    const mbd::AncfCableSpec& spec, double radius) {
  mbd::Model& model = builder.model;
  const auto sides = static_cast<std::uint32_t>(block.integer("tube_sides"));
  const auto rings =
      static_cast<std::uint32_t>(spec.element_count * block.integer("tube_rings_per_element"));
  const double length = (spec.end - spec.start).norm();
  const auto first = static_cast<std::uint32_t>(model.marker_count());
  for (std::uint32_t i = 0; i <= rings; ++i) {
    const double s = i == rings ? length : length * i / rings;
    for (std::uint32_t k = 0; k < sides; ++k)
      model.add_cable_surface_marker(cable, s, 2.0 * std::numbers::pi * k / sides, radius);
  }
  auto vertex = [&](std::uint32_t ring, std::uint32_t side) {
    return first + ring * sides + side % sides;
  };
  auto& triangles = builder.scene.boundary.triangles;
  for (std::uint32_t i = 0; i < rings; ++i) {
    for (std::uint32_t k = 0; k < sides; ++k) {
      triangles.insert(triangles.end(), {vertex(i, k), vertex(i + 1, k), vertex(i + 1, k + 1)});
      triangles.insert(triangles.end(), {vertex(i, k), vertex(i + 1, k + 1), vertex(i, k + 1)});
    }
  }
  const auto start_centre = static_cast<std::uint32_t>(model.add_spatial_marker(cable, {0, 0, 0}));
  const auto end_centre =
      static_cast<std::uint32_t>(model.add_spatial_marker(cable, {length, 0.0, 0.0}));
  for (std::uint32_t k = 0; k < sides; ++k) {
    triangles.insert(triangles.end(), {start_centre, vertex(0, k + 1), vertex(0, k)});
    triangles.insert(triangles.end(), {end_centre, vertex(rings, k), vertex(rings, k + 1)});
  }
}

void build_cable(SceneBuilder& builder, const View& cable) {
  mbd::AncfCableSpec spec;
  const std::optional<mbd::BodyId> id = builder.add_body(cable, [&] {
    spec.name = cable.string("name");
    spec.start = vector3(cable, "start");
    spec.end = vector3(cable, "end");
    spec.element_count = static_cast<int>(cable.integer("elements"));
    spec.axial_stiffness = cable.number("axial_stiffness");
    spec.bending_stiffness = cable.number("bending_stiffness");
    spec.mass_per_length = cable.number("mass_per_length");
    spec.axial_damping = cable.number("axial_damping");
    spec.bending_damping = cable.number("bending_damping");
    return std::optional<mbd::BodyId>(builder.model.add_ancf_cable(spec));
  });
  if (!id) return;
  builder.guard(cable.location(), [&] {
    const double radius = cable.number("radius");
    if (radius > 0.0) add_cable_tube(builder, *id, cable, spec, radius);
  });
}

void build_spatial_bodies(SceneBuilder& builder) {
  for (const View& body : builder.blocks("RigidBody3D"))
    build_rigid_body_3d(builder, body);
  for (const View& mass : builder.blocks("PointMass"))
    build_point_mass(builder, mass);
  for (const View& cable : builder.blocks("AncfCable3D"))
    build_cable(builder, cable);
}

}  // namespace

ElementFamily spatial_bodies_family() {
  return {"spatial bodies", spatial_body_blocks, {build_spatial_bodies}};
}

}  // namespace fsi::scene::detail
