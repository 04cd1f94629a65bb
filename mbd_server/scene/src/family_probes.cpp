// Probes: measurements of the fluid itself, evaluated by fsi-client where the particles are and
// written as columns of sensors.csv at every sensor row (docs/user-guide.md, "Probes"). One block
// per probe kind (the kinds' rules live in fsi::probes, one file each); their columns are named
// by fsi::probes::columns, and must not collide with a sensor's or another probe's.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "distances.hpp"
#include "fsi/probes/probe.hpp"
#include "fsi/scene/scene.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

ParameterSpec probe_name_spec() {
  return text("name", "the probe's name: its columns of sensors.csv start with it");
}

// Probes with a place in space may move with a rigid body (protocol 1.4).
ParameterSpec probe_body_spec() {
  return text("body",
              "a RigidBody2D or RigidBody3D the probe moves with: its coordinates are given where "
              "the body starts (the initial configuration) and follow the body's translation and "
              "rotation; absent: fixed in space")
      .optional();
}

std::vector<BlockSpec> probe_blocks() {
  return {
      block_spec("FluidEnergyProbe",
                 "Kinetic energy sum m v^2/2 and potential energy sum m (-g).(x - datum) of every "
                 "particle [J/m; 3D J]: columns NAME_kinetic, NAME_potential.",
                 {probe_name_spec(),
                  per_dimension(
                      vector("datum", 2, "m", "the point of zero potential energy (3D: [x, y, z])"))
                      .optional()})
          .as_list()
          .for_coupled_runs(),
      block_spec(
          "PointProbe",
          "Velocity and pressure at a point, Shepard-normalised SPH interpolation with "
          "LIGGGHTS' kernel and smoothing length: columns NAME_vx, NAME_vy (3D NAME_vz) "
          "[m/s], NAME_pressure [Pa], NAME_particles (within the kernel's support) and "
          "NAME_wet (0: no particle there; velocity and pressure then read 0).",
          {probe_name_spec(), per_dimension(vector("point", 2, "m", "where (3D: [x, y, z])")),
           probe_body_spec()})
          .as_list()
          .for_coupled_runs(),
      block_spec("FreeSurfaceProbe",
                 "Free-surface elevation on a vertical line (along y; 3D along z): the highest "
                 "point where the kernel sum of the fluid falls through 1/2, scanned from the "
                 "line's bottom up: columns NAME_elevation [m] and NAME_wet (0: no fluid on the "
                 "line; the elevation then reads the bottom).",
                 {probe_name_spec(),
                  per_dimension(vector("bottom", 2, "m",
                                       "the line's lower end (3D: [x, y, z]); it runs upwards")),
                  number("length", "m", "the line's length above its bottom").positive(),
                  integer("samples", "points scanned on the line (resolution length/(samples-1))")
                      .with_default(200.0)
                      .between(2.0, 100000.0),
                  probe_body_spec()})
          .as_list()
          .for_coupled_runs(),
      block_spec("FrontProbe",
                 "The foremost fluid along an axis: the largest (or smallest) coordinate of a "
                 "particle with at least min_neighbours others within 2 d (d the particle "
                 "spacing), so that spray ahead of the front is ignored: columns NAME_position "
                 "[m] and NAME_wet (0: no such particle; the position then reads 0).",
                 {probe_name_spec(),
                  text("axis", "x, y (3D also z)").one_of({"x", "y", "z"}).with_default("x"),
                  text("direction", "increasing: the largest coordinate; decreasing: the smallest")
                      .one_of({"increasing", "decreasing"})
                      .with_default("increasing"),
                  integer("min_neighbours", "neighbours within 2 d a particle needs to count")
                      .with_default(3.0)
                      .between(0.0, 1000.0)})
          .as_list()
          .for_coupled_runs(),
      block_spec("FluxProbe",
                 "Volume flux through a segment (2D, per unit depth) or a planar polygon (3D): the "
                 "integral over the section of the kernel-interpolated sum V_j W v_j.n (no "
                 "Shepard normalisation: a dry part of the section counts 0): column NAME_flux "
                 "[m^2/s; 3D m^3/s]. n: 2D the segment's direction turned clockwise (a segment "
                 "drawn upwards counts flow in +x); 3D the right-hand rule of the points' order.",
                 {probe_name_spec(),
                  per_dimension(matrix("points", 2, "m",
                                       "2D: the segment's two points [[x, y], [x, y]]; 3D: the "
                                       "polygon's corners in order, [[x, y, z], ...]")),
                  integer("samples",
                          "midpoint-rule pieces of the segment (3D: per side of each triangle of "
                          "the polygon's fan)")
                      .with_default(40.0)
                      .between(1.0, 1000.0),
                  probe_body_spec()})
          .as_list()
          .for_coupled_runs(),
      block_spec(
          "WallPressureProbe",
          "The normal force per length (3D: per area) of the fluid on a patch of a boundary mesh, "
          "from the wall law's forces at its sampling points (fix fsi/sph): the sampling points of "
          "the mesh's elements within `radius` of `centre` (a patch fixed in space, or moving "
          "with `body`), each "
          "element's normal turned to `fluid_side`: columns NAME_pressure [Pa] (positive: the "
          "fluid pushes on the wall), NAME_force [N/m; 3D N] (the normal force on the patch) and "
          "NAME_pairs (particle-sampling point pairs within the wall law's range; 0: the patch "
          "is dry, pressure and force then read 0).",
          {probe_name_spec(),
           text("mesh",
                "whose mesh: \"ground\" (every Ground mesh), a Ground block's `name` (its "
                "meshes alone) or a body's name (its meshes)"),
           per_dimension(
               vector("centre", 2, "m", "the patch's centre, on the mesh (3D: [x, y, z])")),
           number("radius", "m",
                  "the patch: the mesh within this distance of the centre (along a straight 2D "
                  "wall, the half-length of the patch)")
               .positive(),
           per_dimension(vector("fluid_side", 2, "",
                                "a direction from the wall into the fluid (3D: [x, y, z])")),
           probe_body_spec()})
          .as_list()
          .for_coupled_runs(),
  };
}

