// The surface the fluid sees: polyline meshes (2D, on bodies and the ground) and the static
// ground triangles of STL files (3D). Built after every body, so that the ground's (static)
// vertices follow the bodies' (dynamic) ones.

#include "fsi/common/error.hpp"
#include "fsi/scene/rounded_corners.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

std::vector<BlockSpec> mesh_blocks() {
  const BlockSpec ground_mesh = block_spec(
      "Mesh",
      "2D: surface line segments through the given world points (thesis §4.3); 3D: the "
      "triangles of an STL file (either orientation: the fix treats both sides alike).",
      {matrix("points", 2, "m",
              "2D: polyline vertices, one [x, y] per row; a row [x, y, r] rounds the corner "
              "there with an arc of radius r (docs/user-guide.md, \"Rounded corners\")")
           .or_rows_of(3)
           .optional(),
       integer("closed", "1: also join the last point to the first").with_default(0).between(0, 1),
       text("stl", "3D: ASCII or binary STL file, relative to the scene").optional(),
       number("scale", "", "3D: the STL coordinates times this are metres")
           .positive()
           .with_default(1.0),
       vector("offset", 3, "m", "3D: added to every scaled STL vertex")
           .with_default({0.0, 0.0, 0.0})});
  return {block_spec("Ground",
                     "Static geometry fixed in space (its meshes are static boundary vertices).",
                     {text("name",
                           "a name for this block's meshes: a WallPressureProbe's `mesh` may "
                           "name it to read them alone (a wall of the tank, not every Ground "
                           "mesh); not a body's name, nor \"ground\"")
                          .optional()},
                     {ground_mesh.as_list()})
              .as_list()};
}

// A 3D ground mesh: the STL's triangles, scaled and shifted, as static vertices.
void add_ground_surface(SceneBuilder& builder, const View& mesh) {
  if (mesh.has("points")) {
    builder.problem(mesh.location("points"),
                    "a 3D Ground mesh is read from an STL file, not from points",
                    "write stl = \"file.stl\" (optional scale, offset = [x, y, z])");
  }
  if (!mesh.has("stl")) {
    if (!mesh.has("points")) {
      builder.problem(mesh.location(), "a 3D Ground mesh needs an STL file",
                      "add stl = \"file.stl\"");
    }
    return;
  }
  const std::optional<TriangleMesh> surface = builder.read_stl(mesh, "stl");
  if (!surface) return;
  const double scale = mesh.number("scale");
  const auto offset = mesh.vector("offset");
  BoundaryMesh& boundary = builder.scene.boundary;
  const auto first = static_cast<std::uint32_t>(boundary.dynamic_vertex_count +
                                                boundary.static_positions.size() / 3);
  for (const Point3& vertex : surface->vertices) {
    for (std::size_t k = 0; k < 3; ++k)
      boundary.static_positions.push_back(scale * vertex[k] + offset[k]);
  }
  for (const auto& triangle : surface->triangles) {
    for (std::uint32_t corner : triangle)
      boundary.triangles.push_back(first + corner);
  }
}

// A coupled scene needs something for the fluid to push against; a run of the structure alone
// does not.
void require_surface(SceneBuilder& builder) {
  if (builder.mode != SceneMode::Coupled) return;
  // 3D: a Ground mesh that gave no triangles has its own problem (no STL, unreadable file).
  bool surface_given = false;
  for (const View& ground : builder.root.blocks("Ground"))
    surface_given = surface_given || (builder.spatial() && ground.has_block("Mesh"));
  // A beam without a thickness has its own problem (family_planar_bodies.cpp).
  for (const View& beam : builder.blocks("AncfBeam2D"))
    surface_given = surface_given || !beam.has("thickness");
  if (builder.scene.boundary.elements().empty() && !builder.skipped_any() && !surface_given) {
    builder.problem(builder.scene.parameters.location,
                    "the scene has no surface mesh: the fluid would see no structure",
                    builder.spatial() ? "add Ground { Mesh { stl = \"file.stl\" } }, or run the "
                                        "structure alone with --mbd-only"
                                      : "add Mesh { points = ... } to bodies or Ground, or run "
                                        "the structure alone with --mbd-only");
  }
}

