// front: the foremost fluid along an axis. A particle counts as fluid only with at least
// min_neighbours other particles within 2 d (d the particle spacing), so that isolated spray
// ahead of the front is ignored; the front is the largest coordinate (times the direction) of a
// particle that counts. Without one the fluid is absent: the position is 0 and wet is 0.
// Parameters: axis (0 x, 1 y, 2 z), direction (+1 or -1), min_neighbours.

#include <algorithm>
#include <cmath>
#include <numeric>

#include "probe_kind.hpp"

namespace fsi::probes::detail {
namespace {

struct FrontRule {
  int axis;
  double direction;
  std::size_t min_neighbours;
};

FrontRule rule_of(const ProbeDefinition& probe) {
  return {static_cast<int>(probe.parameters[0]), probe.parameters[1],
          static_cast<std::size_t>(probe.parameters[2])};
}

std::string problem(const ProbeDefinition& probe, int dimension) {
  if (std::string count = count_problem(probe, 3); !count.empty()) return count;
  const double axis = probe.parameters[0];
  if (axis != std::floor(axis) || axis < 0.0 || axis >= dimension)
    return "front probe '" + probe.name + "' has an axis outside 0 to " +
           std::to_string(dimension - 1);
  if (std::abs(probe.parameters[1]) != 1.0)
    return "front probe '" + probe.name + "' needs a direction of +1 or -1";
  const double neighbours = probe.parameters[2];
  if (neighbours < 0.0 || neighbours > 1000.0 || neighbours != std::floor(neighbours))
    return "front probe '" + probe.name + "' needs min_neighbours from 0 to 1000";
  return {};
}

std::vector<Column> columns(const ProbeDefinition& probe, int) {
  return {{probe.name + "_position", "m"}, {probe.name + "_wet", "-"}};
}

void partials(const ProbeDefinition& probe, const ProbeContext& context,
              const ParticleSet& particles, const Kernel&, const WallSamples&, std::span<double>,
              std::span<double> maxima) {
  const int dimension = context.dimension;
  const FrontRule rule = rule_of(probe);
  const double radius = 2.0 * context.particle_spacing;
  const double radius2 = radius * radius;
  const std::size_t all = particles.positions.size() / static_cast<std::size_t>(dimension);
  auto ahead = [&](std::size_t i) {
    return rule.direction * particles.positions[i * dimension + rule.axis];
  };
  // The rank's own particles from the front backwards, the first that counts is the front: a
  // heap, since that is usually one of the first few (a sort would order all of them).
  std::vector<std::size_t> order(particles.owned);
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto behind = [&](std::size_t a, std::size_t b) { return ahead(a) < ahead(b); };
  std::make_heap(order.begin(), order.end(), behind);
  for (auto end = order.end(); end != order.begin(); --end) {
    std::pop_heap(order.begin(), end, behind);
    const std::size_t candidate = *(end - 1);
    const double* x = &particles.positions[candidate * dimension];
    std::size_t neighbours = 0;
    for (std::size_t j = 0; j < all && neighbours < rule.min_neighbours; ++j) {
      if (j != candidate &&
          squared_distance(x, &particles.positions[j * dimension], dimension) < radius2)
        ++neighbours;
    }
    if (neighbours >= rule.min_neighbours) {
      maxima[0] = ahead(candidate);
      return;
    }
  }
}

void values(const ProbeDefinition& probe, const ProbeContext&, std::span<const double>,
            std::span<const double> maxima, std::span<double> values) {
  const bool wet = std::isfinite(maxima[0]);
  values[0] = wet ? rule_of(probe).direction * maxima[0] : 0.0;
  values[1] = wet ? 1.0 : 0.0;
}

}  // namespace

KindRules front_probe_rules() {
  return {ProbeKind::Front, "front", problem, columns, no_partials, one_partial, partials, values};
}

}  // namespace fsi::probes::detail
