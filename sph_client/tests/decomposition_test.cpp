// The balanced decomposition's arithmetic (decomposition.hpp; docs/user-guide.md "Ranks and
// balance").
#include "decomposition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace fsi::client {
namespace {

TEST(ProcessorGrid, FollowsTheFluidsExtentNotTheBox) {
  // A shallow layer 1 m wide and 0.2 m deep: two ranks cut it once across (0.2 m of ghosts), not
  // along (1 m).
  EXPECT_EQ(choose_processor_grid(2, 2, {1.0, 0.2, 0.0}), (ProcessorGrid{2, 1, 1}));
  // A column 0.057 m wide and 0.114 m high: cut once horizontally.
  EXPECT_EQ(choose_processor_grid(2, 2, {0.057, 0.114, 0.0}), (ProcessorGrid{1, 2, 1}));
  // Four ranks on a square: 2 x 2 (cuts 2 L) beats 4 x 1 (3 L).
  EXPECT_EQ(choose_processor_grid(4, 2, {1.0, 1.0, 0.0}), (ProcessorGrid{2, 2, 1}));
  // Four ranks on a strip 10 times longer than deep: 4 x 1 (cuts 3 x 0.1) beats 2 x 2 (0.1 + 1).
  EXPECT_EQ(choose_processor_grid(4, 2, {1.0, 0.1, 0.0}), (ProcessorGrid{4, 1, 1}));
  // 2D never splits z, whatever z's extent.
  EXPECT_EQ(choose_processor_grid(3, 2, {0.1, 1.0, 50.0}), (ProcessorGrid{1, 3, 1}));
  // 3D: eight ranks on a cube form 2 x 2 x 2; on a flat slab they stay in its plane.
  EXPECT_EQ(choose_processor_grid(8, 3, {1.0, 1.0, 1.0}), (ProcessorGrid{2, 2, 2}));
  EXPECT_EQ(choose_processor_grid(4, 3, {1.0, 1.0, 0.05}), (ProcessorGrid{2, 2, 1}));
  // A prime count has one way to go: along the longest axis.
  EXPECT_EQ(choose_processor_grid(7, 3, {0.2, 3.0, 1.0}), (ProcessorGrid{1, 7, 1}));
  // Ties (a square, two ranks) go to x; one rank is 1 x 1 x 1.
  EXPECT_EQ(choose_processor_grid(2, 2, {1.0, 1.0, 0.0}), (ProcessorGrid{2, 1, 1}));
  EXPECT_EQ(choose_processor_grid(1, 3, {1.0, 2.0, 3.0}), (ProcessorGrid{1, 1, 1}));
  // A single line of particles (no extent across) is still cut along the line.
  EXPECT_EQ(choose_processor_grid(2, 2, {1.0, 0.0, 0.0}), (ProcessorGrid{2, 1, 1}));
}

TEST(ProcessorGrid, TheExtentOfPositions) {
  const std::vector<double> plane{0.0, 1.0, 2.0, -1.0, 0.5, 3.0};  // three 2D points
  EXPECT_EQ(positions_extent(plane, 2), (std::array<double, 3>{2.0, 4.0, 0.0}));
  const std::vector<double> space{1.0, 2.0, 3.0, 0.0, 5.0, 3.5};  // two 3D points
  EXPECT_EQ(positions_extent(space, 3), (std::array<double, 3>{1.0, 3.0, 0.5}));
  EXPECT_EQ(positions_extent({}, 3), (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_THROW(positions_extent(plane, 1), std::invalid_argument);
}

TEST(ProcessorGrid, RefusesNonsense) {
  EXPECT_THROW(choose_processor_grid(0, 2, {1.0, 1.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(choose_processor_grid(2, 1, {1.0, 1.0, 0.0}), std::invalid_argument);
}

TEST(BalancedCuts, SplitTheParticlesNotTheBox) {
  // The box spans 0..1 m; the water fills 0..0.25 m evenly (a column at the left of a dam-break
  // tank): two ranks cut it at 0.125 m, not at the box's middle where rank 1 would hold nothing.
  AxisHistogram column{0.0, 0.25, std::vector<double>(100, 10.0)};
  const std::vector<double> two = balanced_cuts(column, 0.0, 1.0, 2, 0.0);
  ASSERT_EQ(two.size(), 3u);
  EXPECT_DOUBLE_EQ(two[0], 0.0);
  EXPECT_NEAR(two[1], 0.125, 1e-12);
  EXPECT_DOUBLE_EQ(two[2], 1.0);
  // Four ranks: quarters of the water, the last slab reaching the box's upper face.
  const std::vector<double> four = balanced_cuts(column, 0.0, 1.0, 4, 0.0);
  EXPECT_NEAR(four[1], 0.0625, 1e-12);
  EXPECT_NEAR(four[2], 0.125, 1e-12);
  EXPECT_NEAR(four[3], 0.1875, 1e-12);
  // A box that does not start at 0: fractions of the box.
  AxisHistogram shifted{-1.0, -0.5, std::vector<double>(10, 1.0)};
  EXPECT_NEAR(balanced_cuts(shifted, -2.0, 0.0, 2, 0.0)[1], 0.625, 1e-12);  // x = -0.75
}

TEST(BalancedCuts, NeverSplitABinAndLieBetweenLatticePlanes) {
  // 30 particles in one bin [0.4, 0.6] and 10 in [0.8, 1.0]: half of 40 is reached inside the
  // first heap; its upper edge is nearer (30 : 10 rather than 0 : 40), and the cut lies in the
  // middle of the empty bin after it.
  AxisHistogram two_heaps{0.0, 1.0, {0, 0, 30, 0, 10}};
  EXPECT_NEAR(balanced_cuts(two_heaps, 0.0, 1.0, 2, 0.0)[1], 0.7, 1e-12);
  // A lattice: ten planes of 20 particles at x = (k + 1/2) d, binned finely. Two ranks cut
  // between planes 5 and 6 (x = 5 d), not on a plane, where a jitter of the plane's particles
  // would move 20 of them across the cut; five ranks cut at 2 d, 4 d, 6 d, 8 d.
  const double d = 0.0028575;
  AxisHistogram lattice{0.5 * d, 9.5 * d, std::vector<double>(4096, 0.0)};
  for (int k = 0; k < 10; ++k) {
    const double x = (k + 0.5) * d;
    const auto b = std::min<std::size_t>(
        4095, static_cast<std::size_t>((x - lattice.lo) / (9.0 * d) * 4096.0));
    lattice.counts[b] += 20.0;
  }
  const std::vector<double> two = balanced_cuts(lattice, 0.0, 10.0 * d, 2, 0.0);
  EXPECT_NEAR(two[1] * 10.0 * d, 5.0 * d, 0.01 * d);
  const std::vector<double> five = balanced_cuts(lattice, 0.0, 10.0 * d, 5, 0.0);
  for (int j = 1; j < 5; ++j)
    EXPECT_NEAR(five[j] * 10.0 * d, 2.0 * j * d, 0.01 * d) << j;
}

TEST(BalancedCuts, KeepEverySlabOpen) {
  // All particles in one thin layer: the balanced cuts coincide, but every slab keeps min_width.
  AxisHistogram layer{0.5, 0.5 + 1e-6, {100.0}};
  const std::vector<double> cuts = balanced_cuts(layer, 0.0, 1.0, 4, 0.01);
  for (std::size_t j = 1; j < cuts.size(); ++j)
    EXPECT_GE(cuts[j] - cuts[j - 1], 0.01 - 1e-12);
  EXPECT_DOUBLE_EQ(cuts.front(), 0.0);
  EXPECT_DOUBLE_EQ(cuts.back(), 1.0);
  // A min_width the box cannot give to every slab shrinks to even shares.
  const std::vector<double> tight = balanced_cuts(layer, 0.0, 1.0, 4, 10.0);
  for (std::size_t j = 1; j < tight.size(); ++j)
    EXPECT_NEAR(tight[j] - tight[j - 1], 0.25, 1e-12);
  // Water at the upper face: the slabs below it keep min_width too.
  AxisHistogram top{0.999, 1.0, {100.0}};
  const std::vector<double> high = balanced_cuts(top, 0.0, 1.0, 3, 0.05);
  EXPECT_NEAR(high[2], 0.95, 1e-12);
  EXPECT_NEAR(high[1], 0.9, 1e-12);
}

TEST(BalancedCuts, WithoutParticlesAreEven) {
  EXPECT_EQ(balanced_cuts({0.0, 1.0, {0.0, 0.0}}, 0.0, 1.0, 4, 0.0), uniform_cuts(4));
  EXPECT_EQ(balanced_cuts({}, 0.0, 1.0, 2, 0.0), uniform_cuts(2));
  EXPECT_EQ(balanced_cuts({0.0, 1.0, {5.0}}, 0.0, 1.0, 1, 0.0), (std::vector<double>{0.0, 1.0}));
}

TEST(BalancedCuts, RefuseNonsense) {
  AxisHistogram some{0.0, 1.0, {1.0}};
  EXPECT_THROW(balanced_cuts(some, 0.0, 1.0, 0, 0.0), std::invalid_argument);
  EXPECT_THROW(balanced_cuts(some, 1.0, 1.0, 2, 0.0), std::invalid_argument);
  EXPECT_THROW(balanced_cuts(some, 0.0, 0.5, 2, 0.0), std::invalid_argument);
}

TEST(Imbalance, IsTheLargestShareOverTheMean) {
  EXPECT_DOUBLE_EQ(imbalance(std::vector<std::uint64_t>{500, 500}), 1.0);
  EXPECT_DOUBLE_EQ(imbalance(std::vector<std::uint64_t>{1250, 0}), 2.0);
  EXPECT_DOUBLE_EQ(imbalance(std::vector<std::uint64_t>{3, 1, 2, 2}), 1.5);
  EXPECT_DOUBLE_EQ(imbalance(std::vector<std::uint64_t>{0, 0}), 1.0);
  EXPECT_DOUBLE_EQ(imbalance(std::vector<std::uint64_t>{}), 1.0);
  EXPECT_EQ(grid_text({2, 1, 1}), "2 x 1 x 1");
}

}  // namespace
}  // namespace fsi::client
