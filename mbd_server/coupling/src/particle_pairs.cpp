#include "fsi/coupling/particle_pairs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "fsi/common/error.hpp"

namespace fsi::coupling {

ParticlePairs particle_pairs_closer_than(std::span<const double> positions, int dimension,
                                         double radius) {
  FSI_ASSERT(dimension == 2 || dimension == 3, "particle pairs in 2D or 3D only");
  FSI_ASSERT(radius > 0.0, "particle pairs within a positive radius");
  const auto dim = static_cast<std::size_t>(dimension);
  const std::size_t count = positions.size() / dim;
  using Cell = std::array<std::int64_t, 3>;
  const auto cell_of = [&](std::size_t i) {
    Cell cell{0, 0, 0};
    for (std::size_t k = 0; k < dim; ++k)
      cell[k] = static_cast<std::int64_t>(std::floor(positions[dim * i + k] / radius));
    return cell;
  };
  // The particles sorted by cell; a cell's particles are one run of `order`.
  std::vector<std::pair<Cell, std::size_t>> order;
  order.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
    order.emplace_back(cell_of(i), i);
  std::sort(order.begin(), order.end());
  const auto run_of = [&](const Cell& cell) {
    const auto first =
        std::lower_bound(order.begin(), order.end(), std::pair{cell, std::size_t{0}});
    auto last = first;
    while (last != order.end() && last->first == cell)
      ++last;
    return std::pair{first, last};
  };
  ParticlePairs pairs;
  const std::int64_t reach_z = dim == 3 ? 1 : 0;
  for (const auto& [home, i] : order) {
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -reach_z; dz <= reach_z; ++dz) {
          const auto [first, last] = run_of({home[0] + dx, home[1] + dy, home[2] + dz});
          for (auto it = first; it != last; ++it) {
            const std::size_t j = it->second;
            if (j <= i) continue;  // each pair once
            double squared = 0.0;
            for (std::size_t k = 0; k < dim; ++k) {
              const double delta = positions[dim * i + k] - positions[dim * j + k];
              squared += delta * delta;
            }
            if (squared >= radius * radius) continue;
            ++pairs.count;
            const double distance = std::sqrt(squared);
            if (pairs.closest && distance >= *pairs.closest) continue;
            pairs.closest = distance;
            pairs.where.assign(dim, 0.0);
            for (std::size_t k = 0; k < dim; ++k)
              pairs.where[k] = 0.5 * (positions[dim * i + k] + positions[dim * j + k]);
          }
        }
      }
    }
  }
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
