#include "decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace fsi::client {

ProcessorGrid choose_processor_grid(int ranks, int dimension, const std::array<double, 3>& extent) {
  if (ranks < 1) throw std::invalid_argument("a processor grid needs at least one rank");
  if (dimension != 2 && dimension != 3) throw std::invalid_argument("a processor grid is 2D or 3D");
  // A fluid of no extent along an axis (one particle layer) still has one spacing there: take a
  // tiny positive length so that the costs stay ordered and finite.
  std::array<double, 3> length{};
  const double largest = std::max({extent[0], extent[1], dimension == 3 ? extent[2] : 0.0, 0.0});
  for (int k = 0; k < 3; ++k)
    length[k] = std::max(extent[k], largest > 0.0 ? 1e-9 * largest : 1.0);
  ProcessorGrid best{ranks, 1, 1};
  double best_cost = std::numeric_limits<double>::infinity();
  for (int px = ranks; px >= 1; --px) {
    if (ranks % px != 0) continue;
    const int rest = ranks / px;
    for (int py = rest; py >= 1; --py) {
      if (rest % py != 0) continue;
      const int pz = rest / py;
      if (dimension == 2 && pz != 1) continue;
      const double cost = dimension == 2 ? (px - 1) * length[1] + (py - 1) * length[0]
                                         : (px - 1) * length[1] * length[2] +
                                               (py - 1) * length[0] * length[2] +
                                               (pz - 1) * length[0] * length[1];
      // Strictly smaller (with a relative margin against round-off) replaces: ties keep the
      // earlier grid, the one with more ranks along x, then y.
      if (cost < best_cost * (1.0 - 1e-12)) {
        best_cost = cost;
        best = {px, py, pz};
      }
    }
  }
  return best;
}

std::array<double, 3> positions_extent(std::span<const double> positions, int dimension) {
  if (dimension != 2 && dimension != 3) throw std::invalid_argument("positions are 2D or 3D");
  const auto per_point = static_cast<std::size_t>(dimension);
  std::array<double, 3> extent{0.0, 0.0, 0.0};
  if (positions.size() < per_point) return extent;
  for (std::size_t k = 0; k < per_point; ++k) {
    double lo = positions[k];
    double hi = positions[k];
    for (std::size_t i = k; i < positions.size(); i += per_point) {
      lo = std::min(lo, positions[i]);
      hi = std::max(hi, positions[i]);
    }
    extent[k] = hi - lo;
  }
  return extent;
}

std::vector<double> balanced_cuts(const AxisHistogram& histogram, double box_lo, double box_hi,
                                  int parts, double min_width) {
  if (parts < 1) throw std::invalid_argument("cuts need at least one part");
  if (!(box_hi > box_lo)) throw std::invalid_argument("the box has no extent along the axis");
  const double box = box_hi - box_lo;
  if (parts == 1) return {0.0, 1.0};
  const std::size_t bins = histogram.counts.size();
  const double total = std::accumulate(histogram.counts.begin(), histogram.counts.end(), 0.0);
  std::vector<double> cuts(static_cast<std::size_t>(parts) + 1, 0.0);
  cuts.back() = 1.0;
  if (bins == 0 || !(total > 0.0) || !(histogram.hi > histogram.lo)) {
    // Nothing to balance (no particles, or all on one plane): LIGGGHTS' even cuts.
    return uniform_cuts(parts);
  }
  if (histogram.lo < box_lo - 1e-9 * box || histogram.hi > box_hi + 1e-9 * box)
    throw std::invalid_argument("the histogram reaches outside the box");
  const double bin_width = (histogram.hi - histogram.lo) / static_cast<double>(bins);
  const auto empty = [&](std::size_t b) { return histogram.counts[b] == 0.0; };
  // Walk the cumulative count once. Cut j goes to the bin edge nearest to where the count
  // reaches j/parts of the total, never through a bin, and into the middle of the empty bins
  // around that edge: a lattice plane of particles stays on one side, and particles jittering
  // about their plane do not cross the cut.
  double below = 0.0;  // particles in the bins before `bin`
  std::size_t bin = 0;
  for (int j = 1; j < parts; ++j) {
    const double target = total * static_cast<double>(j) / static_cast<double>(parts);
    while (bin < bins && below + histogram.counts[bin] < target)
      below += histogram.counts[bin++];
    std::size_t edge = bins;  // the cut's bin edge: between bins edge - 1 and edge
    if (bin < bins) edge = target - below <= below + histogram.counts[bin] - target ? bin : bin + 1;
    std::size_t gap_begin = edge;
    std::size_t gap_end = edge;
    while (gap_begin > 0 && empty(gap_begin - 1))
      --gap_begin;
    while (gap_end < bins && empty(gap_end))
      ++gap_end;
    // An empty run that reaches the histogram's end has no particles beyond it: keep the edge.
    const bool open_below = gap_begin == 0 && gap_begin < edge;
    const bool open_above = gap_end == bins && gap_end > edge;
    const double middle = open_below || open_above ? static_cast<double>(edge)
                                                   : 0.5 * static_cast<double>(gap_begin + gap_end);
    const double position = histogram.lo + middle * bin_width;
    cuts[static_cast<std::size_t>(j)] = (position - box_lo) / box;
  }
  // Every slab at least min_width (as a fraction; at most an even share of the box): first push
  // cuts up from the lower face, then down from the upper one.
  const double gap = std::min(std::max(min_width, 0.0) / box, 1.0 / static_cast<double>(parts));
  for (int j = 1; j < parts; ++j) {
    const auto i = static_cast<std::size_t>(j);
    cuts[i] = std::clamp(cuts[i], 0.0, 1.0);
    cuts[i] = std::max(cuts[i], cuts[i - 1] + gap);
  }
  for (int j = parts - 1; j >= 1; --j) {
    const auto i = static_cast<std::size_t>(j);
    cuts[i] = std::min(cuts[i], cuts[i + 1] - gap);
  }
  return cuts;
}

std::vector<double> uniform_cuts(int parts) {
  if (parts < 1) throw std::invalid_argument("cuts need at least one part");
  std::vector<double> cuts(static_cast<std::size_t>(parts) + 1);
  for (int j = 0; j <= parts; ++j)
    cuts[static_cast<std::size_t>(j)] = static_cast<double>(j) / static_cast<double>(parts);
  cuts.back() = 1.0;
  return cuts;
}

double imbalance(std::span<const std::uint64_t> counts) {
  if (counts.empty()) return 1.0;
  std::uint64_t total = 0;
  std::uint64_t largest = 0;
  for (const std::uint64_t count : counts) {
    total += count;
    largest = std::max(largest, count);
  }
  if (total == 0) return 1.0;
  return static_cast<double>(largest) * static_cast<double>(counts.size()) /
         static_cast<double>(total);
}

std::string grid_text(const ProcessorGrid& grid) {
  return std::to_string(grid[0]) + " x " + std::to_string(grid[1]) + " x " +
         std::to_string(grid[2]);
}

}  // namespace fsi::client
