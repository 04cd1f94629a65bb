// Planar bodies: RigidBody2D (with its polyline meshes) and AncfBeam2D (with the closed outline of
// its two faces as its mesh).

#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

BlockSpec body_mesh_spec() {
  return block_spec("Mesh",
                    "Surface line segments through the given points (body coordinates on a body, "
                    "world coordinates on the ground), thesis §4.3.",
                    {matrix("points", 2, "m",
                            "polyline vertices, one [x, y] per row; a row [x, y, r] rounds the "
                            "corner there with an arc of radius r (docs/user-guide.md, "
                            "\"Rounded corners\")")
                         .or_rows_of(3),
                     integer("closed", "1: also join the last point to the first")
                         .with_default(0)
                         .between(0, 1)})
      .as_list();
}

std::vector<BlockSpec> planar_body_blocks() {
  return {
      block_spec(
          "RigidBody2D", "A planar rigid body; coordinates x, y, angle of its centre of mass.",
          {text("name", "unique name, used by constraints and sensors"),
           number("mass", "kg/m", "mass (per unit depth in 2D)").positive(),
           number("inertia", "kg m", "moment of inertia about the centre of mass (per unit depth)")
               .positive(),
           vector("position", 2, "m", "initial centre of mass").with_default({0.0, 0.0}),
           number("angle", "rad", "initial angle").with_default(0.0),
           vector("velocity", 2, "m/s", "initial velocity").with_default({0.0, 0.0}),
           number("angular_velocity", "rad/s", "initial angular velocity").with_default(0.0)},
          {body_mesh_spec()})
          .as_list()
          .planar(),
      block_spec(
          "AncfBeam2D",
          "A planar ANCF beam (Gerstmayr's elastic line, docs/theory.md): straight and "
          "stress-free from start to end, at rest unless given a rigid initial motion (velocity, "
          "angular_velocity); 4 coordinates per node (x, y, slope x, slope y). Its points (joints, "
          "springs) are [s, eta]: s along the undeformed centre line "
          "from start, eta along the deformed line's normal, left of start -> end. Its surface "
          "mesh is the closed outline of both faces eta = +-thickness/2.",
          {text("name", "unique name, used by clamps, joints and sensors"),
           vector("start", 2, "m", "first node (s = 0)"),
           vector("end", 2, "m", "last node (s = L)"),
           integer("elements", "number of equal elements").at_least(1),
           number("axial_stiffness", "N/m",
                  "EA (per unit depth in 2D; a plate in plane strain: E h / (1 - nu^2))")
               .positive(),
           number("bending_stiffness", "N m",
                  "EI (per unit depth in 2D; a plate in plane strain: the plate's D = E h^3 / "
                  "(12 (1 - nu^2)))")
               .positive(),
           number("mass_per_length", "kg/m^2", "rho A (per unit depth in 2D)").positive(),
           number("axial_damping", "N s/m", "viscous axial damping: N = EA eps + this * deps/dt")
               .at_least(0.0)
               .with_default(0.0),
           number("bending_damping", "N m s",
                  "viscous bending damping: M = EI kappa + this * dkappa/dt")
               .at_least(0.0)
               .with_default(0.0),
           number("thickness", "m",
                  "h: distance of the two faces the mesh follows; needed for the mesh of a "
                  "coupled run, not by --mbd-only (a beam without it has no mesh there)")
               .positive()
               .optional(),
           integer("face_points_per_element",
                   "mesh segments per element on each face (0: no surface mesh)")
               .at_least(0)
               .with_default(4),
           vector("velocity", 2, "m/s",
                  "initial velocity of the start (s = 0); with angular_velocity a rigid motion "
                  "of the whole beam, without strain rate")
               .with_default({0.0, 0.0}),
           number("angular_velocity", "rad/s",
                  "initial angular velocity about the start: a point r moves at velocity + "
                  "angular_velocity z x (r - start)")
               .with_default(0.0)})
          .as_list()
          .planar(),
  };
}

