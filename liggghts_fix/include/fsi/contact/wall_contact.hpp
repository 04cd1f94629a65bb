#pragma once
// The SPH–wall contact of thesis ch. 4 for 2D boundaries made of line segments (§4.3, §5.5.2):
// each segment is bisected until its pieces are shorter than the refinement resolution, each piece
// is sampled by Gauss–Legendre points, every sampling point interacts with the particles within the
// cut-off (found through a cell grid), and the counterforce of every pair is redistributed to the
// segment's two vertices by linear weighting (eq. 4.11/4.12, redistribution.hpp), which keeps
// forces and moments in balance exactly. Input checks, the pair kernel, the diagnostics and the
// redistribution are those of the triangle half (wall_contact_3d.hpp): one skeleton
// (src/contact_skeleton.hpp) over two samplings.
//
// Pure C++ over plain arrays: no LIGGGHTS or MPI types.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fsi/contact/cell_grid.hpp"
#include "fsi/contact/contact_evaluation.hpp"
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
  // Throws std::invalid_argument on inconsistent sizes, a segment referring to a missing vertex
  // (naming both) or a vertex with a non-finite position or velocity (naming it).
  void validate() const;
};

struct ContactSettings {
  ForceLaw law;
  int gauss_points = 3;                // per (sub-)segment, 1..5
  double refinement_resolution = 0.0;  // bisect until pieces are shorter than this [m]
  // Throws std::invalid_argument naming the bad setting.
  void validate() const;
};

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
  // first) and returns the diagnostics of this evaluation. Throws, before writing anything,
  // NonFiniteParticle for a particle with a non-finite position or velocity, and
  // std::invalid_argument for a bad mesh or a wrong buffer size. With an enabled `samples`, also
  // records the force at every sampling point (WallSampleRecord).
  ContactDiagnostics compute(const BoundaryMesh2D& mesh, const ParticleArrays& particles,
                             std::span<double> vertex_forces, WallSampleRecord* samples = nullptr);

 private:
  ContactSettings settings_;
  NeighbourSearchBuffers<2> buffers_;
};

// All-pairs reference of WallContact2D::compute (same sampling, no cell grid), for tests.
ContactDiagnostics compute_all_pairs(const ContactSettings& settings, const BoundaryMesh2D& mesh,
                                     const ParticleArrays& particles,
                                     std::span<double> vertex_forces,
                                     WallSampleRecord* samples = nullptr);

}  // namespace fsi::contact