// A point of the scene's dimension as x, y, z (2D: z = 0); nullopt after a reported problem.
std::optional<std::array<double, 3>> point_of(SceneBuilder& builder, const View& block,
                                              std::string_view key) {
  const auto value = builder.dimension_vector(block, key, builder.dimension);
  if (!value) return std::nullopt;
  return std::array<double, 3>{(*value)[0], (*value)[1], builder.spatial() ? (*value)[2] : 0.0};
}

// Adds the probe unless one of its columns is taken by a sensor or another probe.
void add_probe(SceneBuilder& builder, const View& block, probes::ProbeDefinition probe) {
  std::set<std::string> taken;
  for (const SensorSpec& sensor : builder.scene.sensors)
    taken.insert(sensor.name);
  for (const probes::ProbeDefinition& other : builder.scene.probes) {
    for (const probes::Column& column : probes::columns(other, builder.dimension))
      taken.insert(column.name);
  }
  for (const probes::Column& column : probes::columns(probe, builder.dimension)) {
    if (taken.count(column.name) != 0) {
      builder.problem(block.location("name"),
                      "probe '" + probe.name + "' writes the column '" + column.name +
                          "', which a sensor or another probe writes already",
                      "rename the probe");
      return;
    }
  }
  if (block.has("body")) {
    const mbd::BodyId body = builder.find_body(block, "body");
    const std::string kind = builder.model.body_kind(body);
    if (kind != "rigid_body_2d" && kind != "rigid_body_3d") {
      builder.problem(block.location("body"),
                      "probe '" + probe.name + "' cannot move with '" + block.string("body") +
                          "' (" + kind + "): a probe moves rigidly, with a rigid body only",
                      "attach it to a RigidBody2D or RigidBody3D, or leave `body` out");
      return;
    }
    builder.scene.attached_probes.push_back({builder.scene.probes.size(), body});
  }
  builder.scene.probes.push_back(std::move(probe));
}

