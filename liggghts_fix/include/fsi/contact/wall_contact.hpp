#pragma once
// The SPH–wall contact of thesis ch. 4 for 2D boundaries made of line segments (§4.3, §5.5.2):
// each segment is bisected until its pieces are shorter than the refinement resolution, each piece
// is sampled by Gauss–Legendre points, every sampling point interacts with the particles within the
// cut-off (found through a cell grid), and the counterforce of every pair is redistributed to the
// segment's two vertices by linear weighting (eq. 4.11/4.12), which keeps forces and moments in
// balance exactly.
//
// Pure C++ over plain arrays: no LIGGGHTS or MPI types. Particle arrays use LAMMPS' layout
// (3 doubles per particle, contiguous).

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "fsi/contact/cell_grid.hpp"
#include "fsi/contact/force_law.hpp"

namespace fsi::contact {

// A 2D boundary: vertex positions and velocities (x, y per vertex) and segments (two vertex
// indices each). The orientation of a segment does not matter (thesis §4.4).
struct BoundaryMesh2D {
  std::vector<double> positions;
  std::vector<double> velocities;
  std::vector<std::uint32_t> segments;

  std::size_t vertex_count() const { return positions.size() / 2; }
  std::size_t segment_count() const { return segments.size() / 2; }
  // Throws std::invalid_argument on inconsistent sizes, bad indices or non-finite coordinates.
  void validate() const;
};

// Thrown when a participating particle has a non-finite position or velocity. Nothing has been
// written to any force array. index is the particle's index in ParticleArrays.
struct NonFiniteParticle : std::invalid_argument {
  NonFiniteParticle(std::size_t particle, const std::string& message)
      : std::invalid_argument(message), index(particle) {}
  std::size_t index;
};

// Particles owned by this process. forces is accumulated into (+=). A particle takes part if
// group_mask is empty or (group_mask[i] & group_bit) != 0.
struct ParticleArrays {
  std::size_t count = 0;
  const double* positions = nullptr;   // 3 per particle
  const double* velocities = nullptr;  // 3 per particle
  double* forces = nullptr;            // 3 per particle
  std::span<const int> group_mask;
  int group_bit = 0;
};

struct ContactSettings {
  ForceLaw law;
  int gauss_points = 3;                // per (sub-)segment, 1..5
  double refinement_resolution = 0.0;  // bisect until pieces are shorter than this [m]
  // Throws std::invalid_argument naming the bad setting.
  void validate() const;
};

struct ContactDiagnostics {
  std::array<double, 3> force_on_particles{};   // sum over all pairs, on the fluid
  std::array<double, 3> force_on_structure{};   // sum over all vertex forces
  double pair_force_magnitude_sum = 0.0;        // sum of |pair force|: scale for balance checks
  std::size_t particles_in_range = 0;           // distinct particles within the cut-off
  std::size_t pair_count = 0;                   // (particle, sampling point) pairs within range
  std::size_t candidate_pairs = 0;              // pairs examined (cell-list candidates)
  std::size_t sampling_points = 0;              // sampling points of this evaluation
  double closest_distance = 0.0;                // smallest particle–segment distance in range;
                                                // +inf when no particle is in range
  void merge(const ContactDiagnostics& other);  // sum/min of two partial results
};

// Marks (near[i] = 1) the particles of the group that lie within `range` of the bounding box of
// the mesh vertices (`dimension` coordinates per vertex in vertex_positions): only they can
// interact with the mesh, so only they enter the cell grid. Far-away particles (a large fluid
// domain around a small structure, a stray particle) then cost one comparison each.
void mark_particles_near_mesh(const ParticleArrays& particles,
                              std::span<const double> vertex_positions, int dimension, double range,
                              std::vector<std::uint8_t>& near);

// Number of bisection levels so that a segment of the given length is cut into pieces shorter
// than the resolution: smallest k with length / 2^k < resolution.
int bisection_levels(double length, double resolution);

// Evaluates the contact forces with a cell grid over the particles. Reuses its buffers between
// calls; not thread-safe.
class WallContact2D {
 public:
  explicit WallContact2D(const ContactSettings& settings);

  const ContactSettings& settings() const { return settings_; }

  // Adds the contact forces to particles.forces, writes the vertex forces (2 per vertex, zeroed
  // first) and returns the diagnostics of this evaluation.
  ContactDiagnostics compute(const BoundaryMesh2D& mesh, const ParticleArrays& particles,
                             std::span<double> vertex_forces);

 private:
  ContactSettings settings_;
  std::vector<std::uint8_t> near_;  // particles that can reach the mesh (grid members)
  CellGrid<2> grid_;
  std::vector<std::uint8_t> in_range_;
};

// All-pairs reference of WallContact2D::compute (same sampling, no cell grid), for tests.
ContactDiagnostics compute_all_pairs(const ContactSettings& settings, const BoundaryMesh2D& mesh,
                                     const ParticleArrays& particles,
                                     std::span<double> vertex_forces);

}  // namespace fsi::contact
