#pragma once
// Probes: measurements of the fluid itself (docs/user-guide.md, "Probes"), declared in the scene,
// evaluated by fsi-client where the particles are, and written by fsi-server as columns of
// sensors.csv. This header is what both sides share: a probe's definition as it travels in
// protocol 1.3 and the columns it writes.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fsi::probes {

// The wire ids of the probe kinds (ProbeSetup, docs/protocol.md): never renumber one.
enum class ProbeKind : std::uint32_t {
  FluidEnergy = 1,
  Point = 2,
  FreeSurface = 3,
  Front = 4,
  Flux = 5,
  WallPressure = 6
};

// One probe. `parameters` holds the kind's numbers in the kind's own order; build definitions
// with the functions below rather than by hand.
struct ProbeDefinition {
  ProbeKind kind = ProbeKind::FluidEnergy;
  std::string name;
  std::vector<double> parameters;
  bool operator==(const ProbeDefinition&) const = default;
};

// What every probe of a run shares.
struct ProbeContext {
  int dimension = 2;
  std::array<double, 3> gravity{};  // [m/s^2] (2D: z = 0)
  // The particle spacing d [m] (front: the neighbour radius is 2 d); 0: fsi-client derives it
  // from the particles' mass and density, (m / rho)^(1 / dimension).
  double particle_spacing = 0.0;
};

// Kinetic energy sum m v^2 / 2 and potential energy sum m (-g) . (x - datum) of every particle.
ProbeDefinition fluid_energy_probe(std::string name, const std::array<double, 3>& datum);
// Velocity and pressure at `point`, Shepard-normalised SPH interpolation.
ProbeDefinition point_probe(std::string name, const std::array<double, 3>& point);
// The free-surface elevation on the vertical line (the last axis: y in 2D, z in 3D) from `bottom`
// up by `length`, scanned at `samples` equally spaced points.
ProbeDefinition free_surface_probe(std::string name, const std::array<double, 3>& bottom,
                                   double length, int samples);
// The foremost fluid along `axis` (0 x, 1 y, 2 z) in `direction` (+1 or -1), counting only
// particles with at least `min_neighbours` others within 2 d.
ProbeDefinition front_probe(std::string name, int axis, int direction, int min_neighbours);

// The volume flux through a segment (2D: two points) or a planar polygon (3D: three or more
// points, in order), each section sampled by the midpoint rule on `samples` pieces per side.
ProbeDefinition flux_probe(std::string name, const std::vector<std::array<double, 3>>& points,
                           int samples);

// The normal force per length (2D) or area (3D) of the fluid on the patch of the boundary mesh
// within `radius` of `centre`, among the elements of `element_ranges` ([first, end) pairs of
// element indices of the boundary mesh: one body's or the ground's mesh); `fluid_side` points
// from the wall into the fluid (positive: a pressure pushing on the wall).
ProbeDefinition wall_pressure_probe(
    std::string name, const std::array<double, 3>& centre, double radius,
    const std::array<double, 3>& fluid_side,
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& element_ranges);

// Does an element whose normal is `normal` (any length, either orientation) face `fluid_side` to
// within 45 degrees? A wall pressure probe reads only those elements of its patch: at a corner,
// the wall it is on, not the floor its radius also reaches. `dimension` components each.
bool faces_fluid_side(const double* normal, const double* fluid_side, int dimension);

// A rigid motion of a body from its initial configuration to its current one, x -> R x + b: a
// probe declared with `body = "NAME"` is placed by it at every probe step (protocol 1.4,
// ProbePlacement).
struct RigidPlacement {
  std::array<double, 9> rotation{1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};  // R, row by row
  std::array<double, 3> translation{};                                          // b [m]
  std::array<double, 3> point(const std::array<double, 3>& x) const;            // R x + b
  std::array<double, 3> direction(const std::array<double, 3>& v) const;        // R v
};

// Can a probe of this kind move with a body? Those with a place in space can: point,
// free_surface, flux, wall_pressure; fluid_energy and front measure all the fluid.
bool can_move(ProbeKind kind);
// The probe declared as `initial` (world coordinates in the bodies' initial configuration) where
// `placement` carries it: its points moved, its directions turned; the free-surface probe's line
// stays vertical (its bottom moves), the wall pressure probe keeps its elements. Throws
// fsi::Error for a kind that cannot move.
ProbeDefinition placed(const ProbeDefinition& initial, const RigidPlacement& placement);

// Does the probe read the wall law's sampling points (WallSamples) rather than the particles?
bool reads_wall_samples(const ProbeDefinition& probe);

// A column of sensors.csv.
struct Column {
  std::string name;
  std::string unit;
};

// The columns a probe writes, in order: the one place that maps probes to sensors.csv columns.
// Units per unit depth in 2D.
std::vector<Column> columns(const ProbeDefinition& probe, int dimension);

// "fluid_energy", "point", "free_surface", "front", "flux", "wall_pressure"; "kind 42" for an
// unknown id.
std::string kind_name(ProbeKind kind);
bool is_known_kind(std::uint32_t kind);

// Empty when the definition fits its kind in this dimension; otherwise what is wrong (a wire
// definition from a peer is checked with it before use).
std::string definition_problem(const ProbeDefinition& probe, int dimension);

}  // namespace fsi::probes
