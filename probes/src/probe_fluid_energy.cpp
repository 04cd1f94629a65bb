// fluid_energy: kinetic energy sum m v^2 / 2 and potential energy sum m (-g) . (x - datum) of
// every particle. Parameters: the datum point x, y, z.

#include "probe_kind.hpp"

namespace fsi::probes::detail {
namespace {

std::string problem(const ProbeDefinition& probe, int) {
  return count_problem(probe, 3);
}

std::vector<Column> columns(const ProbeDefinition& probe, int dimension) {
  const std::string unit = per_depth(dimension, "J/m", "J");
  return {{probe.name + "_kinetic", unit}, {probe.name + "_potential", unit}};
}

std::size_t two(const ProbeDefinition&, int) {
  return 2;
}

void partials(const ProbeDefinition& probe, const ProbeContext& context,
              const ParticleSet& particles, const Kernel&, const WallSamples&,
              std::span<double> sums, std::span<double>) {
  const int dimension = context.dimension;
  const double* datum = probe.parameters.data();
  double kinetic = 0.0, potential = 0.0;
  for (std::size_t i = 0; i < particles.owned; ++i) {
    const double* x = &particles.positions[i * dimension];
    const double* v = &particles.velocities[i * dimension];
    double speed2 = 0.0, height_times_g = 0.0;
    for (int k = 0; k < dimension; ++k) {
      speed2 += v[k] * v[k];
      height_times_g -= context.gravity[k] * (x[k] - datum[k]);
    }
    kinetic += 0.5 * particles.mass[i] * speed2;
    potential += particles.mass[i] * height_times_g;
  }
  sums[0] = kinetic;
  sums[1] = potential;
}

void values(const ProbeDefinition&, const ProbeContext&, std::span<const double> sums,
            std::span<const double>, std::span<double> values) {
  values[0] = sums[0];
  values[1] = sums[1];
}

}  // namespace

KindRules fluid_energy_probe_rules() {
  return {
      ProbeKind::FluidEnergy, "fluid_energy", problem, columns, two, no_partials, partials, values};
}

}  // namespace fsi::probes::detail