// A WallPressureProbe: its mesh (the elements of the ground or of one body, as [first, end)
// ranges of the boundary mesh's elements) and a patch that reaches it in the initial
// configuration.
void build_wall_pressure_probe(SceneBuilder& builder, const View& block) {
  const auto centre = point_of(builder, block, "centre");
  const auto side = point_of(builder, block, "fluid_side");
  if (!centre || !side) return;
  const std::string& name = block.string("name");
  const std::string& owner = block.string("mesh");
  const BoundaryMesh& boundary = builder.scene.boundary;
  const mbd::Model& model = builder.model;
  const int corners = builder.dimension;
  auto body_of = [&](std::uint32_t vertex) {
    return vertex < boundary.dynamic_vertex_count ? model.marker_body(static_cast<int>(vertex))
                                                  : mbd::kGround;
  };
  auto name_of = [&](mbd::BodyId body) {
    return body == mbd::kGround ? std::string("ground") : model.body_name(body);
  };
  const auto& elements = boundary.elements();
  const std::size_t element_count = elements.size() / static_cast<std::size_t>(corners);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges;
  std::vector<std::string> owners;
  for (std::size_t e = 0; e < element_count; ++e) {
    const std::string element_owner = name_of(body_of(elements[e * corners]));
    if (std::find(owners.begin(), owners.end(), element_owner) == owners.end())
      owners.push_back(element_owner);
    if (element_owner != owner) continue;
    const auto index = static_cast<std::uint32_t>(e);
    if (!ranges.empty() && ranges.back().second == index) {
      ++ranges.back().second;
    } else {
      ranges.emplace_back(index, index + 1);
    }
  }
  // A named Ground block: its meshes alone.
  for (const auto& [ground, its_ranges] : builder.names.ground_meshes) {
    if (!its_ranges.empty()) owners.push_back(ground);
    if (ground == owner) ranges = its_ranges;
  }
  if (ranges.empty()) {
    std::string known;
    for (const std::string& candidate : owners)
      known += (known.empty() ? "\"" : ", \"") + candidate + "\"";
    builder.problem(block.location("mesh"),
                    "wall pressure probe '" + name + "': '" + owner + "' has no mesh",
                    known.empty() ? "give the scene a Mesh first"
                                  : "write mesh = one of " + known +
                                        " (\"ground\": every Ground mesh; a named Ground: its "
                                        "meshes; a body: its meshes)");
    return;
  }
  const double radius = block.number("radius");
  if (std::hypot((*side)[0], (*side)[1], (*side)[2]) == 0.0) {
    builder.problem(block.location("fluid_side"),
                    "wall pressure probe '" + name + "' has no fluid side (a zero vector)",
                    "give a direction from the wall into the fluid, e.g. [1, 0] for a left wall");
    return;
  }
  // The patch must reach the mesh where the run starts (the bodies' initial configuration).
  std::vector<double> positions, velocities;
  boundary_state(boundary, model, model.initial_configuration(), positions, velocities);
  // The probe reads the elements that face its fluid side (probes::faces_fluid_side): the nearest
  // of those, and of all.
  double nearest = std::numeric_limits<double>::infinity(), nearest_facing = nearest;
  for (const auto& [first, end] : ranges) {
    for (std::uint32_t e = first; e < end; ++e) {
      const std::uint32_t* vertex = &elements[static_cast<std::size_t>(e) * corners];
      const double* a = &positions[vertex[0] * static_cast<std::size_t>(corners)];
      const double* b = &positions[vertex[1] * static_cast<std::size_t>(corners)];
      const double* c = corners == 3 ? &positions[vertex[2] * std::size_t{3}] : nullptr;
      const double distance = corners == 2 ? distance_to_segment(centre->data(), a, b, 2)
                                           : distance_to_triangle(centre->data(), a, b, c);
      nearest = std::min(nearest, distance);
      std::array<double, 3> normal{};
      if (corners == 2) {
        normal = {a[1] - b[1], b[0] - a[0], 0.0};
      } else {
        const std::array<double, 3> u{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const std::array<double, 3> v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        normal = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      }
      if (probes::faces_fluid_side(normal.data(), side->data(), 3))
        nearest_facing = std::min(nearest_facing, distance);
    }
  }
  if (nearest <= radius && !(nearest_facing <= radius)) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "its patch (radius %.6g m) reaches elements of the mesh of '%s' only where they "
                  "face another way than fluid_side [%.6g, %.6g, %.6g] (more than 45 degrees "
                  "off), and it reads only the elements that face it; the nearest element facing "
                  "it lies %.6g m from the centre",
                  radius, owner.c_str(), (*side)[0], (*side)[1], (*side)[2], nearest_facing);
    builder.problem(block.location("fluid_side"), "wall pressure probe '" + name + "': " + text,
                    "give fluid_side as the direction from this wall into the fluid (e.g. [0, 1] "
                    "on a floor, [1, 0] on a left wall)");
    return;
  }
  if (!(nearest <= radius)) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "its patch (radius %.6g m) reaches no element of the mesh of '%s' in the "
                  "initial configuration; the nearest element of its mesh lies %.6g m from the "
                  "centre",
                  radius, owner.c_str(), nearest);
    builder.problem(block.location("centre"), "wall pressure probe '" + name + "': " + text,
                    "put the centre on the mesh, or choose the mesh the centre lies on");
    return;
  }
  add_probe(builder, block, probes::wall_pressure_probe(name, *centre, radius, *side, ranges));
}

