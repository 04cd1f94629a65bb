// free_surface: the elevation of the free surface on a vertical line (the last axis: y in 2D, z
// in 3D). The line is scanned at equally spaced samples from its bottom up; at each the kernel
// sum (Shepard denominator) S(x) = sum_j V_j W(|x - x_j|), V_j = m_j / rho_j, is about 1 inside
// the fluid, about 1/2 at its surface and 0 outside. The elevation is where S falls through 1/2
// above the highest sample with S >= 1/2 (linear between that sample and the next); at the top
// of the line when the top sample is still wet. An isolated drop does not reach 1/2 (V W(0) < 1/2
// for the kernels and spacings of SPH), so spray above the surface is not taken for it. Without
// any sample at S >= 1/2 the line is dry: the elevation is the line's bottom and wet is 0.
// Parameters: the bottom point x, y, z, the length, the number of samples.

#include <algorithm>
#include <cmath>

#include "probe_kind.hpp"

namespace fsi::probes::detail {
namespace {

constexpr double kSurfaceLevel = 0.5;

std::size_t samples_of(const ProbeDefinition& probe) {
  return static_cast<std::size_t>(probe.parameters[4]);
}

std::string problem(const ProbeDefinition& probe, int) {
  if (std::string count = count_problem(probe, 5); !count.empty()) return count;
  if (!(probe.parameters[3] > 0.0))
    return "free_surface probe '" + probe.name + "' needs a length > 0";
  const double samples = probe.parameters[4];
  if (samples < 2.0 || samples > 100000.0 || samples != std::floor(samples))
    return "free_surface probe '" + probe.name + "' needs 2 to 100000 samples";
  return {};
}

std::vector<Column> columns(const ProbeDefinition& probe, int) {
  return {{probe.name + "_elevation", "m"}, {probe.name + "_wet", "-"}};
}

std::size_t sum_count(const ProbeDefinition& probe, int) {
  return samples_of(probe);
}

void partials(const ProbeDefinition& probe, const ProbeContext& context,
              const ParticleSet& particles, const Kernel& kernel, const WallSamples&,
              std::span<double> sums, std::span<double>) {
  const int dimension = context.dimension;
  const int up = dimension - 1;
  const double* bottom = probe.parameters.data();
  const double length = probe.parameters[3];
  const std::size_t samples = samples_of(probe);
  const double spacing = length / static_cast<double>(samples - 1);
  const double support2 = kernel.support * kernel.support;
  for (std::size_t i = 0; i < particles.owned; ++i) {
    const double* x = &particles.positions[i * dimension];
    double across2 = 0.0;  // squared distance from the line
    for (int k = 0; k < up; ++k)
      across2 += (x[k] - bottom[k]) * (x[k] - bottom[k]);
    if (across2 >= support2) continue;
    const double reach = std::sqrt(support2 - across2);
    const double height = x[up] - bottom[up];
    const double first = std::ceil((height - reach) / spacing);
    const double last = std::floor((height + reach) / spacing);
    if (last < 0.0 || first > static_cast<double>(samples - 1)) continue;
    const double volume = particles.mass[i] / particles.density[i];
    for (auto s = static_cast<std::size_t>(std::max(first, 0.0));
         s <= std::min(static_cast<std::size_t>(last), samples - 1); ++s) {
      const double along = height - static_cast<double>(s) * spacing;
      sums[s] += volume * kernel.value(std::sqrt(across2 + along * along));
    }
  }
}

void values(const ProbeDefinition& probe, const ProbeContext& context, std::span<const double> sums,
            std::span<const double>, std::span<double> values) {
  const double bottom = probe.parameters[static_cast<std::size_t>(context.dimension - 1)];
  const std::size_t samples = samples_of(probe);
  const double spacing = probe.parameters[3] / static_cast<double>(samples - 1);
  for (std::size_t s = samples; s-- > 0;) {
    if (sums[s] < kSurfaceLevel) continue;
    double elevation = bottom + static_cast<double>(s) * spacing;
    if (s + 1 < samples) elevation += spacing * (sums[s] - kSurfaceLevel) / (sums[s] - sums[s + 1]);
    values[0] = elevation;
    values[1] = 1.0;
    return;
  }
  values[0] = bottom;
  values[1] = 0.0;
}

// The line's bottom moves with a body; the line stays vertical (along gravity's axis).
void place(std::span<double> parameters, const RigidPlacement& placement) {
  move_point(parameters, 0, placement);
}

}  // namespace

KindRules free_surface_probe_rules() {
  return {ProbeKind::FreeSurface,
          "free_surface",
          problem,
          columns,
          sum_count,
          no_partials,
          partials,
          values,
          nullptr,
          place};
}

}  // namespace fsi::probes::detail
