#pragma once
// The balanced domain decomposition of the fluid (docs/user-guide.md, "Ranks and balance"): which
// processor grid the ranks form and where the cuts between their sub-domains lie. LIGGGHTS 3.8
// has no `balance` command (ARCHITECTURE.md §13); fsi-client sets LIGGGHTS' fractional cuts
// (Comm::xsplit/ysplit/zsplit) itself from these functions. Pure arithmetic, no LIGGGHTS, no MPI:
// the driver builds the histograms (reduced over the ranks) and applies the result.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace fsi::client {

// Ranks along x, y and z.
using ProcessorGrid = std::array<int, 3>;

// The grid of `ranks` ranks for a fluid whose particles span `extent` (lengths along x, y, z; z is
// ignored in 2D, where the grid has one layer): the factorisation px py pz = ranks whose cuts
// through the fluid's bounding box are shortest in total, (px - 1) Ly + (py - 1) Lx in 2D and
// (px - 1) Ly Lz + (py - 1) Lx Lz + (pz - 1) Lx Ly in 3D: the ghost layers the ranks exchange.
// Ties go to the grid with more ranks along the earlier axis. Throws std::invalid_argument for
// ranks < 1 or a dimension other than 2 or 3.
ProcessorGrid choose_processor_grid(int ranks, int dimension, const std::array<double, 3>& extent);

// The lengths of the bounding box of `positions` (`dimension` values per point) along x, y, z;
// 0 along an axis the dimension lacks and for no points. Throws std::invalid_argument for a
// dimension other than 2 or 3.
std::array<double, 3> positions_extent(std::span<const double> positions, int dimension);

// Counts of particle coordinates along one axis in equal bins over [lo, hi].
struct AxisHistogram {
  double lo = 0.0;
  double hi = 0.0;
  std::vector<double> counts;
};

// The fractional cuts (LIGGGHTS' xsplit: 0 at the box's lower face, 1 at its upper one; parts + 1
// values) that split the particles of `histogram` into `parts` slabs of equal count along an axis
// whose box is [box_lo, box_hi], as nearly as whole bins allow: a cut never splits a bin, and it
// lies in the middle of the empty bins around it (between two lattice planes of particles, not on
// one). The outer slabs reach the box's faces; every slab is at least `min_width` wide (a length;
// clamped to what the box allows) so that no rank is left without a sub-domain. Throws
// std::invalid_argument for parts < 1, an empty box or a histogram outside it.
std::vector<double> balanced_cuts(const AxisHistogram& histogram, double box_lo, double box_hi,
                                  int parts, double min_width);

// Evenly spaced cuts (LIGGGHTS' default decomposition): parts + 1 values from 0 to 1.
std::vector<double> uniform_cuts(int parts);

// The largest count over the mean: 1 for a perfect balance, `ranks` when one rank holds all.
// 1 for no particles at all.
double imbalance(std::span<const std::uint64_t> counts);

// "2 x 1 x 1".
std::string grid_text(const ProcessorGrid& grid);

}  // namespace fsi::client