// The boundary mesh's elements so far (its segments in 2D, triangles in 3D).
std::size_t element_count(const SceneBuilder& builder) {
  const BoundaryMesh& boundary = builder.scene.boundary;
  return builder.spatial() ? boundary.triangles.size() / 3 : boundary.segments.size() / 2;
}

// Is a Ground block's name one a WallPressureProbe can tell from the others?
bool ground_name_is_free(SceneBuilder& builder, const View& ground, const std::string& name) {
  const auto taken = [&](const std::string& why) {
    builder.problem(ground.location("name"), "Ground '" + name + "': " + why,
                    "give this Ground block another name");
    return false;
  };
  if (name.empty()) return taken("the name is empty");
  if (name == "ground") return taken("\"ground\" names every Ground mesh at once");
  if (builder.names.ground_meshes.count(name) != 0) return taken("another Ground has this name");
  for (int body = 0; body < builder.model.body_count(); ++body) {
    if (builder.model.body_name(body) == name) return taken("a body has this name");
  }
  return true;
}

void build_meshes(SceneBuilder& builder) {
  BoundaryMesh& boundary = builder.scene.boundary;
  boundary.dynamic_vertex_count = static_cast<std::size_t>(builder.model.marker_count());
  for (const View& ground : builder.root.blocks("Ground")) {
    const std::size_t first = element_count(builder);
    for (const View& mesh : ground.blocks("Mesh")) {
      builder.guard(mesh.location(), [&] {
        if (builder.spatial()) {
          add_ground_surface(builder, mesh);
        } else {
          add_polyline_mesh(builder, mesh, mbd::kGround);
        }
      });
    }
    if (!ground.has("name")) continue;
    const std::string& name = ground.string("name");
    if (!ground_name_is_free(builder, ground, name)) continue;
    const std::size_t end = element_count(builder);
    auto& ranges = builder.names.ground_meshes[name];
    if (end > first)
      ranges.emplace_back(static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(end));
  }
  boundary.vertex_count = static_cast<std::size_t>(builder.model.marker_count()) +
                          (builder.spatial() ? boundary.static_positions.size() / 3 : 0);
  require_surface(builder);
}

}  // namespace

void add_polyline_mesh(SceneBuilder& builder, const View& mesh, mbd::BodyId body) {
  if (mesh.has("stl")) {
    builder.problem(mesh.location("stl"), "STL meshes need a 3D scene (dimension = 2 here)",
                    "set dimension = 3 at the top of the scene, or give points = [[x, y], ...]");
    return;
  }
  if (!mesh.has("points")) {
    builder.problem(mesh.location(), "a 2D mesh needs points",
                    "add points = [[x, y], [x, y], ...]");
    return;
  }
  if (mesh.matrix("points").size() < 2) {
    builder.problem(mesh.location("points"), "a mesh needs at least 2 points", "add points");
    return;
  }
  const bool closed = mesh.integer("closed") == 1;
  std::vector<Point2> points;
  try {
    points = round_corners(outline_points(mesh.matrix("points")), closed);
  } catch (const Error& error) {
    builder.problem(mesh.location("points"), error.fault(), error.remedy());
    return;
  }
  mbd::Model& model = builder.model;
  const auto first = static_cast<std::uint32_t>(model.marker_count());
  for (const Point2& point : points)
    model.add_marker(body, {point[0], point[1]});
  const auto count = static_cast<std::uint32_t>(points.size());
  auto& segments = builder.scene.boundary.segments;
  for (std::uint32_t k = 0; k + 1 < count; ++k)
    segments.insert(segments.end(), {first + k, first + k + 1});
  if (closed && count > 2) segments.insert(segments.end(), {first + count - 1, first});
}

ElementFamily meshes_family() {
  return {"meshes", mesh_blocks, {build_meshes}};
}

}  // namespace fsi::scene::detail
