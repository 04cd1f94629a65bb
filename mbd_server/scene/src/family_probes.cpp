// Probes: measurements of the fluid itself, evaluated by fsi-client where the particles are and
// written as columns of sensors.csv at every sensor row (docs/user-guide.md, "Probes"). One block
// per probe kind (the kinds' rules live in fsi::probes, one file each); their columns are named
// by fsi::probes::columns, and must not collide with a sensor's or another probe's.

#include <set>

#include "fsi/probes/probe.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

ParameterSpec probe_name_spec() {
  return text("name", "the probe's name: its columns of sensors.csv start with it");
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
          {probe_name_spec(), per_dimension(vector("point", 2, "m", "where (3D: [x, y, z])"))})
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
                      .between(2.0, 100000.0)})
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
                      .between(1.0, 1000.0)})
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
  builder.scene.probes.push_back(std::move(probe));
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
}

}  // namespace

ElementFamily probes_family() {
  return {"probes", probe_blocks, {build_probes}};
}

}  // namespace fsi::scene::detail
