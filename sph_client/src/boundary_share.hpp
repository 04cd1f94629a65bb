#pragma once
// A rank's share of the boundary mesh (thesis §7.1, "a distributed-memory treatment of the
// surfaces instead of identical copies on every process"; docs/user-guide.md, "Ranks and
// balance"). Rank 0 holds the whole mesh, as the server sends it; every rank evaluates the wall
// law on its share only: the elements that can come within the wall law's range of a particle
// the rank may own before the next selection. Pure arithmetic over plain arrays, no MPI, no
// LIGGGHTS: boundary_distribution.hpp moves the shares between the ranks.
//
// The guarantee. A rank covers the box C: its sub-domain and the bounding box of its particles
// at the selection, widened by the margin m. An element belongs to its share when its bounding
// box at the selection, widened by the wall's range plus m, meets C or a periodic image of C.
// As long as (a) every particle of the rank stays in C and (b) no vertex moves more than m from
// where it was at the selection, every element within the range of one of the rank's particles
// (or of a periodic image of one) is in its share: the rank's pairs, and so its forces, are those
// it would find on the whole mesh. The client selects again when a particle leaves C shrunk by
// m / 2 or a vertex has moved m / 2, and fix fsi/sph stops with an error if (a) is ever broken.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace fsi::client {

// An axis-aligned box; empty until something is included. In 2D the third axis is unused (the
// functions below take the dimension).
struct ShareBox {
  std::array<double, 3> low{kEmptyLow, kEmptyLow, kEmptyLow};
  std::array<double, 3> high{kEmptyHigh, kEmptyHigh, kEmptyHigh};

  static constexpr double kEmptyLow = 1e300;
  static constexpr double kEmptyHigh = -1e300;

  bool empty(int dimension) const;
  void include(std::span<const double> point, int dimension);
  void include(const ShareBox& other, int dimension);
  // Grown by `margin` on every side (an empty box stays empty).
  ShareBox widened(double margin, int dimension) const;
  bool contains(std::span<const double> point, int dimension) const;
  bool meets(const ShareBox& other, int dimension) const;
};

// The bounding box of `positions` (`dimension` values per point).
ShareBox bounding_box(std::span<const double> positions, int dimension);

// The periodic axes of the simulation box and their periods (LIGGGHTS `boundary p ...`).
struct SharePeriodicity {
  std::array<bool, 3> periodic{};
  std::array<double, 3> period{};
};

// The whole mesh as rank 0 holds it: `dimension` values per vertex, `dimension` vertices per
// element (segments in 2D, triangles in 3D), the dynamic vertices first.
struct WholeMesh {
  int dimension = 2;
  std::span<const double> positions;
  std::span<const std::uint32_t> elements;
  std::size_t dynamic_vertex_count = 0;
};

// Which elements and vertices of the whole mesh a rank holds, in the whole mesh's order (the
// rank's evaluation visits its elements in the same order as an evaluation of the whole mesh).
struct BoundaryShare {
  std::vector<std::uint32_t> elements;  // indices into the whole mesh's elements, ascending
  std::vector<std::uint32_t> vertices;  // the vertices they use, ascending
  std::size_t dynamic_vertices = 0;     // how many of `vertices` are dynamic (they come first)
};

// The elements whose bounding box, widened by `reach` (the wall's range plus the margin), meets
// `covered` or one of its images shifted by -1, 0 or +1 period along each periodic axis. An empty
// `covered` selects nothing. Throws std::invalid_argument for a dimension other than 2 or 3, an
// element naming a vertex the mesh lacks, or a negative reach.
BoundaryShare select_share(const WholeMesh& mesh, const ShareBox& covered, double reach,
                           const SharePeriodicity& periodicity);

// Every element: the share of a rank that must see the whole mesh.
BoundaryShare whole_share(const WholeMesh& mesh);

// A share's own mesh: its vertices' values and its elements renumbered to them.
struct LocalMesh {
  std::vector<double> positions;
  std::vector<double> velocities;
  std::vector<std::uint32_t> elements;
};
LocalMesh local_mesh(const WholeMesh& mesh, std::span<const double> velocities,
                     const BoundaryShare& share);

// The values of the first `count` of `vertices` taken from whole-mesh arrays (`dimension` per
// vertex), and the reverse: a share's values added into whole-mesh arrays.
std::vector<double> share_values(std::span<const double> whole,
                                 std::span<const std::uint32_t> vertices, std::size_t count,
                                 int dimension);
void add_share_values(std::span<const double> share, std::span<const std::uint32_t> vertices,
                      std::size_t count, int dimension, std::span<double> whole);

// The largest distance between corresponding points of `a` and `b` (equal sizes).
double largest_displacement(std::span<const double> a, std::span<const double> b, int dimension);

}  // namespace fsi::client
