#pragma once
// What an evaluation of the wall contact takes and gives, the same for 2D segments
// (wall_contact.hpp) and 3D triangles (wall_contact_3d.hpp): the particles of this process in
// LAMMPS' layout (3 doubles per particle, contiguous, also in 2D), the refusal of a non-finite
// particle, and the diagnostics of one evaluation.
//
// Pure C++ over plain arrays: no LIGGGHTS or MPI types.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "fsi/contact/cell_grid.hpp"

namespace fsi::contact {

// Thrown, in 2D and 3D alike, when a participating particle has a non-finite position or
// velocity. Nothing has been written to any force array. index is the particle's index in
// ParticleArrays (the adapter turns it into the atom ID).
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

struct ContactDiagnostics {
  std::array<double, 3> force_on_particles{};   // sum over all pairs, on the fluid
  std::array<double, 3> force_on_structure{};   // sum over all vertex forces
  double pair_force_magnitude_sum = 0.0;        // sum of |pair force|: scale for balance checks
  std::size_t particles_in_range = 0;           // distinct particles within the cut-off
  std::size_t pair_count = 0;                   // (particle, sampling point) pairs within range
  std::size_t candidate_pairs = 0;              // pairs examined (cell-list or all-pairs)
  std::size_t sampling_points = 0;              // sampling points of this evaluation
  std::size_t sampling_points_skipped = 0;      // of which never generated: their (sub-)element
                                                // lies beyond the range of every particle of
                                                // this process (the rank's share of the boundary
                                                // is sampling_points - sampling_points_skipped)
  double closest_distance = 0.0;                // smallest particle–element distance in range;
                                                // +inf when no particle is in range
  void merge(const ContactDiagnostics& other);  // sum/min of two partial results
};

// The force of the fluid on the wall at every sampling point of one evaluation, in the sampling's
// order (element by element), for the wall-pressure probes (fsi::probes): an evaluation fills it
// only when `enabled`, since it costs a few stores per sampling point. Every process holds every
// sampling point, with the forces of the particles it owns (sums over the processes give the
// total). `dimension` values per sample in positions, normals and forces.
struct WallSampleRecord {
  bool enabled = false;
  int dimension = 2;
  std::vector<double> positions;        // [m]
  std::vector<double> normals;          // unit normal of the sample's element (2D: the segment's
                                        // direction turned clockwise; 3D: the right-hand rule)
  std::vector<double> forces;           // force of the particles on the wall [N; 2D N/m]
  std::vector<double> measures;         // length (2D) or area (3D) the sample stands for
  std::vector<std::uint32_t> elements;  // the sample's element in the mesh
  std::vector<std::uint32_t> pairs;     // particles within the wall law's range of the sample
  std::size_t count() const { return measures.size(); }
  // Empties the arrays and keeps their capacity.
  void clear();
};

// Marks (near[i] = 1) the particles of the group that lie within `range` of the bounding box of
// the mesh vertices (`dimension` coordinates per vertex in vertex_positions): only they can
// interact with the mesh, so only they enter the cell grid. Far-away particles (a large fluid
// domain around a small structure, a stray particle) then cost one comparison each.
void mark_particles_near_mesh(const ParticleArrays& particles,
                              std::span<const double> vertex_positions, int dimension, double range,
                              std::vector<std::uint8_t>& near);

// What an evaluation with a cell grid keeps between calls, so that a step allocates nothing.
template <int Dimension>
struct NeighbourSearchBuffers {
  std::vector<std::uint8_t> near;  // particles that can reach the mesh (grid members)
  CellGrid<Dimension> grid;
  // Per particle: the last element a pair was made with (kNoElement: none yet, so the particle
  // is not yet counted in particles_in_range).
  std::vector<std::uint32_t> last_element;
};

}  // namespace fsi::contact