void build_probes(SceneBuilder& builder) {
  builder.each("FluidEnergyProbe", [&](const View& block) {
    if (const auto datum = point_of(builder, block, "datum"))
      add_probe(builder, block, probes::fluid_energy_probe(block.string("name"), *datum));
  });
  builder.each("PointProbe", [&](const View& block) {
    if (const auto point = point_of(builder, block, "point"))
      add_probe(builder, block, probes::point_probe(block.string("name"), *point));
  });
  builder.each("FreeSurfaceProbe", [&](const View& block) {
    if (const auto bottom = point_of(builder, block, "bottom")) {
      add_probe(builder, block,
                probes::free_surface_probe(block.string("name"), *bottom, block.number("length"),
                                           static_cast<int>(block.integer("samples"))));
    }
  });
  builder.each("FluxProbe", [&](const View& block) {
    std::vector<std::array<double, 3>> points;
    for (const std::vector<double>& row : block.matrix("points")) {
      if (row.size() != static_cast<std::size_t>(builder.dimension)) {
        builder.problem(
            block.location("points"),
            "a point of 'points' has " + std::to_string(row.size()) +
                " components, the scene has dimension = " + std::to_string(builder.dimension),
            builder.spatial() ? "write points = [[x, y, z], ...]"
                              : "write points = [[x, y], [x, y]]");
        return;
      }
      points.push_back({row[0], row[1], builder.spatial() ? row[2] : 0.0});
    }
    probes::ProbeDefinition probe = probes::flux_probe(block.string("name"), points,
                                                       static_cast<int>(block.integer("samples")));
    if (const std::string problem = probes::definition_problem(probe, builder.dimension);
        !problem.empty()) {
      builder.problem(block.location("points"), problem,
                      builder.spatial() ? "give three or more corners of a planar polygon"
                                        : "give the segment's two distinct points");
      return;
    }
    add_probe(builder, block, std::move(probe));
  });
  builder.each("FrontProbe", [&](const View& block) {
    const std::string& axis = block.string("axis");
    if (axis == "z" && !builder.spatial()) {
      builder.problem(block.location("axis"), "axis z needs a 3D scene (dimension = 2 here)",
                      "write x or y");
      return;
    }
    add_probe(builder, block,
              probes::front_probe(block.string("name"),
                                  axis == "x"   ? 0
                                  : axis == "y" ? 1
                                                : 2,
                                  block.string("direction") == "increasing" ? 1 : -1,
                                  static_cast<int>(block.integer("min_neighbours"))));
  });
  builder.each("WallPressureProbe",
               [&](const View& block) { build_wall_pressure_probe(builder, block); });
}

}  // namespace

ElementFamily probes_family() {
  return {"probes", probe_blocks, {build_probes}};
}

}  // namespace fsi::scene::detail
