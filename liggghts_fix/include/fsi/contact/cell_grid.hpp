#pragma once
// The regular cell grid of thesis §5.5.2 ("cell method", "cell-linked lists") in D = 2 or 3
// dimensions: the member particles are hashed into cells at least one interaction range wide, so
// the partners of a sampling point lie in the at most 3^D cells overlapping the box of half-width
// `range` around it. Compressed-row storage: the particles of cell c are
// members()[start(c) .. start(c + 1)).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace fsi::contact {

template <int D>
struct GridGeometry {
  std::array<double, D> origin{};
  std::array<double, D> cell_size{};
  std::array<int, D> cells{};  // 0 cells: no member particle
};

template <int D>
class CellGrid {
  static_assert(D == 2 || D == 3);

 public:
  // Hashes the particles i with member[i] != 0 (positions: 3 doubles per particle, LAMMPS
  // layout; only the first D are used) into cells at least `range` wide. A far-away member must
  // not blow up memory: the cell count is capped (4 per member, at least 4096) by coarsening.
  void build(const double* positions, std::span<const std::uint8_t> member, double range) {
    build(positions, 3, member, range);
  }

  // The same for `stride` doubles per particle (at least D; D for packed points).
  void build(const double* positions, std::size_t stride, std::span<const std::uint8_t> member,
             double range) {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    std::array<double, D> low, high;
    low.fill(kInfinity);
    high.fill(-kInfinity);
    std::size_t members = 0;
    for (std::size_t i = 0; i < member.size(); ++i) {
      if (!member[i]) continue;
      ++members;
      for (int k = 0; k < D; ++k) {
        low[k] = std::min(low[k], positions[stride * i + k]);
        high[k] = std::max(high[k], positions[stride * i + k]);
      }
    }
    geometry_ = GridGeometry<D>{};
    low_ = low;
    high_ = high;
    if (members == 0) {
      start_.assign(1, 0);
      members_.clear();
      return;
    }
    const double max_cells = std::max(4096.0, 4.0 * static_cast<double>(members));
    std::array<double, D> counts;
    for (int k = 0; k < D; ++k)
      counts[k] = std::max(1.0, std::floor((high[k] - low[k]) / range));
    auto product = [&] {
      double p = 1.0;
      for (double c : counts)
        p *= c;
      return p;
    };
    while (product() > max_cells) {
      const auto largest = std::max_element(counts.begin(), counts.end());
      *largest = std::max(1.0, std::floor(*largest / 2.0));
    }
    std::size_t cell_count = 1;
    for (int k = 0; k < D; ++k) {
      geometry_.cells[k] = static_cast<int>(counts[k]);
      geometry_.origin[k] = low[k];
      geometry_.cell_size[k] = std::max(range, (high[k] - low[k]) / counts[k]);
      cell_count *= static_cast<std::size_t>(geometry_.cells[k]);
    }
    start_.assign(cell_count + 1, 0);
    cell_of_.resize(member.size());
    for (std::size_t i = 0; i < member.size(); ++i) {
      if (!member[i]) continue;
      const std::uint32_t cell = cell_of(positions + stride * i);
      cell_of_[i] = cell;
      ++start_[cell + 1];
    }
    for (std::size_t c = 0; c < cell_count; ++c)
      start_[c + 1] += start_[c];
    members_.resize(members);
    fill_.assign(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < member.size(); ++i) {
      if (member[i]) members_[fill_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
    }
  }

  const GridGeometry<D>& geometry() const { return geometry_; }

  // The bounding box of the member particles (low > high when there is none).
  const std::array<double, D>& members_low() const { return low_; }
  const std::array<double, D>& members_high() const { return high_; }

  // Calls visit(i) for every member particle in the cells overlapping the box
  // [point - reach, point + reach] (at most three cells per axis when reach <= the cell size)
  // and returns how many it visited.
  template <class Visit>
  std::size_t visit_near(const double* point, double reach, Visit&& visit) const {
    if (geometry_.cells[0] == 0) return 0;
    std::array<int, D> begin, end;
    for (int k = 0; k < D; ++k) {
      const double relative = point[k] - geometry_.origin[k];
      const double first = std::floor((relative - reach) / geometry_.cell_size[k]);
      const double last = std::floor((relative + reach) / geometry_.cell_size[k]);
      const double top = static_cast<double>(geometry_.cells[k] - 1);
      if (last < 0.0 || first > top) return 0;
      begin[k] = static_cast<int>(std::max(first, 0.0));
      end[k] = static_cast<int>(std::min(last, top));
    }
    std::size_t visited = 0;
    auto visit_row = [&](std::size_t row) {
      const std::size_t from = start_[row + static_cast<std::size_t>(begin[0])];
      const std::size_t to = start_[row + static_cast<std::size_t>(end[0]) + 1];
      visited += to - from;
      for (std::size_t m = from; m < to; ++m)
        visit(members_[m]);
    };
    const auto nx = static_cast<std::size_t>(geometry_.cells[0]);
    if constexpr (D == 2) {
      for (int cy = begin[1]; cy <= end[1]; ++cy)
        visit_row(static_cast<std::size_t>(cy) * nx);
    } else {
      const auto ny = static_cast<std::size_t>(geometry_.cells[1]);
      for (int cz = begin[2]; cz <= end[2]; ++cz)
        for (int cy = begin[1]; cy <= end[1]; ++cy)
          visit_row((static_cast<std::size_t>(cz) * ny + static_cast<std::size_t>(cy)) * nx);
    }
    return visited;
  }

 private:
  std::uint32_t cell_of(const double* x) const {
    std::size_t cell = 0;
    for (int k = D - 1; k >= 0; --k) {
      const double offset = (x[k] - geometry_.origin[k]) / geometry_.cell_size[k];
      const int index = std::clamp(static_cast<int>(offset), 0, geometry_.cells[k] - 1);
      cell = cell * static_cast<std::size_t>(geometry_.cells[k]) + static_cast<std::size_t>(index);
    }
    return static_cast<std::uint32_t>(cell);
  }

  GridGeometry<D> geometry_;
  std::array<double, D> low_{};
  std::array<double, D> high_{};
  std::vector<std::uint32_t> start_{0};
  std::vector<std::uint32_t> members_;
  std::vector<std::uint32_t> cell_of_;
  std::vector<std::uint32_t> fill_;
};

// Calls visit(i, j, squared distance) for every point i of `points` and every point j of
// `others` (both `dimension` = 2 or 3 packed values per point) closer than `radius` (> 0), the
// points in order and each one's partners in the grid's order: a cell grid over `others`, so the
// cost is linear in the points for any lattice-like set. For the pairs within one set pass it
// twice and keep j > i.
template <class Visit>
void for_each_close_pair(std::span<const double> points, std::span<const double> others,
                         int dimension, double radius, Visit&& visit) {
  const auto run = [&]<int D>() {
    CellGrid<D> grid;
    const std::vector<std::uint8_t> all(others.size() / D, 1);
    grid.build(others.data(), D, all, radius);
    for (std::size_t i = 0; i < points.size() / D; ++i) {
      const double* x = points.data() + D * i;
      grid.visit_near(x, radius, [&](std::uint32_t j) {
        double squared = 0.0;
        for (int k = 0; k < D; ++k) {
          const double delta = x[k] - others[D * j + k];
          squared += delta * delta;
        }
        if (squared < radius * radius) visit(i, std::size_t{j}, squared);
      });
    }
  };
  if (dimension == 2)
    run.template operator()<2>();
  else
    run.template operator()<3>();
}

}  // namespace fsi::contact
