#include "fsi/coupling/particle_pairs.hpp"

#include <cmath>

#include "fsi/common/error.hpp"
#include "fsi/contact/cell_grid.hpp"

namespace fsi::coupling {

ParticlePairs particle_pairs_closer_than(std::span<const double> positions, int dimension,
                                         double radius) {
  FSI_ASSERT(dimension == 2 || dimension == 3, "particle pairs in 2D or 3D only");
  FSI_ASSERT(radius > 0.0, "particle pairs within a positive radius");
  const auto dim = static_cast<std::size_t>(dimension);
  ParticlePairs pairs;
  contact::for_each_close_pair(
      positions, positions, dimension, radius, [&](std::size_t i, std::size_t j, double squared) {
        if (j <= i) return;  // each pair once
        ++pairs.count;
        const double distance = std::sqrt(squared);
        if (pairs.closest && distance >= *pairs.closest) return;
        pairs.closest = distance;
        pairs.where.assign(dim, 0.0);
        for (std::size_t k = 0; k < dim; ++k)
          pairs.where[k] = 0.5 * (positions[dim * i + k] + positions[dim * j + k]);
      });
  return pairs;
}

std::optional<double> nearest_particle_distance(std::span<const double> positions, int dimension,
                                                std::size_t index) {
  FSI_ASSERT(dimension == 2 || dimension == 3, "particle distances in 2D or 3D only");
  const auto dim = static_cast<std::size_t>(dimension);
  FSI_ASSERT(dim * (index + 1) <= positions.size(), "a particle index within the positions");
  std::optional<double> nearest;
  for (std::size_t j = 0; j < positions.size() / dim; ++j) {
    if (j == index) continue;
    double squared = 0.0;
    for (std::size_t k = 0; k < dim; ++k) {
      const double delta = positions[dim * index + k] - positions[dim * j + k];
      squared += delta * delta;
    }
    if (!nearest || squared < *nearest) nearest = squared;
  }
  if (nearest) nearest = std::sqrt(*nearest);
  return nearest;
}

}  // namespace fsi::coupling
