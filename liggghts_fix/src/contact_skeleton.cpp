#include "contact_skeleton.hpp"

#include <cstdio>
#include <stdexcept>

namespace fsi::contact {
namespace skeleton {
namespace {

std::string coordinates(const double* x, int dimension) {
  char text[96];
  if (dimension == 2) {
    std::snprintf(text, sizeof text, "(%.6g, %.6g)", x[0], x[1]);
  } else {
    std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", x[0], x[1], x[2]);
  }
  return text;
}

const char* count_word(int count) {
  return count == 2 ? "two" : "three";
}

void check_particles(const ParticleArrays& particles) {
  if (particles.count > 0 && (!particles.positions || !particles.velocities || !particles.forces)) {
    throw std::invalid_argument("particle arrays are missing positions, velocities or forces");
  }
  if (!particles.group_mask.empty() && particles.group_mask.size() < particles.count) {
    throw std::invalid_argument("group mask is shorter than the particle count");
  }
  if (particles.count > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("more than 2^32 particles on one process");
  }
  // A non-finite particle would poison the cell grid and the force array: refuse it before any
  // force is written. All three components, also in 2D: LIGGGHTS integrates z there too.
  for (std::size_t i = 0; i < particles.count; ++i) {
    if (!takes_part(particles, i)) continue;
    const double* x = particles.positions + 3 * i;
    const double* u = particles.velocities + 3 * i;
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(x[k]) || !std::isfinite(u[k])) {
        throw NonFiniteParticle(
            i, "particle " + std::to_string(i) + " (local index) has a non-finite position " +
                   coordinates(x, 3) + " or velocity " + coordinates(u, 3) +
                   ": the fluid has blown up; reduce the time step or raise the wall repulsion k");
      }
    }
  }
}

}  // namespace

void validate_mesh(const MeshShape& shape, std::span<const double> positions,
                   std::span<const double> velocities, std::span<const std::uint32_t> elements) {
  const auto dimension = static_cast<std::size_t>(shape.dimension);
  const auto corners = static_cast<std::size_t>(shape.corners);
  if (positions.size() % dimension != 0 || velocities.size() != positions.size()) {
    throw std::invalid_argument(
        std::to_string(dimension) + "D boundary mesh needs " + (dimension == 2 ? "x,y" : "x,y,z") +
        " per vertex for positions and velocities (" + std::to_string(positions.size()) +
        " position and " + std::to_string(velocities.size()) + " velocity values)");
  }
  if (elements.size() % corners != 0) {
    throw std::invalid_argument(std::to_string(dimension) + "D boundary " + shape.element_name +
                                "s need " + count_word(shape.corners) + " vertex indices each (" +
                                std::to_string(elements.size()) + " indices given)");
  }
  const std::size_t vertex_count = positions.size() / dimension;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    if (elements[k] >= vertex_count) {
      throw std::invalid_argument(std::string(shape.element_name) + " " +
                                  std::to_string(k / corners) + " refers to vertex " +
                                  std::to_string(elements[k]) + " but the mesh has " +
                                  std::to_string(vertex_count) + " vertices (0 to " +
                                  std::to_string(vertex_count) + " - 1)");
    }
  }
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (!std::isfinite(positions[k]) || !std::isfinite(velocities[k])) {
      const std::size_t first = k - k % dimension;
      throw std::invalid_argument(
          "vertex " + std::to_string(k / dimension) + " has a non-finite position " +
          coordinates(&positions[first], shape.dimension) + " or velocity " +
          coordinates(&velocities[first], shape.dimension));
    }
  }
}

void check_evaluation_inputs(const MeshShape& shape, const ParticleArrays& particles,
                             std::span<const double> vertex_positions,
                             std::span<const double> vertex_velocities,
                             std::span<const std::uint32_t> elements,
                             std::span<const double> vertex_forces) {
  check_particles(particles);
  if (vertex_forces.size() != vertex_positions.size()) {
    throw std::invalid_argument("vertex force buffer holds " +
                                std::to_string(vertex_forces.size()) + " values, the mesh needs " +
                                std::to_string(vertex_positions.size()) + " (" +
                                std::to_string(shape.dimension) + " per vertex)");
  }
  validate_mesh(shape, vertex_positions, vertex_velocities, elements);
}

}  // namespace skeleton

void WallSampleRecord::clear() {
  positions.clear();
  normals.clear();
  forces.clear();
  measures.clear();
  elements.clear();
  pairs.clear();
}

void ContactDiagnostics::merge(const ContactDiagnostics& other) {
  for (int k = 0; k < 3; ++k) {
    force_on_particles[k] += other.force_on_particles[k];
    force_on_structure[k] += other.force_on_structure[k];
  }
  pair_force_magnitude_sum += other.pair_force_magnitude_sum;
  particles_in_range += other.particles_in_range;
  pair_count += other.pair_count;
  candidate_pairs += other.candidate_pairs;
  sampling_points += other.sampling_points;
  sampling_points_skipped += other.sampling_points_skipped;
  closest_distance = std::min(closest_distance, other.closest_distance);
}

void mark_particles_near_mesh(const ParticleArrays& particles,
                              std::span<const double> vertex_positions, int dimension, double range,
                              std::vector<std::uint8_t>& near) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  near.assign(particles.count, 0);
  if (vertex_positions.empty()) return;
  double low[3] = {kInfinity, kInfinity, kInfinity};
  double high[3] = {-kInfinity, -kInfinity, -kInfinity};
  for (std::size_t v = 0; v < vertex_positions.size(); v += static_cast<std::size_t>(dimension)) {
    for (int k = 0; k < dimension; ++k) {
      low[k] = std::min(low[k], vertex_positions[v + k]);
      high[k] = std::max(high[k], vertex_positions[v + k]);
    }
  }
  // A relative margin so that a particle exactly at the range is not lost to round-off.
  const double reach = range * (1.0 + skeleton::kSearchMargin);
  for (std::size_t i = 0; i < particles.count; ++i) {
    if (!skeleton::takes_part(particles, i)) continue;
    bool inside = true;
    for (int k = 0; k < dimension && inside; ++k) {
      const double x = particles.positions[3 * i + k];
      inside = x >= low[k] - reach && x <= high[k] + reach;
    }
    near[i] = inside ? 1 : 0;
  }
}

}  // namespace fsi::contact