void build_rigid_body(SceneBuilder& builder, const View& body) {
  const std::optional<mbd::BodyId> id = builder.add_body(body, [&] {
    mbd::RigidBody2DSpec spec;
    spec.name = body.string("name");
    spec.mass = body.number("mass");
    spec.inertia = body.number("inertia");
    const auto position = body.vector("position");
    const auto velocity = body.vector("velocity");
    spec.position = {position[0], position[1]};
    spec.velocity = {velocity[0], velocity[1]};
    spec.angle = body.number("angle");
    spec.angular_velocity = body.number("angular_velocity");
    return std::optional<mbd::BodyId>(builder.model.add_rigid_body(spec));
  });
  if (!id) return;
  for (const View& mesh : body.blocks("Mesh"))
    builder.guard(mesh.location(), [&] { add_polyline_mesh(builder, mesh, *id); });
}

// The beam's surface: the closed outline, the upper face from s = 0 to L, the lower face back.
void add_beam_outline(SceneBuilder& builder, mbd::BodyId beam, const mbd::AncfBeamSpec& spec,
                      double half_thickness, int per_element) {
  mbd::Model& model = builder.model;
  const double length = (spec.end - spec.start).norm();
  const int count = spec.element_count * per_element;
  const auto first = static_cast<std::uint32_t>(model.marker_count());
  for (int k = 0; k <= count; ++k)
    model.add_marker(beam, {length * k / count, half_thickness});
  for (int k = count; k >= 0; --k)
    model.add_marker(beam, {length * k / count, -half_thickness});
  const auto vertices = static_cast<std::uint32_t>(2 * (count + 1));
  auto& segments = builder.scene.boundary.segments;
  for (std::uint32_t k = 0; k < vertices; ++k)
    segments.insert(segments.end(), {first + k, first + (k + 1) % vertices});
}

void build_beam(SceneBuilder& builder, const View& beam) {
  mbd::AncfBeamSpec spec;
  const std::optional<mbd::BodyId> id = builder.add_body(beam, [&] {
    spec.name = beam.string("name");
    const auto start = beam.vector("start");
    const auto end = beam.vector("end");
    spec.start = {start[0], start[1]};
    spec.end = {end[0], end[1]};
    spec.element_count = static_cast<int>(beam.integer("elements"));
    spec.axial_stiffness = beam.number("axial_stiffness");
    spec.bending_stiffness = beam.number("bending_stiffness");
    spec.mass_per_length = beam.number("mass_per_length");
    spec.axial_damping = beam.number("axial_damping");
    spec.bending_damping = beam.number("bending_damping");
    const auto velocity = beam.vector("velocity");
    spec.velocity = {velocity[0], velocity[1]};
    spec.angular_velocity = beam.number("angular_velocity");
    // Read before the beam exists: a value in error skips the beam, not just its mesh.
    if (beam.has("thickness")) (void)beam.number("thickness");
    (void)beam.integer("face_points_per_element");
    return std::optional<mbd::BodyId>(builder.model.add_ancf_beam(spec));
  });
  if (!id) return;
  const auto per_element = static_cast<int>(beam.integer("face_points_per_element"));
  if (per_element == 0) return;
  if (!beam.has("thickness")) {
    // The structure alone needs no surface; the fluid would not see a beam without one.
    if (builder.mode == SceneMode::MbdOnly) return;
    builder.problem(beam.location(),
                    "AncfBeam2D '" + spec.name +
                        "' has no thickness: a coupled run needs it for the beam's surface mesh "
                        "(its faces at eta = +-thickness/2), which the fluid sees",
                    "give thickness = h, or face_points_per_element = 0 for a beam the fluid "
                    "does not touch");
    return;
  }
  add_beam_outline(builder, *id, spec, 0.5 * beam.number("thickness"), per_element);
}

void build_planar_bodies(SceneBuilder& builder) {
  for (const View& body : builder.blocks("RigidBody2D"))
    build_rigid_body(builder, body);
  for (const View& beam : builder.blocks("AncfBeam2D"))
    build_beam(builder, beam);
}

}  // namespace

ElementFamily planar_bodies_family() {
  return {"planar bodies", planar_body_blocks, {build_planar_bodies}};
}

}  // namespace fsi::scene::detail
