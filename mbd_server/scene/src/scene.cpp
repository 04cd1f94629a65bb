#include "fsi/scene/scene.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <tuple>

#include "fsi/common/error.hpp"
#include "fsi/contact/wall_contact_3d.hpp"
#include "fsi/scene/fluid_region.hpp"
#include "scene_assembly.hpp"
#include "scene_elements.hpp"
#include "scene_spatial.hpp"

namespace fsi::scene {
namespace {

namespace fs = std::filesystem;
using detail::coordinate_of;

ParameterSpec with_default(ParameterSpec p, Value value) {
  p.default_value = std::move(value);
  return p;
}
ParameterSpec positive(ParameterSpec p) {
  p.minimum = 0.0;
  p.minimum_exclusive = true;
  return p;
}
ParameterSpec at_least(ParameterSpec p, double minimum) {
  p.minimum = minimum;
  return p;
}
ParameterSpec choice(ParameterSpec p, std::vector<std::string> choices) {
  p.choices = std::move(choices);
  return p;
}
ParameterSpec optional(ParameterSpec p) {
  p.optional_without_default = true;
  return p;
}
// A vector of `dimension` components (2 or 3): the builder checks the length against it.
ParameterSpec per_dimension(ParameterSpec p) {
  p.length.reset();
  return p;
}

BlockSpec block(std::string name, std::string doc, std::vector<ParameterSpec> parameters,
                std::vector<BlockSpec> blocks = {}) {
  BlockSpec b;
  b.name = std::move(name);
  b.doc = std::move(doc);
  b.parameters = std::move(parameters);
  b.blocks = std::move(blocks);
  return b;
}
BlockSpec repeated(BlockSpec b) {
  b.repeated = true;
  return b;
}
BlockSpec required(BlockSpec b) {
  b.required = true;
  return b;
}

BlockSpec make_schema() {
  BlockSpec timeint = required(block(
      "Timeint", "Time integration of the multibody system (fixed step when coupled).",
      {positive(number("step_size", "s",
                       "coupled time step, the same on both sides; SPH needs <= 0.25 h/c; "
                       "--mbd-only with an error-controlled method: the output step")),
       with_default(choice(text("method",
                                "fixed: the tableau at step_size; adaptive: the tableau with "
                                "step-doubling error control; ida: SUNDIALS IDA (BDF 1-5); the "
                                "last two for --mbd-only (ErrorControl), a coupled run always "
                                "takes the fixed step"),
                           {"fixed", "adaptive", "ida"}),
                    text_value("fixed")),
       with_default(choice(text("tableau", "implicit Runge-Kutta scheme (HOTINT's tableau_name)"),
                           {"RadauIIA", "LobattoIIIA"}),
                    text_value("RadauIIA")),
       [] {
         ParameterSpec p = with_default(
             integer("stages",
                     "Radau IIA: 1, 2, 3 (orders 1, 3, 5); Lobatto IIIA: 2, 3 (orders 2, 4)"),
             number_value(3));
         p.minimum = 1;
         p.maximum = 3;
         return p;
       }(),
       with_default(choice(text("constraint_form",
                                "index3: position constraints C = 0 at the stages (no drift); "
                                "index2: their rates G v + dC/dt = 0 (positions drift by the "
                                "integration error; HOTINT's alternative)"),
                           {"index3", "index2"}),
                    text_value("index3"))}));
  BlockSpec newton = block(
      "Newton", "Newton iterations of the implicit stage equations.",
      {with_default(positive(number("relative_tolerance", "",
                                    "increment tolerance relative to the stage values")),
                    number_value(1e-10)),
       with_default(at_least(integer("max_iterations", "iterations before the step fails"), 1),
                    number_value(12)),
       with_default(at_least(integer("max_modified_newton_steps",
                                     "steps that reuse one factorised Jacobian (0: full Newton)"),
                             0),
                    number_value(20)),
       with_default(number("max_contraction", "",
                           "a reused Jacobian is replaced when |dx_k|/|dx_k-1| exceeds this")
                        .above(0.0)
                        .at_most(1.0),
                    number_value(0.5)),
       with_default(positive(number("absolute_tolerance", "SI",
                                    "increment tolerance where a whole block stays zero")),
                    number_value(1e-14))});
  BlockSpec error_control =
      block("ErrorControl",
            "Local error test of Timeint.method = adaptive or ida (--mbd-only): per coordinate and "
            "velocity |e| <= relative_tolerance |y| + absolute_tolerance (weighted RMS).",
            {with_default(positive(number("relative_tolerance", "", "relative local error")),
                          number_value(1e-6)),
             with_default(positive(number("absolute_tolerance", "SI", "absolute local error")),
                          number_value(1e-8)),
             with_default(at_least(number("max_step", "s", "largest step (0: no limit)"), 0.0),
                          number_value(0.0))});
  BlockSpec solver =
      required(block("SolverOptions", "Solver settings of the run.",
                     {positive(number("end_time", "s", "simulated time of the coupled phase"))},
                     {timeint, newton, error_control}));

  BlockSpec output = block(
      "Output", "What the server writes into the output folder.",
      {with_default(
           at_least(integer("sensor_every_steps", "write a sensors.csv row every N steps"), 1),
           number_value(1)),
       with_default(at_least(integer("snapshot_every_steps",
                                     "request an SPH particle snapshot every N steps (0: never)"),
                             0),
                    number_value(0))});

  BlockSpec gravity = block("Gravity", "Uniform gravitational acceleration.",
                            {with_default(per_dimension(vector("acceleration", 2, "m/s^2",
                                                               "acceleration vector ([x, y]; 3D: "
                                                               "[x, y, z], default 0)")),
                                          vector_value({0.0, 0.0}))});

  BlockSpec mesh = repeated(
      block("Mesh",
            "Surface line segments through the given points (body coordinates on a body, world "
            "coordinates on "
            "the ground), thesis §4.3.",
            {matrix("points", 2, "m", "polyline vertices, one [x, y] per row"), [] {
               ParameterSpec p = with_default(
                   integer("closed", "1: also join the last point to the first"), number_value(0));
               p.minimum = 0;
               p.maximum = 1;
               return p;
             }()}));

  BlockSpec body = repeated(block(
      "RigidBody2D", "A planar rigid body; coordinates x, y, angle of its centre of mass.",
      {text("name", "unique name, used by constraints and sensors"),
       positive(number("mass", "kg/m", "mass (per unit depth in 2D)")),
       positive(number("inertia", "kg m",
                       "moment of inertia about the centre of mass (per unit depth)")),
       with_default(vector("position", 2, "m", "initial centre of mass"), vector_value({0.0, 0.0})),
       with_default(number("angle", "rad", "initial angle"), number_value(0.0)),
       with_default(vector("velocity", 2, "m/s", "initial velocity"), vector_value({0.0, 0.0})),
       with_default(number("angular_velocity", "rad/s", "initial angular velocity"),
                    number_value(0.0))},
      {mesh}));

  BlockSpec beam = repeated(block(
      "AncfBeam2D",
      "A planar ANCF beam (Gerstmayr's elastic line, docs/theory.md): straight and stress-free "
      "from start to end, at rest; 4 coordinates per node (x, y, slope x, slope y). Its points "
      "(joints, springs) are [s, eta]: s along the undeformed centre line from start, eta along "
      "the deformed line's normal, left of start -> end. Its surface mesh is the closed outline "
      "of both faces eta = +-thickness/2.",
      {text("name", "unique name, used by clamps, joints and sensors"),
       vector("start", 2, "m", "first node (s = 0)"), vector("end", 2, "m", "last node (s = L)"),
       at_least(integer("elements", "number of equal elements"), 1),
       positive(number("axial_stiffness", "N/m", "EA (per unit depth in 2D)")),
       positive(number("bending_stiffness", "N m", "EI (per unit depth in 2D)")),
       positive(number("mass_per_length", "kg/m^2", "rho A (per unit depth in 2D)")),
       with_default(at_least(number("axial_damping", "N s/m",
                                    "viscous axial damping: N = EA eps + this * deps/dt"),
                             0.0),
                    number_value(0.0)),
       with_default(at_least(number("bending_damping", "N m s",
                                    "viscous bending damping: M = EI kappa + this * dkappa/dt"),
                             0.0),
                    number_value(0.0)),
       positive(number("thickness", "m", "h: distance of the two faces the mesh follows")),
       with_default(at_least(integer("face_points_per_element",
                                     "mesh segments per element on each face (0: no surface mesh)"),
                             0),
                    number_value(4))}));

  // A Ground mesh: a polyline (2D) or a triangle surface from an STL file (3D).
  BlockSpec ground_mesh = mesh;
  ground_mesh.doc =
      "2D: surface line segments through the given world points (thesis §4.3); 3D: the triangles "
      "of an STL file (either orientation: the fix treats both sides alike).";
  ground_mesh.parameters[0] = optional(ground_mesh.parameters[0]);
  ground_mesh.parameters[0].doc = "2D: polyline vertices, one [x, y] per row";
  ground_mesh.parameters.push_back(
      optional(text("stl", "3D: ASCII or binary STL file, relative to the scene")));
  ground_mesh.parameters.push_back(
      with_default(positive(number("scale", "", "3D: the STL coordinates times this are metres")),
                   number_value(1.0)));
  ground_mesh.parameters.push_back(
      with_default(vector("offset", 3, "m", "3D: added to every scaled STL vertex"),
                   vector_value({0.0, 0.0, 0.0})));
  BlockSpec ground = repeated(
      block("Ground", "Static geometry fixed in space (its meshes are static boundary vertices).",
            {}, {ground_mesh}));

  ParameterSpec body_name = text("body", "name of a RigidBody2D");
  ParameterSpec coordinate = choice(text("coordinate", "body coordinate"), {"x", "y", "angle"});
  BlockSpec coordinate_constraint = repeated(block(
      "CoordinateConstraint",
      "Holds a body coordinate at a value (position level; force from a Lagrange multiplier).",
      {body_name, coordinate,
       optional(number("value", "m or rad", "held value (default: the initial coordinate)"))}));
  BlockSpec beam_clamp = repeated(block(
      "BeamClamp",
      "Clamps a node of an AncfBeam2D to the ground (or to the RigidBody2D `to`) at its initial "
      "position and slope direction (rows x, y, slope direction); slope = \"full\" also holds "
      "the slope's length (4 rows).",
      {text("beam", "name of an AncfBeam2D"),
       optional(text("to", "name of the holding RigidBody2D; absent: the ground")),
       with_default(at_least(integer("node", "node index: 0 at start, elements at end"), 0),
                    number_value(0)),
       with_default(choice(text("slope",
                                "direction: the axial stretch at the clamp stays free "
                                "(Gerstmayr & Irschik); full: held too"),
                           {"direction", "full"}),
                    text_value("direction"))}));
  BlockSpec velocity_constraint = repeated(block(
      "VelocityConstraint",
      "Prescribes the velocity of a body coordinate (velocity level, thesis §6.3 piston).",
      {body_name, coordinate, number("velocity", "m/s or rad/s", "prescribed constant velocity")}));

  // Elements between two body points; body_b absent: point_b is a fixed point of the world.
  auto two_points = [](std::vector<ParameterSpec> extra) {
    std::vector<ParameterSpec> parameters = {
        detail::element_name_spec(), text("body_a", "name of a RigidBody2D or AncfBeam2D"),
        with_default(
            vector("point_a", 2, "m", "point on body_a: body coordinates, [s, eta] on a beam"),
            vector_value({0.0, 0.0})),
        optional(text("body_b", "name of a RigidBody2D or AncfBeam2D; absent: the ground")),
        with_default(vector("point_b", 2, "m",
                            "point on body_b (body coordinates, [s, eta] on a beam) or in the "
                            "world"),
                     vector_value({0.0, 0.0}))};
    parameters.insert(parameters.end(), extra.begin(), extra.end());
    return parameters;
  };
  BlockSpec revolute = repeated(
      block("RevoluteJoint", "Pins point_a of body_a to point_b (2 constraint rows, x then y).",
            two_points({})));
  BlockSpec distance = repeated(block(
      "DistanceConstraint",
      "A massless rod: |r_b - r_a| = length (1 row; lambda is the rod force, tension positive).",
      two_points({optional(
          positive(number("length", "m", "rod length (default: the initial distance)")))})));
  BlockSpec spring = repeated(block(
      "SpringDamper", "Linear spring-damper between the two points: tension k (l - l0) + c dl/dt.",
      two_points({at_least(number("stiffness", "N/m", "k (2D: per unit depth)"), 0.0),
                  with_default(at_least(number("damping", "N s/m", "c"), 0.0), number_value(0.0)),
                  optional(at_least(
                      number("rest_length", "m", "l0 (default: the initial distance)"), 0.0))})));

  BlockSpec sensor = repeated(block(
      "Sensor", "A column of sensors.csv, written every Output.sensor_every_steps steps.",
      {text("name", "column name"),
       choice(text("type",
                   "what is measured (total_fluid_force: on every boundary, walls included; "
                   "joint_force: what the joint exerts on its body_a (Clamp: body); spring_force: "
                   "tension, or torque of a RotationalSpringDamper; energies of the whole system, "
                   "potential = gravity + springs)"),
              {"position", "velocity", "fluid_force", "constraint_force", "total_fluid_force",
               "joint_force", "spring_force", "kinetic_energy", "potential_energy"}),
       optional(text("body",
                     "name of a RigidBody2D (position, velocity, fluid and constraint "
                     "forces), or of an AncfBeam2D (fluid_force)")),
       optional(per_dimension(
           vector("point", 2, "m",
                  "position, velocity: a point of the body instead of its centre of mass (body "
                  "coordinates; [s, eta] on an AncfBeam2D; 3D: [x, y, z], [s, 0, 0] on a cable)"))),
       optional(text("joint", "joint_force: the name of a joint block")),
       optional(text("element", "spring_force: the name of a spring block")),
       optional(choice(text("component",
                            "x, y, angle (torque for forces); 3D: x, y, z, and torque_x, "
                            "torque_y, torque_z (about the centre of mass) for fluid_force and "
                            "joint_force; not for spring_force and energies"),
                       {"x", "y", "z", "angle", "torque", "torque_x", "torque_y", "torque_z"}))}));

  BlockSpec fluid = block(
      "FluidRegion",
      "SPH particles generated by the server on a square (3D: cubic) lattice (thesis §6.2) and "
      "sent to the client.",
      {choice(text("shape",
                   "region shape: box (lower, upper), polygon (2D: points, Hole blocks) or stl "
                   "(3D: a closed surface)"),
              {"box", "polygon", "stl"}),
       optional(
           per_dimension(vector("lower", 2, "m", "box: lower corner ([x, y]; 3D: [x, y, z])"))),
       optional(
           per_dimension(vector("upper", 2, "m", "box: upper corner ([x, y]; 3D: [x, y, z])"))),
       optional(text("stl", "stl: closed STL surface (ASCII or binary), relative to the scene")),
       optional(matrix("points", 2, "m",
                       "polygon: vertices in order around the region (concave allowed, must not "
                       "cross itself)")),
       positive(number("spacing", "m", "lattice constant d")),
       positive(number("density", "kg/m^3",
                       "initial density rho0; particle mass = rho0 d^2 (3D: rho0 d^3)")),
       with_default(per_dimension(vector("velocity", 2, "m/s",
                                         "initial particle velocity (3D: [x, y, z], default 0)")),
                    vector_value({0.0, 0.0})),
       with_default(number("random_displacement", "",
                           "uniform random offset per coordinate, as a fraction of d (not in %)")
                        .between(0.0, 0.5),
                    number_value(0.0)),
       with_default(integer("seed", "random generator seed"), number_value(1)),
       with_default(at_least(integer("atom_type", "LIGGGHTS atom type of the particles"), 1),
                    number_value(1))},
      {repeated(block("Hole", "polygon: a region left empty, inside the polygon (even-odd rule)",
                      {matrix("points", 2, "m", "hole vertices in order")}))});

  BlockSpec liggghts = required(block(
      "LIGGGHTS",
      "The two LIGGGHTS input scripts (thesis §5.6), sent by the server; paths relative to the "
      "scene.",
      {text("script1", "set-up script, run before the equilibration"),
       text("script2", "script run after the equilibration (e.g. the real viscosity)"),
       with_default(
           at_least(
               integer("equilibration_steps", "LIGGGHTS-only steps with the structure at rest"), 0),
           number_value(0))}));

  BlockSpec sph =
      block("LIGGGHTS_SPH_parameters",
            "Every entry becomes a LIGGGHTS string variable ${name} defined before script 1.", {});
  sph.open = true;

  BlockSpec coupling = required(block(
      "Coupling", "The SPH-wall contact of fix fsi/sph (docs/fix_fsi_sph.md).",
      {positive(number("refinement_resolution", "m",
                       "segments are bisected until shorter than this (thesis eq. 4.7: ~2h)")),
       [] {
         ParameterSpec p = with_default(
             integer("refinement_option",
                     "3D triangles, thesis Table 5.1: 0 none, 1 recursive at every step, 2 "
                     "pre-refined once, 3 pre-refined then recursive; 2D segments: always 1"),
             number_value(1));
         p.minimum = contact::kMinRefinementOption;
         p.maximum = contact::kMaxRefinementOption;
         return p;
       }()}));

  BlockSpec root;
  root.name = "";
  root.doc = "A scene file.";
  root.user_blocks_allowed = true;
  root.parameters = {with_default(
      integer("dimension",
              "2: planar scene (RigidBody2D, AncfBeam2D, polyline meshes); 3: spatial scene "
              "(RigidBody3D, PointMass, AncfCable3D, STL meshes, a 3D fluid)")
          .between(2, 3),
      number_value(2))};
  root.blocks = {solver,
                 detail::assembly_block_spec(),
                 output,
                 gravity,
                 body,
                 beam,
                 ground,
                 coordinate_constraint,
                 velocity_constraint,
                 beam_clamp,
                 revolute,
                 distance,
                 spring,
                 fluid,
                 liggghts,
                 sph,
                 coupling};
  // The connectors, force elements and loads of scene_elements.cpp, then the sensors.
  const auto elements = detail::element_block_specs();
  const auto after_springs =
      std::find_if(root.blocks.begin(), root.blocks.end(),
                   [](const BlockSpec& b) { return b.name == "SpringDamper"; }) +
      1;
  const auto sensors = root.blocks.insert(after_springs, elements.begin(), elements.end()) +
                       static_cast<std::ptrdiff_t>(elements.size());
  root.blocks.insert(sensors, sensor);
  const auto spatial = detail::spatial_block_specs();
  const auto after_beam = std::find_if(root.blocks.begin(), root.blocks.end(),
                                       [](const BlockSpec& b) { return b.name == "AncfBeam2D"; }) +
                          1;
  root.blocks.insert(after_beam, spatial.begin(), spatial.end());
  return root;
}

std::string format_exact(double value) {
  // Shortest text that reads back to the same double.
  char text[40];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

// Where a file named at `where` is: relative to the folder of the scene file that names it (an
// included file's own folder), or to the top-level scene's for a --set; unless absolute.
fs::path scene_relative(const fs::path& scene_dir, const SourceLocation& where,
                        const std::string& name) {
  if (fs::path(name).is_absolute()) return name;
  const bool in_a_file = where.line > 0;
  return (in_a_file ? fs::path(where.file).parent_path() : scene_dir) / name;
}

std::string read_script(const fs::path& scene_dir, const std::string& name,
                        const SourceLocation& where, std::vector<Problem>& problems) {
  const fs::path path = scene_relative(scene_dir, where, name);
  std::ifstream in(path);
  if (!in) {
    problems.push_back({where, "LIGGGHTS script '" + path.string() + "' cannot be read",
                        "give the path relative to the scene file that names it"});
    return {};
  }
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Reads the STL file named by `key`; a missing or unreadable file becomes a problem at the key.
std::optional<TriangleMesh> read_scene_stl(const View& block, std::string_view key,
                                           const fs::path& scene_dir,
                                           std::vector<Problem>& problems) {
  const fs::path file = scene_relative(scene_dir, block.location(key), block.string(key));
  std::error_code error;
  if (!fs::is_regular_file(file, error)) {
    problems.push_back({block.location(key), "STL file '" + file.string() + "' does not exist",
                        "give the path relative to the scene file that names it"});
    return std::nullopt;
  }
  try {
    return read_stl(file.string());
  } catch (const Error& failure) {
    const std::string where = failure.location().empty() ? "" : " (" + failure.location() + ")";
    problems.push_back({block.location(key), failure.fault() + where, failure.remedy()});
    return std::nullopt;
  }
}

// A per-dimension vector: its length must be the scene's dimension; absent, zeros.
std::optional<std::vector<double>> dimension_vector(const View& block, std::string_view key,
                                                    int dimension, std::vector<Problem>& problems) {
  const auto size = static_cast<std::size_t>(dimension);
  if (!block.has(key)) return std::vector<double>(size, 0.0);
  std::vector<double> value = block.vector(key);
  if (value.size() == size) return value;
  problems.push_back({block.location(key),
                      "'" + std::string(key) + "' has " + std::to_string(value.size()) +
                          " components, the scene has dimension = " + std::to_string(dimension),
                      dimension == 3 ? "write " + std::string(key) + " = [x, y, z]"
                                     : "write " + std::string(key) +
                                           " = [x, y], or set dimension = 3 at the top "
                                           "of the scene"});
  return std::nullopt;
}

// Writes the fluid region's lattice into `fluid`; a mistake becomes a problem at its key.
void build_fluid(const View& region, int dimension, const fs::path& scene_dir,
                 FluidParticles& fluid, std::vector<Problem>& problems) {
  LatticeOptions options;
  options.spacing = region.number("spacing");
  options.random_displacement = region.number("random_displacement");
  options.seed = static_cast<std::uint64_t>(region.integer("seed"));
  fluid.dimension = dimension;
  fluid.spacing = options.spacing;
  fluid.density = region.number("density");
  fluid.mass = lattice_particle_mass(fluid.density, options.spacing, dimension);
  fluid.atom_type = static_cast<int>(region.integer("atom_type"));
  const std::optional<std::vector<double>> velocity =
      dimension_vector(region, "velocity", dimension, problems);
  const std::string shape = region.string("shape");
  bool complete = velocity.has_value();
  if (shape == "polygon" && dimension == 3) {
    problems.push_back({region.location("shape"), "a polygon fluid region is 2D only",
                        "use shape = \"box\" with 3-component lower and upper, or shape = "
                        "\"stl\" with stl = \"file.stl\""});
    return;
  }
  if (shape == "stl" && dimension == 2) {
    problems.push_back({region.location("shape"),
                        "an stl fluid region needs a 3D scene (dimension = 2 here)",
                        "set dimension = 3 at the top of the scene, or use shape = \"box\" or "
                        "\"polygon\""});
    return;
  }
  const std::vector<std::string> all = {"lower", "upper", "points", "stl"};
  const std::vector<std::string> needed = shape == "box"
                                              ? std::vector<std::string>{"lower", "upper"}
                                          : shape == "stl" ? std::vector<std::string>{"stl"}
                                                           : std::vector<std::string>{"points"};
  for (const std::string& key : needed) {
    if (!region.has(key)) {
      problems.push_back({region.location("shape"),
                          "a " + shape + " fluid region needs '" + key + "'",
                          "add " + key + " = ... to FluidRegion"});
      complete = false;
    }
  }
  for (const std::string& key : all) {
    if (region.has(key) && std::find(needed.begin(), needed.end(), key) == needed.end()) {
      const std::string owner = key == "points" ? "polygon" : key == "stl" ? "stl" : "box";
      problems.push_back({region.location(key),
                          "'" + key + "' belongs to the other shape than '" + shape + "'",
                          "remove it, or set shape = \"" + owner + "\""});
      complete = false;
    }
  }
  if (shape != "polygon" && region.has_block("Hole")) {
    problems.push_back({region.block("Hole").location(),
                        "a " + shape + " fluid region has no holes",
                        dimension == 2 ? "use shape = \"polygon\" with points = ..."
                                       : "remove the Hole block (3D: cut the hole out of the STL "
                                         "surface)"});
    complete = false;
  }
  std::optional<std::vector<double>> lower, upper;
  if (shape == "box" && region.has("lower") && region.has("upper")) {
    lower = dimension_vector(region, "lower", dimension, problems);
    upper = dimension_vector(region, "upper", dimension, problems);
    if (!lower || !upper) complete = false;
  }
  if (!complete) return;
  const SourceLocation where = region.location(shape == "box"   ? "upper"
                                               : shape == "stl" ? "stl"
                                                                : "points");
  try {
    if (shape == "box" && dimension == 2) {
      fluid.positions =
          fill_box(Point2{(*lower)[0], (*lower)[1]}, Point2{(*upper)[0], (*upper)[1]}, options);
    } else if (shape == "box") {
      fluid.positions = fill_box_3d(Point3{(*lower)[0], (*lower)[1], (*lower)[2]},
                                    Point3{(*upper)[0], (*upper)[1], (*upper)[2]}, options);
    } else if (shape == "stl") {
      const std::optional<TriangleMesh> surface =
          read_scene_stl(region, "stl", scene_dir, problems);
      if (!surface) return;
      fluid.positions = fill_closed_surface(*surface, options);
    } else {
      Polygon polygon;
      for (const auto& row : region.matrix("points"))
        polygon.outer.push_back({row[0], row[1]});
      for (const View& hole : region.blocks("Hole")) {
        polygon.holes.emplace_back();
        for (const auto& row : hole.matrix("points"))
          polygon.holes.back().push_back({row[0], row[1]});
      }
      fluid.positions = fill_polygon(polygon, options);
    }
  } catch (const AlreadyReported&) {
    throw;
  } catch (const Error& error) {
    problems.push_back({where, error.fault(), error.remedy()});
    return;
  }
  fluid.velocities.clear();
  fluid.velocities.reserve(fluid.positions.size());
  for (std::size_t i = 0; i < fluid.count(); ++i)
    fluid.velocities.insert(fluid.velocities.end(), velocity->begin(), velocity->end());
}

// Marks the parameter at `where` as failed (a schema problem names it), so that the builder
// skips what needs it.
bool mark_failed(Block& block, const SourceLocation& where) {
  for (Parameter& parameter : block.parameters) {
    if (parameter.location == where) {
      parameter.failed = true;
      return true;
    }
  }
  for (Block& child : block.blocks) {
    if (mark_failed(child, where)) return true;
  }
  return false;
}

}  // namespace

const BlockSpec& scene_schema() {
  static const BlockSpec schema = make_schema();
  return schema;
}

Scene build_scene(const std::string& path, const std::vector<Override>& overrides) {
  Scene scene;
  scene.file = path;
  // Every problem is collected: evaluation, schema, then what the builder finds in the values
  // that are sound. Elements that need a value in error are skipped, not reported again.
  std::vector<Problem> problems;
  const BlockSpec& schema = scene_schema();
  scene.parameters = load_parameter_file(path, overrides, problems, declared_parameters(schema));
  for (Problem& problem : validate(scene.parameters, schema)) {
    mark_failed(scene.parameters, problem.location);
    problems.push_back(std::move(problem));
  }
  const bool input_sound = problems.empty();
  bool skipped_any = false;  // an element was skipped for a value in error
  // Runs one element's construction: a value in error skips it, an fsi::Error becomes a problem.
  auto guard = [&](const SourceLocation& element, auto&& step) {
    try {
      step();
    } catch (const AlreadyReported&) {
      skipped_any = true;
    } catch (const Error& error) {
      const SourceLocation where =
          error.location().empty() ? element : SourceLocation{error.location()};
      problems.push_back({where, error.fault(), error.remedy()});
    }
  };

  const View root(scene.parameters, schema);
  if (!scene.parameters.language_version) {
    // Required, not defaulted: a later language version may change what existing syntax means,
    // and an unversioned file would then be read by the wrong rules without a word.
    Problem missing;
    missing.location.file = path;
    missing.location.line = 1;
    missing.location.column = 1;
    missing.message = "the scene does not state the scene language version it is written for";
    missing.fix = "add the line 'scene_language = " + std::to_string(kSceneLanguageVersion) +
                  "' at the top of the file (comments may stand above it)";
    problems.push_back(std::move(missing));
  }
  if (const Block* old = scene.parameters.child("SceneFormat")) {
    problems.push_back({old->location, "SceneFormat { version = N } is no longer read",
                        "replace it by 'scene_language = N' as the first entry of the file"});
  }

  // Solver and output.
  guard(root.location(), [&] {
    const View solver = root.block("SolverOptions");
    scene.solver.end_time = solver.number("end_time");
    scene.solver.step_size = solver.block("Timeint").number("step_size");
    scene.solver.stages = static_cast<int>(solver.block("Timeint").integer("stages"));
    const bool lobatto = solver.block("Timeint").string("tableau") == "LobattoIIIA";
    scene.solver.constraint_form = solver.block("Timeint").string("constraint_form") == "index2"
                                       ? mbd::ConstraintForm::Index2
                                       : mbd::ConstraintForm::Index3;
    scene.solver.family = lobatto ? mbd::TableauFamily::LobattoIIIA : mbd::TableauFamily::RadauIIA;
    const std::string& method = solver.block("Timeint").string("method");
    scene.solver.method = method == "adaptive" ? IntegrationMethod::AdaptiveRadau
                          : method == "ida"    ? IntegrationMethod::Ida
                                               : IntegrationMethod::FixedStep;
    scene.solver.method_location = solver.block("Timeint").location("method");
    const View error_control = solver.block("ErrorControl");
    scene.solver.relative_tolerance = error_control.number("relative_tolerance");
    scene.solver.absolute_tolerance = error_control.number("absolute_tolerance");
    scene.solver.max_step = error_control.number("max_step");
    if (lobatto && scene.solver.stages < 2) {
      problems.push_back(
          {solver.block("Timeint").location("stages"),
           "Lobatto IIIA has 2 or 3 stages, not " + std::to_string(scene.solver.stages),
           "write stages = 2 (order 2) or stages = 3 (order 4)"});
    }
    const View newton = solver.block("Newton");
    scene.solver.newton.relative_tolerance = newton.number("relative_tolerance");
    scene.solver.newton.max_iterations = static_cast<int>(newton.integer("max_iterations"));
    scene.solver.newton.max_modified_newton_steps =
        static_cast<int>(newton.integer("max_modified_newton_steps"));
    scene.solver.newton.max_contraction = newton.number("max_contraction");
    scene.solver.newton.absolute_tolerance = newton.number("absolute_tolerance");
  });
  guard(root.location(), [&] {
    scene.output.sensor_every_steps = root.block("Output").integer("sensor_every_steps");
    scene.output.snapshot_every_steps = root.block("Output").integer("snapshot_every_steps");
  });

  // Bodies and their meshes: body vertices first (dynamic), ground vertices after (static).
  mbd::Model& model = scene.model;
  guard(root.location(), [&] { scene.dimension = static_cast<int>(root.integer("dimension")); });
  const int dimension = scene.dimension;
  const bool spatial = dimension == 3;
  scene.boundary.dimension = dimension;
  scene.fluid.dimension = dimension;
  guard(root.location(), [&] {
    const View gravity_block = root.block("Gravity");
    if (!gravity_block.has("acceleration")) return;  // default: none
    const auto gravity = dimension_vector(gravity_block, "acceleration", dimension, problems);
    if (!gravity) return;
    for (std::size_t k = 0; k < gravity->size(); ++k)
      scene.gravity[k] = (*gravity)[k];
    if (spatial) {
      model.set_spatial_gravity({scene.gravity[0], scene.gravity[1], scene.gravity[2]});
    } else {
      model.set_gravity({scene.gravity[0], scene.gravity[1]});
    }
  });
  const fs::path scene_dir = fs::path(path).parent_path();
  if (spatial) {
    for (const char* planar :
         {"RigidBody2D", "AncfBeam2D", "CoordinateConstraint", "VelocityConstraint", "BeamClamp",
          "RevoluteJoint", "DistanceConstraint", "SpringDamper", "PrismaticJoint", "Clamp",
          "RotationalSpringDamper", "NonlinearSpringDamper", "SpringActor", "PointForce", "Torque",
          "PrescribedMotion", "PrescribedVelocity"}) {
      for (const View& element : root.blocks(planar)) {
        problems.push_back(
            {element.location(),
             std::string(planar) + " is a planar (2D) element: planar bodies and their joints "
                                   "need dimension = 2",
             "set dimension = 2, or use its spatial counterpart (RigidBody3D, AncfCable3D, "
             "SphericalJoint, RevoluteJoint3D, FixedJoint3D, DistanceConstraint3D, CableClamp)"});
      }
    }
  } else {
    for (const std::string& block_name : detail::spatial_block_names()) {
      for (const View& element : root.blocks(block_name)) {
        problems.push_back({element.location(),
                            block_name + " is a spatial (3D) element: it needs dimension = 3",
                            "set dimension = 3 at the top of the scene, or use a planar element"});
      }
    }
  }
  // A 3D ground mesh: the STL's triangles, scaled and shifted, as static vertices.
  auto add_surface = [&](const View& mesh) {
    if (mesh.has("points")) {
      problems.push_back({mesh.location("points"),
                          "a 3D Ground mesh is read from an STL file, not from points",
                          "write stl = \"file.stl\" (optional scale, offset = [x, y, z])"});
    }
    if (!mesh.has("stl")) {
      if (!mesh.has("points")) {
        problems.push_back(
            {mesh.location(), "a 3D Ground mesh needs an STL file", "add stl = \"file.stl\""});
      }
      return;
    }
    const std::optional<TriangleMesh> surface = read_scene_stl(mesh, "stl", scene_dir, problems);
    if (!surface) return;
    const double scale = mesh.number("scale");
    const auto offset = mesh.vector("offset");
    auto& boundary = scene.boundary;
    // Ground vertices follow the bodies' (dynamic) ones.
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
  };
  auto add_mesh = [&](const View& mesh, mbd::BodyId body) {
    if (mesh.has("stl")) {
      problems.push_back({mesh.location("stl"), "STL meshes need a 3D scene (dimension = 2 here)",
                          "set dimension = 3 at the top of the scene, or give points = [[x, y], "
                          "...]"});
      return;
    }
    if (!mesh.has("points")) {
      problems.push_back(
          {mesh.location(), "a 2D mesh needs points", "add points = [[x, y], [x, y], ...]"});
      return;
    }
    const auto points = mesh.matrix("points");
    if (points.size() < 2) {
      problems.push_back({mesh.location("points"), "a mesh needs at least 2 points", "add points"});
      return;
    }
    const bool closed = mesh.integer("closed") == 1;
    const auto first = static_cast<std::uint32_t>(model.marker_count());
    for (const auto& point : points)
      model.add_marker(body, {point[0], point[1]});
    const auto count = static_cast<std::uint32_t>(points.size());
    for (std::uint32_t k = 0; k + 1 < count; ++k) {
      scene.boundary.segments.insert(scene.boundary.segments.end(), {first + k, first + k + 1});
    }
    if (closed && count > 2) {
      scene.boundary.segments.insert(scene.boundary.segments.end(), {first + count - 1, first});
    }
  };
  std::vector<std::string> skipped_bodies;  // bodies not built for a value in error
  bool unnamed_body_skipped = false;        // a body whose name is in error: its name is unknown
  for (const View& body : spatial ? std::vector<View>{} : root.blocks("RigidBody2D")) {
    const Parameter* name_given = body.raw().find("name");
    if (name_given && name_given->failed) unnamed_body_skipped = true;
    std::optional<mbd::BodyId> id;
    guard(body.location(), [&] {
      mbd::RigidBody2DSpec spec;
      spec.name = body.string("name");
      skipped_bodies.push_back(spec.name);
      spec.mass = body.number("mass");
      spec.inertia = body.number("inertia");
      const auto position = body.vector("position");
      const auto velocity = body.vector("velocity");
      spec.position = {position[0], position[1]};
      spec.velocity = {velocity[0], velocity[1]};
      spec.angle = body.number("angle");
      spec.angular_velocity = body.number("angular_velocity");
      try {
        id = model.add_rigid_body(spec);
      } catch (const Error& error) {
        problems.push_back({body.location("name"), error.fault(), error.remedy()});
        return;
      }
      skipped_bodies.pop_back();
    });
    if (!id) continue;
    for (const View& mesh : body.blocks("Mesh"))
      guard(mesh.location(), [&] { add_mesh(mesh, *id); });
  }
  for (const View& beam : spatial ? std::vector<View>{} : root.blocks("AncfBeam2D")) {
    const Parameter* name_given = beam.raw().find("name");
    if (name_given && name_given->failed) unnamed_body_skipped = true;
    guard(beam.location(), [&] {
      mbd::AncfBeamSpec spec;
      spec.name = beam.string("name");
      skipped_bodies.push_back(spec.name);
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
      const double half_thickness = 0.5 * beam.number("thickness");
      const auto per_element = static_cast<int>(beam.integer("face_points_per_element"));
      mbd::BodyId id = 0;
      try {
        id = model.add_ancf_beam(spec);
      } catch (const Error& error) {
        problems.push_back({beam.location("name"), error.fault(), error.remedy()});
        return;
      }
      skipped_bodies.pop_back();
      if (per_element == 0) return;
      // The closed outline: the upper face from s = 0 to L, the lower face back.
      const double length = (spec.end - spec.start).norm();
      const int count = spec.element_count * per_element;
      const auto first = static_cast<std::uint32_t>(model.marker_count());
      for (int k = 0; k <= count; ++k)
        model.add_marker(id, {length * k / count, half_thickness});
      for (int k = count; k >= 0; --k)
        model.add_marker(id, {length * k / count, -half_thickness});
      const auto vertices = static_cast<std::uint32_t>(2 * (count + 1));
      for (std::uint32_t k = 0; k < vertices; ++k) {
        scene.boundary.segments.insert(scene.boundary.segments.end(),
                                       {first + k, first + (k + 1) % vertices});
      }
    });
  }
  if (spatial) {
    detail::SpatialBodyBuilder bodies{
        model,
        scene.boundary,
        [&](const SourceLocation& where, const std::function<void()>& step) { guard(where, step); },
        [&](const SourceLocation& where, const std::string& message, const std::string& fix) {
          problems.push_back({where, message, fix});
        },
        [&](const View& mesh, std::string_view key) {
          return read_scene_stl(mesh, key, scene_dir, problems);
        },
        skipped_bodies,
        unnamed_body_skipped};
    detail::build_spatial_bodies(root, bodies);
  }
  scene.boundary.dynamic_vertex_count = static_cast<std::size_t>(model.marker_count());
  for (const View& ground : root.blocks("Ground")) {
    for (const View& mesh : ground.blocks("Mesh")) {
      guard(mesh.location(), [&] {
        if (spatial) {
          add_surface(mesh);
        } else {
          add_mesh(mesh, mbd::kGround);
        }
      });
    }
  }
  scene.boundary.vertex_count =
      static_cast<std::size_t>(model.marker_count()) +
      (spatial ? scene.boundary.static_positions.size() / 3 : std::size_t{0});
  guard(root.location(), [&] {
    const View coupling = root.block("Coupling");
    scene.boundary.refinement_resolution = coupling.number("refinement_resolution");
    scene.boundary.refinement_option = static_cast<int>(coupling.integer("refinement_option"));
    if (!spatial && scene.boundary.refinement_option != 1) {
      problems.push_back({coupling.location("refinement_option"),
                          "refinement_option " + std::to_string(scene.boundary.refinement_option) +
                              " is for 3D triangle meshes; 2D segments are bisected at every step",
                          "remove refinement_option or set it to 1"});
    }
  });
  // 3D: a Ground mesh that gave no triangles has its own problem (no STL, unreadable file).
  bool surface_given = false;
  for (const View& ground : root.blocks("Ground"))
    surface_given = surface_given || (spatial && ground.has_block("Mesh"));
  if (scene.boundary.elements().empty() && !skipped_any && !surface_given) {
    problems.push_back({scene.parameters.location,
                        "the scene has no surface mesh: the fluid would see no structure",
                        spatial ? "add Ground { Mesh { stl = \"file.stl\" } }"
                                : "add Mesh { points = ... } to bodies or Ground"});
  }

  // A body the element names; a body skipped for a value in error skips the element too.
  auto find_body = [&](const View& element, std::string_view key) -> mbd::BodyId {
    const std::string& name = element.string(key);
    if (std::find(skipped_bodies.begin(), skipped_bodies.end(), name) != skipped_bodies.end()) {
      throw AlreadyReported(element.location(key));
    }
    try {
      return model.find_body(name);
    } catch (const Error& error) {
      if (unnamed_body_skipped) throw AlreadyReported(element.location(key));  // perhaps it
      throw Error(error.fault(), element.location(key).text(), error.remedy());
    }
  };
  for (const View& c : spatial ? std::vector<View>{} : root.blocks("CoordinateConstraint")) {
    guard(c.location(), [&] {
      const mbd::BodyId body = find_body(c, "body");
      std::optional<double> value;
      if (c.has("value")) value = c.number("value");
      model.add_coordinate_constraint(body, coordinate_of(c.string("coordinate")), value);
    });
  }
  for (const View& c : spatial ? std::vector<View>{} : root.blocks("VelocityConstraint")) {
    guard(c.location(), [&] {
      const mbd::BodyId body = find_body(c, "body");
      model.add_velocity_constraint(body, coordinate_of(c.string("coordinate")),
                                    c.number("velocity"));
    });
  }
  auto point_spec = [&](const View& element, const std::string& side) {
    mbd::BodyPointSpec point;
    if (side == "a" || element.has("body_b")) point.body = find_body(element, "body_" + side);
    const auto local = element.vector("point_" + side);
    point.local = {local[0], local[1]};
    return point;
  };
  // The model's messages name no place: give them the element's.
  auto placed = [](const View& element, auto&& add) {
    try {
      add();
    } catch (const AlreadyReported&) {
      throw;
    } catch (const Error& error) {
      throw Error(error.fault(), element.location().text(), error.remedy());
    }
  };
  detail::NamedElements named;
  detail::ElementBuilder elements{
      model,
      named,
      [&](const SourceLocation& where, const std::function<void()>& step) { guard(where, step); },
      [&](const View& element, std::string_view key) { return find_body(element, key); },
      [&](const View& element, const std::string& side) { return point_spec(element, side); },
      [&](const View& element, const std::function<void()>& add) { placed(element, add); },
      [&](const SourceLocation& where, const std::string& message, const std::string& fix) {
        problems.push_back({where, message, fix});
      },
      scene.solver.end_time};
  auto name_of = [](const View& element) {
    return element.has("name") ? element.string("name") : std::string();
  };
  for (const View& c : spatial ? std::vector<View>{} : root.blocks("BeamClamp")) {
    guard(c.location(), [&] {
      const mbd::BodyId beam = find_body(c, "beam");
      const auto node = static_cast<int>(c.integer("node"));
      const auto slope =
          c.string("slope") == "full" ? mbd::BeamClamp::Full : mbd::BeamClamp::Direction;
      const mbd::BodyId to = c.has("to") ? find_body(c, "to") : mbd::kGround;
      placed(c, [&] { model.add_beam_clamp(beam, node, slope, to); });
    });
  }
  for (const View& j : spatial ? std::vector<View>{} : root.blocks("RevoluteJoint")) {
    guard(j.location(), [&] {
      const auto a = point_spec(j, "a");
      const auto b = point_spec(j, "b");
      int row = 0;
      placed(j, [&] { row = model.add_revolute_joint(a, b, name_of(j)); });
      detail::register_joint(elements, j, {row, 2, a.body, "revolute joint"});
    });
  }
  for (const View& c : spatial ? std::vector<View>{} : root.blocks("DistanceConstraint")) {
    guard(c.location(), [&] {
      const auto a = point_spec(c, "a");
      const auto b = point_spec(c, "b");
      std::optional<double> length;
      if (c.has("length")) length = c.number("length");
      int row = 0;
      placed(c, [&] { row = model.add_distance_constraint(a, b, length, name_of(c)); });
      detail::register_joint(elements, c, {row, 1, a.body, "distance constraint"});
    });
  }
  for (const View& f : spatial ? std::vector<View>{} : root.blocks("SpringDamper")) {
    guard(f.location(), [&] {
      mbd::SpringDamperSpec spec;
      spec.a = point_spec(f, "a");
      spec.b = point_spec(f, "b");
      spec.stiffness = f.number("stiffness");
      spec.damping = f.number("damping");
      if (f.has("rest_length")) spec.rest_length = f.number("rest_length");
      placed(f, [&] { model.add_spring_damper(spec); });
      detail::register_force_element(elements, f, model.force_element_count() - 1, false);
    });
  }
  if (spatial) {
    detail::build_spatial_connectors(root, elements);
  } else {
    detail::build_elements(root, elements);
  }
  // The joint or spring a sensor names; a problem at its key (and nullptr) when there is none.
  auto named_joint = [&](const View& s) -> const detail::NamedJoint* {
    const auto found = named.joints.find(s.string("joint"));
    if (found != named.joints.end()) return &found->second;
    problems.push_back({s.location("joint"), "no joint named '" + s.string("joint") + "'",
                        "give the joint block name = \"" + s.string("joint") + "\""});
    return nullptr;
  };
  auto named_spring = [&](const View& s, const std::string& block) -> std::optional<int> {
    const auto found = named.force_elements.find(s.string("element"));
    if (found != named.force_elements.end() && found->second >= 0) return found->second;
    problems.push_back({s.location("element"), "no spring named '" + s.string("element") + "'",
                        "give the " + block + " name = \"" + s.string("element") + "\""});
    return std::nullopt;
  };
  // A sensor of a 3D scene: components x, y, z of the centre of mass (position, velocity of a
  // RigidBody3D or PointMass) or of a force (fluid_force on any spatial body, joint_force on
  // its body_a, total_fluid_force), or an energy.
  auto build_spatial_sensor = [&](const View& s, const std::string& type,
                                  const std::string& component, SensorSpec& sensor) {
    if (sensor.type == SensorType::ConstraintForce) {
      problems.push_back({s.location("type"), "a " + type + " sensor has no 3D form yet",
                          "use joint_force (the force a named joint exerts) or fluid_force"});
      return;
    }
    const bool spring = sensor.type == SensorType::SpringForce;
    const bool energy =
        sensor.type == SensorType::KineticEnergy || sensor.type == SensorType::PotentialEnergy;
    const bool on_body = sensor.type == SensorType::Position ||
                         sensor.type == SensorType::Velocity ||
                         sensor.type == SensorType::FluidForce;
    bool complete = true;
    auto check_key = [&](const char* key, bool wanted, const std::string& example) {
      if (wanted && !s.has(key)) {
        problems.push_back({s.location("name"), "sensor '" + sensor.name + "' needs " + key,
                            std::string("add ") + key + " = " + example});
        complete = false;
      } else if (!wanted && s.has(key)) {
        problems.push_back({s.location(key), "a " + type + " sensor takes no " + key, "remove it"});
        complete = false;
      }
    };
    check_key("body", on_body, "\"...\"");
    check_key("joint", sensor.type == SensorType::JointForce, "\"...\" (a joint's name)");
    check_key("element", spring, "\"...\" (a SpringDamper3D's name)");
    check_key("component", !energy && !spring, "\"x\"");
    const bool kinematic =
        sensor.type == SensorType::Position || sensor.type == SensorType::Velocity;
    if (!kinematic && s.has("point")) check_key("point", false, "");
    if (!complete) return;
    const bool torque = component.rfind("torque_", 0) == 0;
    if (!energy && !spring) {
      const bool takes_torque =
          sensor.type == SensorType::FluidForce || sensor.type == SensorType::JointForce;
      if ((component != "x" && component != "y" && component != "z" && !torque) ||
          (torque && !takes_torque)) {
        problems.push_back({s.location("component"),
                            "a 3D " + type + " sensor has components x, y or z" +
                                (takes_torque ? " (or torque_x, torque_y, torque_z)" : ""),
                            "write x, y or z (angles of 3D bodies are not sensors yet)"});
        return;
      }
      const char last = component.back();
      sensor.axis = (last == 'z' ? 2 : last == 'y' ? 1 : 0) + (torque ? 3 : 0);
    }
    sensor.unit = sensor.type == SensorType::Position   ? "m"
                  : sensor.type == SensorType::Velocity ? "m/s"
                  : energy                              ? "J"
                  : torque                              ? "N m"
                                                        : "N";
    if (on_body) sensor.body = find_body(s, "body");
    if (kinematic && s.has("point")) {
      const auto point = dimension_vector(s, "point", 3, problems);
      if (!point) return;
      sensor.point = std::array<double, 3>{(*point)[0], (*point)[1], (*point)[2]};
      try {
        model.check_spatial_point({sensor.body, {(*point)[0], (*point)[1], (*point)[2]}},
                                  "sensor '" + sensor.name + "'");
      } catch (const Error& error) {
        problems.push_back({s.location("point"), error.fault(), error.remedy()});
        return;
      }
    }
    if (kinematic && !sensor.point && model.is_cable(sensor.body)) {
      problems.push_back({s.location("body"),
                          "a " + type + " sensor reads a centre of mass, and '" + s.string("body") +
                              "' is an AncfCable3D",
                          "give a centre-line point = [s, 0, 0], or use type = \"fluid_force\""});
      return;
    }
    if (spring) {
      const std::optional<int> element = named_spring(s, "SpringDamper3D block");
      if (!element) return;
      sensor.force_element = *element;
    }
    if (sensor.type == SensorType::JointForce) {
      const detail::NamedJoint* joint = named_joint(s);
      if (joint == nullptr) return;
      sensor.body = joint->body;
      if (sensor.body == mbd::kGround || model.is_cable(sensor.body)) {
        problems.push_back(
            {s.location("joint"),
             "joint '" + s.string("joint") + "' has no rigid body or point mass as its first body",
             "give the joint a RigidBody3D or PointMass as body_a (body of a "
             "FixedJoint3D)"});
        return;
      }
      sensor.first_row = joint->first_row;
      sensor.rows = joint->rows;
    }
    for (const auto& other : scene.sensors) {
      if (other.name == sensor.name) {
        problems.push_back(
            {s.location("name"), "a second sensor is named '" + sensor.name + "'", "rename it"});
        return;
      }
    }
    scene.sensors.push_back(sensor);
  };
  for (const View& s : root.blocks("Sensor")) {
    guard(s.location(), [&] {
      SensorSpec sensor;
      sensor.name = s.string("name");
      const std::string type = s.string("type");
      const std::string component = s.has("component") ? s.string("component") : std::string();
      sensor.type = type == "position"           ? SensorType::Position
                    : type == "velocity"         ? SensorType::Velocity
                    : type == "fluid_force"      ? SensorType::FluidForce
                    : type == "constraint_force" ? SensorType::ConstraintForce
                    : type == "joint_force"      ? SensorType::JointForce
                    : type == "spring_force"     ? SensorType::SpringForce
                    : type == "kinetic_energy"   ? SensorType::KineticEnergy
                    : type == "potential_energy" ? SensorType::PotentialEnergy
                                                 : SensorType::TotalFluidForce;
      if (spatial) {
        build_spatial_sensor(s, type, component, sensor);
        return;
      }
      if (component == "z" && !spatial) {
        problems.push_back({s.location("component"),
                            "component z needs a 3D scene (dimension = 2 here)",
                            "write x or y, or set dimension = 3"});
        return;
      }
      sensor.axis = component == "z" ? 2 : component == "y" ? 1 : 0;
      for (const auto& other : scene.sensors) {
        if (other.name == sensor.name) {
          problems.push_back(
              {s.location("name"), "a second sensor is named '" + sensor.name + "'", "rename it"});
        }
      }
      // Which of body, joint, element and component the type takes.
      const bool on_body =
          sensor.type == SensorType::Position || sensor.type == SensorType::Velocity ||
          sensor.type == SensorType::FluidForce || sensor.type == SensorType::ConstraintForce;
      const bool energy =
          sensor.type == SensorType::KineticEnergy || sensor.type == SensorType::PotentialEnergy;
      const bool has_component = !energy && sensor.type != SensorType::SpringForce;
      const bool force = sensor.type != SensorType::Position && sensor.type != SensorType::Velocity;
      bool complete = true;
      auto forbid = [&](const char* key, const std::string& fix) {
        if (!s.has(key)) return;
        problems.push_back({s.location(key), "a " + type + " sensor takes no " + key, fix});
        complete = false;
      };
      auto need = [&](const char* key, const std::string& example) {
        if (s.has(key)) return;
        problems.push_back({s.location("name"), "sensor '" + sensor.name + "' needs " + key,
                            std::string("add ") + key + " = " + example});
        complete = false;
      };
      if (!on_body)
        forbid("body", sensor.type == SensorType::TotalFluidForce
                           ? "remove body, or use type = \"fluid_force\""
                           : "remove it");
      if (sensor.type != SensorType::JointForce) forbid("joint", "remove it");
      if (sensor.type != SensorType::SpringForce) forbid("element", "remove it");
      if (!has_component) forbid("component", "remove it");
      const bool kinematic =
          sensor.type == SensorType::Position || sensor.type == SensorType::Velocity;
      if (!kinematic) forbid("point", "remove it (point is for position and velocity sensors)");
      if (component.rfind("torque_", 0) == 0) {
        problems.push_back({s.location("component"),
                            "torque_x, torque_y and torque_z are components of 3D sensors",
                            "write torque"});
        complete = false;
      }
      if (has_component) need("component", "\"x\"");
      if (on_body) need("body", "\"...\"");
      if (sensor.type == SensorType::JointForce) need("joint", "\"...\" (a joint's name)");
      if (sensor.type == SensorType::SpringForce) need("element", "\"...\" (a spring's name)");
      if (has_component && !component.empty()) {
        if (force && component == "angle") {
          problems.push_back({s.location("component"),
                              "a force sensor has components x, y or torque", "write torque"});
        }
        if (!force && component == "torque") {
          problems.push_back({s.location("component"),
                              "a " + type + " sensor has components x, y or angle", "write angle"});
        }
        if (sensor.type == SensorType::TotalFluidForce && component == "torque") {
          problems.push_back({s.location("component"),
                              spatial ? "total_fluid_force has components x, y and z"
                                      : "total_fluid_force has components x and y",
                              spatial ? "write x, y or z" : "write x or y"});
        }
        sensor.component = coordinate_of(component);
      }
      if (!complete) return;
      const bool rotational = sensor.component == mbd::Coordinate::Angle;
      sensor.unit = sensor.type == SensorType::Position   ? (rotational ? "rad" : "m")
                    : sensor.type == SensorType::Velocity ? (rotational ? "rad/s" : "m/s")
                    : energy                              ? "J/m"
                                                          : (rotational ? "N m/m" : "N/m");
      if (spatial && force) sensor.unit = "N";  // a 3D force, not per unit depth
      if (on_body) sensor.body = find_body(s, "body");
      if (kinematic && s.has("point")) {
        if (rotational) {
          problems.push_back({s.location("component"), "a point has components x and y, no angle",
                              "write x or y, or remove point for the body's angle"});
          return;
        }
        const auto point = dimension_vector(s, "point", 2, problems);
        if (!point) return;
        sensor.point = std::array<double, 3>{(*point)[0], (*point)[1], 0.0};
        try {
          model.check_point({sensor.body, {(*point)[0], (*point)[1]}},
                            "sensor '" + sensor.name + "'");
        } catch (const Error& error) {
          problems.push_back({s.location("point"), error.fault(), error.remedy()});
          return;
        }
        sensor.axis = sensor.component == mbd::Coordinate::Y ? 1 : 0;
      }
      if (on_body && model.is_beam(sensor.body) && sensor.type != SensorType::FluidForce &&
          !sensor.point) {
        problems.push_back({s.location("type"),
                            "a " + type + " sensor reads rigid-body coordinates, and '" +
                                s.string("body") + "' is an AncfBeam2D",
                            "give a beam point = [s, eta], or use type = \"fluid_force\""});
        return;
      }
      if (sensor.type == SensorType::JointForce) {
        const detail::NamedJoint* joint = named_joint(s);
        if (joint == nullptr) return;
        sensor.body = joint->body;
        if (sensor.body != mbd::kGround && model.is_beam(sensor.body)) {
          problems.push_back({s.location("joint"),
                              "joint '" + s.string("joint") +
                                  "' holds an AncfBeam2D as its first body; joint_force reads a "
                                  "rigid body's force and torque",
                              "give the joint a rigid body as body_a, or measure the beam with "
                              "a fluid_force sensor"});
          return;
        }
        sensor.first_row = joint->first_row;
        sensor.rows = joint->rows;
      }
      if (sensor.type == SensorType::SpringForce) {
        const std::optional<int> element = named_spring(s, "spring block");
        if (!element) return;
        sensor.force_element = *element;
        if (named.rotational[s.string("element")]) sensor.unit = "N m/m";
      }
      scene.sensors.push_back(sensor);
    });
  }

  // Fluid particles on a lattice.
  if (root.has_block("FluidRegion")) {
    guard(root.block("FluidRegion").location(), [&] {
      build_fluid(root.block("FluidRegion"), dimension, scene_dir, scene.fluid, problems);
    });
  }

  // LIGGGHTS scripts and variables.
  const View liggghts = root.block("LIGGGHTS");
  guard(liggghts.location(), [&] {
    scene.liggghts.script1_name = liggghts.string("script1");
    scene.liggghts.script1_text =
        read_script(scene_dir, scene.liggghts.script1_name, liggghts.location("script1"), problems);
  });
  guard(liggghts.location(), [&] {
    scene.liggghts.script2_name = liggghts.string("script2");
    scene.liggghts.script2_text =
        read_script(scene_dir, scene.liggghts.script2_name, liggghts.location("script2"), problems);
  });
  guard(liggghts.location(), [&] {
    scene.liggghts.equilibration_steps =
        static_cast<std::uint64_t>(liggghts.integer("equilibration_steps"));
  });
  if (const Block* sph = scene.parameters.child("LIGGGHTS_SPH_parameters")) {
    for (const Parameter& p : sph->parameters) {
      if (p.failed) continue;
      if (p.value.kind == ValueKind::Number) {
        scene.liggghts.variables.emplace_back(p.key, format_exact(p.value.number));
      } else if (p.value.kind == ValueKind::String) {
        scene.liggghts.variables.emplace_back(p.key, p.value.text);
      } else {
        problems.push_back(
            {p.location,
             "LIGGGHTS variable '" + p.key + "' is a " + std::string(name(p.value.kind)),
             "LIGGGHTS variables are numbers or strings"});
      }
    }
  }

  const auto assembly = detail::assembly_request(root, model, problems);

  // In the order of the scene file; problems in included files after it.
  std::stable_sort(problems.begin(), problems.end(), [&](const Problem& a, const Problem& b) {
    const auto key = [&](const Problem& p) {
      return std::make_tuple(p.location.file != path, p.location.file, p.location.line,
                             p.location.column);
    };
    return key(a) < key(b);
  });
  throw_if_any(problems, path);
  FSI_ASSERT(input_sound && !skipped_any, "a value in error was skipped without a problem");
  if (assembly) scene.assembly = detail::assemble_initial_configuration(model, *assembly);
  try {
    (void)model.initial_state();
  } catch (const Error& error) {
    throw Error(error.fault(), path, error.remedy());
  }
  return scene;
}

}  // namespace fsi::scene
