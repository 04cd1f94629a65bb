#pragma once
// Particles closer than a fraction of the lattice spacing. LIGGGHTS' Shepard density filter
// (`fix sph/density/corr shepard`) resets each density to a weighted mean of its neighbours',
// which does not rise when two particles close in on one site; the pressure then does not push
// them apart and the first layer along a wall bunches into such pairs, first at concave corners
// (docs/theory.md, "Particle pairs along the walls"). The server counts them in every snapshot.
// Pure.

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace fsi::coupling {

struct ParticlePairs {
  std::size_t count = 0;          // pairs closer than the radius asked for
  std::optional<double> closest;  // the distance of the closest of them [m]; none: no pair
  std::vector<double> where;      // its midpoint (dimension values)
};

// `positions` holds `dimension` (2 or 3) values per particle; a cell list of cells `radius`
// wide, so the cost is linear in the particles for any lattice-like fluid.
ParticlePairs particle_pairs_closer_than(std::span<const double> positions, int dimension,
                                         double radius);

// The distance from particle `index` to its nearest other particle [m]; none when it is alone.
std::optional<double> nearest_particle_distance(std::span<const double> positions, int dimension,
                                                std::size_t index);

}  // namespace fsi::coupling
