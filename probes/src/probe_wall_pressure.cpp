// wall_pressure: the normal force per length (2D) or area (3D) of the fluid on a patch of the
// boundary mesh, from the wall law's own forces at its sampling points (fix fsi/sph, thesis eq.
// 4.2), not from the vertex forces, so that a patch smaller than an element is resolved:
//   p = sum_s -F_s . n_s / sum_s A_s
// over the sampling points s of the patch: those of the named mesh's elements (one body's or the
// ground's) that lie within `radius` of `centre` at the evaluation (a patch fixed in space) and
// whose element faces the fluid side to within 45 degrees (at a corner, the wall it is on).
// F_s is the force of the fluid on the wall at s, A_s the length (area) s stands for, and n_s the
// unit normal of its element turned to the fluid's side (n_s . fluid_side >= 0), so that p > 0
// is a pressure pushing on the wall and p < 0 a suction. The columns also give the normal force
// sum_s -F_s . n_s and the particle-sample pairs within the wall law's range; a patch no particle
// reaches is dry: pairs 0, force and pressure 0.
// Parameters: the centre x, y, z, the radius, the fluid side x, y, z, the number R of element
// ranges, then R pairs [first, end) of element indices.

#include <cmath>

#include "probe_kind.hpp"

namespace fsi::probes::detail {
namespace {

constexpr std::size_t kRanges = 7;  // index of R in the parameters

std::size_t range_count(const ProbeDefinition& probe) {
  return static_cast<std::size_t>(probe.parameters[kRanges]);
}

std::string problem(const ProbeDefinition& probe, int dimension) {
  const std::string where = "wall pressure probe '" + probe.name + "'";
  if (probe.parameters.size() < kRanges + 1) return where + " has no element ranges";
  const double ranges = probe.parameters[kRanges];
  if (ranges < 1.0 || ranges > 1e6 || ranges != std::floor(ranges))
    return where + " needs 1 to 10^6 element ranges";
  if (std::string counted = count_problem(probe, kRanges + 1 + 2 * range_count(probe));
      !counted.empty())
    return counted;
  if (!(probe.parameters[3] > 0.0)) return where + " needs a positive radius";
  const double* side = &probe.parameters[4];
  if (!(squared_distance(side, std::array<double, 3>{}.data(), dimension) > 0.0))
    return where + " needs a fluid side (a direction from the wall into the fluid)";
  for (std::size_t r = 0; r < range_count(probe); ++r) {
    const double first = probe.parameters[kRanges + 1 + 2 * r];
    const double end = probe.parameters[kRanges + 2 + 2 * r];
    if (first < 0.0 || first != std::floor(first) || end != std::floor(end) || !(end > first) ||
        end > 4294967295.0)
      return where + " has an element range that is not [first, end) of element indices";
  }
  return {};
}

std::vector<Column> columns(const ProbeDefinition& probe, int dimension) {
  return {{probe.name + "_pressure", "Pa"},
          {probe.name + "_force", per_depth(dimension, "N/m", "N")},
          {probe.name + "_pairs", "-"}};
}

// Normal force, particle-sample pairs.
std::size_t sum_count(const ProbeDefinition&, int) {
  return 2;
}

bool in_ranges(const ProbeDefinition& probe, std::uint32_t element) {
  const double e = static_cast<double>(element);
  for (std::size_t r = 0; r < range_count(probe); ++r) {
    if (e >= probe.parameters[kRanges + 1 + 2 * r] && e < probe.parameters[kRanges + 2 + 2 * r])
      return true;
  }
  return false;
}

// Calls visit(s) for every sampling point of the patch.
template <class Visit>
void for_each_in_patch(const ProbeDefinition& probe, int dimension, const WallSamples& wall,
                       Visit&& visit) {
  const double* centre = probe.parameters.data();
  const double radius2 = probe.parameters[3] * probe.parameters[3];
  const double* side = &probe.parameters[4];
  for (std::size_t s = 0; s < wall.count; ++s) {
    if (squared_distance(&wall.positions[s * dimension], centre, dimension) > radius2) continue;
    if (in_ranges(probe, wall.elements[s]) &&
        faces_fluid_side(&wall.normals[s * dimension], side, dimension))
      visit(s);
  }
}

std::size_t patch_samples(const ProbeDefinition& probe, int dimension, const WallSamples& wall) {
  std::size_t count = 0;
  for_each_in_patch(probe, dimension, wall, [&](std::size_t) { ++count; });
  return count;
}

// Sums: normal force, pairs; maximum: the patch's length (area), the same on every rank.
void partials(const ProbeDefinition& probe, const ProbeContext& context, const ParticleSet&,
              const Kernel&, const WallSamples& wall, std::span<double> sums,
              std::span<double> maxima) {
  const int dimension = context.dimension;
  const double* side = &probe.parameters[4];
  double force = 0.0, pairs = 0.0, measure = 0.0;
  for_each_in_patch(probe, dimension, wall, [&](std::size_t s) {
    const double* n = &wall.normals[s * dimension];
    const double* f = &wall.forces[s * dimension];
    double facing = 0.0, along_normal = 0.0;
    for (int k = 0; k < dimension; ++k) {
      facing += n[k] * side[k];
      along_normal += f[k] * n[k];
    }
    force -= facing >= 0.0 ? along_normal : -along_normal;
    pairs += static_cast<double>(wall.pairs[s]);
    measure += wall.measures[s];
  });
  sums[0] = force;
  sums[1] = pairs;
  if (measure > 0.0) maxima[0] = measure;
}

void values(const ProbeDefinition&, const ProbeContext&, std::span<const double> sums,
            std::span<const double> maxima, std::span<double> values) {
  const double measure = maxima[0];
  const bool wet = sums[1] > 0.0 && measure > 0.0;
  values[0] = wet ? sums[0] / measure : 0.0;
  values[1] = wet ? sums[0] : 0.0;
  values[2] = sums[1];
}

// The patch's centre moves with a body and its fluid side turns with it; the elements stay.
void place(std::span<double> parameters, const RigidPlacement& placement) {
  move_point(parameters, 0, placement);
  turn_direction(parameters, 4, placement);
}

}  // namespace

KindRules wall_pressure_probe_rules() {
  return {ProbeKind::WallPressure,
          "wall_pressure",
          problem,
          columns,
          sum_count,
          one_partial,
          partials,
          values,
          patch_samples,
          place};
}

}  // namespace fsi::probes::detail

namespace fsi::probes {

bool faces_fluid_side(const double* normal, const double* fluid_side, int dimension) {
  double facing = 0.0, normal2 = 0.0, side2 = 0.0;
  for (int k = 0; k < dimension; ++k) {
    facing += normal[k] * fluid_side[k];
    normal2 += normal[k] * normal[k];
    side2 += fluid_side[k] * fluid_side[k];
  }
  return 2.0 * facing * facing >= normal2 * side2;
}

}  // namespace fsi::probes
