// point: velocity and pressure at a point by Shepard-normalised SPH interpolation,
//   u(x) = sum_j V_j W(|x - x_j|) u_j / sum_j V_j W(|x - x_j|),  V_j = m_j / rho_j,
// with the fluid's kernel; and how many particles lie within the kernel's support. Where none
// does the point is dry: velocity and pressure are 0 and the wet column says 0.
// Parameters: the point x, y, z.

#include <cmath>

#include "probe_kind.hpp"

namespace fsi::probes::detail {
namespace {

std::string problem(const ProbeDefinition& probe, int) {
  return count_problem(probe, 3);
}

std::vector<Column> columns(const ProbeDefinition& probe, int dimension) {
  std::vector<Column> result;
  for (int k = 0; k < dimension; ++k)
    result.push_back({probe.name + "_v" + axis_suffix(k), "m/s"});
  result.push_back({probe.name + "_pressure", "Pa"});
  result.push_back({probe.name + "_particles", "-"});
  result.push_back({probe.name + "_wet", "-"});
  return result;
}

// Weighted velocity (dimension), weighted pressure, weight sum, particle count.
std::size_t sum_count(const ProbeDefinition&, int dimension) {
  return static_cast<std::size_t>(dimension) + 3;
}

void partials(const ProbeDefinition& probe, const ProbeContext& context,
              const ParticleSet& particles, const Kernel& kernel, const WallSamples&,
              std::span<double> sums, std::span<double>) {
  const int dimension = context.dimension;
  const double* point = probe.parameters.data();
  const double support2 = kernel.support * kernel.support;
  for (std::size_t i = 0; i < particles.owned; ++i) {
    const double distance2 =
        squared_distance(point, &particles.positions[i * dimension], dimension);
    if (distance2 >= support2) continue;
    const double weight =
        particles.mass[i] / particles.density[i] * kernel.value(std::sqrt(distance2));
    for (int k = 0; k < dimension; ++k)
      sums[k] += weight * particles.velocities[i * dimension + k];
    sums[dimension] += weight * particles.pressure[i];
    sums[dimension + 1] += weight;
    sums[dimension + 2] += 1.0;
  }
}

void values(const ProbeDefinition&, const ProbeContext& context, std::span<const double> sums,
            std::span<const double>, std::span<double> values) {
  const int dimension = context.dimension;
  const double weight = sums[dimension + 1];
  const bool wet = sums[dimension + 2] > 0.0 && weight > 0.0;
  for (int k = 0; k <= dimension; ++k)
    values[k] = wet ? sums[k] / weight : 0.0;
  values[dimension + 1] = sums[dimension + 2];
  values[dimension + 2] = wet ? 1.0 : 0.0;
}

// The point moves with a body.
void place(std::span<double> parameters, const RigidPlacement& placement) {
  move_point(parameters, 0, placement);
}

}  // namespace

KindRules point_probe_rules() {
  return {ProbeKind::Point, "point",  problem, columns, sum_count,
          no_partials,      partials, values,  nullptr, place};
}

}  // namespace fsi::probes::detail
