#pragma once
// The SPH–wall contact of thesis ch. 4 for 3D boundaries made of triangles (§4.3, remark at its
// end; §5.5.2; Table 5.1): each triangle is split into sub-triangles, each sub-triangle is sampled
// by a symmetric triangle rule, every sampling point interacts with the particles within the
// range of the force law (found through a cell grid), and the counterforce of every pair is
// redistributed to the triangle's three vertices by the sampling point's barycentric coordinates
// with respect to the original triangle — the 3D analogue of eq. (4.11/4.12), redistribution.hpp,
// which keeps forces and moments in balance exactly. Input checks, the pair kernel, the
// diagnostics and the redistribution are those of the segment half (wall_contact.hpp): one
// skeleton (src/contact_skeleton.hpp) over two samplings.
//
// Refinement. A triangle is split into four by its edge midpoints. All four children are similar
// to the parent with half its edge lengths, so recursive splitting "until every edge of every
// sub-triangle is shorter than the refinement resolution" is uniform: a triangle whose longest
// edge is L is split to level k, the smallest k with L / 2^k < resolution (4^k sub-triangles).
// The sub-triangles are kept as barycentric triangles of the original element, so they follow the
// element when it moves and deforms. Options (thesis Table 5.1):
//   0  no refinement: one sub-triangle per element
//   1  recursive refinement of the current geometry at every evaluation
//   2  pre-refined once (first evaluation or prepare()) from the geometry then; the sub-triangles
//      follow the mesh and their number never changes
//   3  pre-refined as option 2, then at every evaluation each stored sub-triangle is refined
//      further wherever its edges in the current geometry are not shorter than the resolution
//
// Pure C++ over plain arrays: no LIGGGHTS or MPI types. Particles and diagnostics as in 2D
// (contact_evaluation.hpp).

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fsi/contact/cell_grid.hpp"
#include "fsi/contact/contact_evaluation.hpp"
#include "fsi/contact/force_law.hpp"

namespace fsi::contact {

// A 3D boundary: vertex positions and velocities (x, y, z per vertex) and triangles (three vertex
// indices each). The orientation of a triangle does not matter. A triangle of zero area (repeated
// vertex or collinear vertices) is allowed and contributes nothing.
struct BoundaryMesh3D {
  std::vector<double> positions;
  std::vector<double> velocities;
  std::vector<std::uint32_t> triangles;

  std::size_t vertex_count() const { return positions.size() / 3; }
  std::size_t triangle_count() const { return triangles.size() / 3; }
  // Throws std::invalid_argument on inconsistent sizes, a triangle referring to a missing vertex
  // (naming both) or a vertex with a non-finite position or velocity (naming it).
  void validate() const;
};

inline constexpr int kMinRefinementOption = 0;
inline constexpr int kMaxRefinementOption = 3;
// Refinement beyond this level (4^10 ~ 10^6 sub-triangles per element) is refused: it means the
// resolution is far too small for the mesh.
inline constexpr int kMaxRefinementLevel = 10;

struct ContactSettings3D {
  ForceLaw law;
  int quadrature_points = 7;           // per (sub-)triangle: 1, 3 or 7
  int refinement_option = 1;           // 0..3, see above
  double refinement_resolution = 0.0;  // split until all sub-triangle edges are shorter [m]
  // Throws std::invalid_argument naming the bad setting and its admissible values.
  void validate() const;
};

// Refinement level of a triangle with this longest edge: smallest k with edge / 2^k < resolution.
// Throws std::invalid_argument if k would exceed kMaxRefinementLevel (the message names the
// triangle index given here and says how to fix it).
int triangle_refinement_level(double longest_edge, double resolution, std::size_t triangle);

// The geometry of the cell grid (thesis §5.5.2): cells[k] cells of width cell_size[k] from
// origin[k] along axis k. Every cell is at least ForceLaw::range() wide.
using CellGrid3D = GridGeometry<3>;

// Evaluates the contact forces with a cell grid over the particles. Keeps the pre-refinement of
// options 2 and 3 and reuses its buffers between calls; not thread-safe.
class WallContact3D {
 public:
  explicit WallContact3D(const ContactSettings3D& settings);

  const ContactSettings3D& settings() const { return settings_; }

  // Options 2 and 3: fixes the pre-refinement of every triangle from this geometry (done by the
  // first compute() otherwise; calling it again re-does it). No effect for options 0 and 1.
  void prepare(const BoundaryMesh3D& mesh);
  // Options 2 and 3: the levels fixed elsewhere, one per triangle of the meshes compute() gets
  // next (a rank's share of a mesh pre-refined whole, pre_refinement_levels()). No effect for
  // options 0 and 1.
  void prepare(std::vector<std::uint8_t> levels);

  // Adds the contact forces to particles.forces, writes the vertex forces (3 per vertex, zeroed
  // first) and returns the diagnostics of this evaluation. Throws, before writing anything,
  // NonFiniteParticle for a particle with a non-finite position or velocity (naming it), and
  // std::invalid_argument for a bad mesh, a wrong buffer size, or a mesh whose triangle count
  // differs from the prepared one. With an enabled `samples`, also records the force at every
  // sampling point (WallSampleRecord).
  ContactDiagnostics compute(const BoundaryMesh3D& mesh, const ParticleArrays& particles,
                             std::span<double> vertex_forces, WallSampleRecord* samples = nullptr);

  // The grid of the latest compute(), for tests and diagnostics.
  const CellGrid3D& grid() const { return buffers_.grid.geometry(); }

 private:
  ContactSettings3D settings_;
  std::vector<std::uint8_t> pre_refinement_;  // level per triangle (options 2, 3)
  bool prepared_ = false;
  std::vector<std::uint8_t> levels_;  // refinement level per triangle of the latest compute()
  NeighbourSearchBuffers<3> buffers_;
};

// The pre-refinement level of every triangle of `mesh` (options 2 and 3) as prepare() fixes it
// from this geometry; zeros for options 0 and 1. Throws std::invalid_argument like compute() for
// a triangle that would need too many levels.
std::vector<std::uint8_t> pre_refinement_levels(const ContactSettings3D& settings,
                                                const BoundaryMesh3D& mesh);

// All-pairs reference of WallContact3D::compute (same sampling, no cell grid), for tests. For
// options 2 and 3 it pre-refines from this mesh, like the first evaluation of a WallContact3D.
ContactDiagnostics compute_all_pairs_3d(const ContactSettings3D& settings,
                                        const BoundaryMesh3D& mesh, const ParticleArrays& particles,
                                        std::span<double> vertex_forces,
                                        WallSampleRecord* samples = nullptr);

}  // namespace fsi::contact
