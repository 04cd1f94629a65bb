// A rank's share of the boundary mesh (boundary_share.hpp; docs/user-guide.md "Ranks and
// balance").
#include "boundary_share.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace fsi::client {
namespace {

// A 2D floor of `n` segments from x = 0 to x = 1 at y = 0, its vertices 0..n; the first
// `dynamic` vertices are dynamic.
struct Floor {
  std::vector<double> positions;
  std::vector<std::uint32_t> segments;
  WholeMesh view(std::size_t dynamic) const { return {2, positions, segments, dynamic}; }
};

Floor floor_of(std::size_t n) {
  Floor floor;
  for (std::size_t i = 0; i <= n; ++i) {
    floor.positions.push_back(static_cast<double>(i) / static_cast<double>(n));
    floor.positions.push_back(0.0);
  }
  for (std::size_t i = 0; i < n; ++i) {
    floor.segments.push_back(static_cast<std::uint32_t>(i));
    floor.segments.push_back(static_cast<std::uint32_t>(i + 1));
  }
  return floor;
}

ShareBox box_2d(double x0, double y0, double x1, double y1) {
  ShareBox box;
  box.include(std::vector<double>{x0, y0}, 2);
  box.include(std::vector<double>{x1, y1}, 2);
  return box;
}

TEST(BoundaryShare, HoldsTheElementsWithinReachOfTheCoveredBoxOnly) {
  const Floor floor = floor_of(10);  // segments of 0.1 m
  // Water over 0.42 <= x <= 0.58 up to 0.2 m; reach 0.05 m: segments [0.3, 0.4] .. [0.6, 0.7].
  const BoundaryShare share =
      select_share(floor.view(11), box_2d(0.42, 0.0, 0.58, 0.2), 0.05, SharePeriodicity{});
  EXPECT_EQ(share.elements, (std::vector<std::uint32_t>{3, 4, 5, 6}));
  EXPECT_EQ(share.vertices, (std::vector<std::uint32_t>{3, 4, 5, 6, 7}));
  EXPECT_EQ(share.dynamic_vertices, 5u);
  // Water 0.1 m above the floor with a reach of 0.05 m: nothing.
  EXPECT_TRUE(select_share(floor.view(11), box_2d(0.0, 0.16, 1.0, 0.3), 0.05, SharePeriodicity{})
                  .elements.empty());
  // No particles, no sub-domain: nothing.
  EXPECT_TRUE(select_share(floor.view(11), ShareBox{}, 0.05, SharePeriodicity{}).elements.empty());
  // Only the first 4 vertices dynamic: 3 of the share's are.
  EXPECT_EQ(select_share(floor.view(4), box_2d(0.42, 0.0, 0.58, 0.2), 0.05, SharePeriodicity{})
                .dynamic_vertices,
            1u);
}

TEST(BoundaryShare, ReachesAcrossAPeriodicBoundary) {
  const Floor floor = floor_of(10);
  // Water near x = 0 of a box periodic in x with period 1: its images near x = 1 reach the last
  // segment too.
  SharePeriodicity periodic;
  periodic.periodic = {true, false, false};
  periodic.period = {1.0, 0.0, 0.0};
  const ShareBox near_zero = box_2d(0.0, 0.0, 0.03, 0.1);
  EXPECT_EQ(select_share(floor.view(11), near_zero, 0.05, SharePeriodicity{}).elements,
            (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(select_share(floor.view(11), near_zero, 0.05, periodic).elements,
            (std::vector<std::uint32_t>{0, 9}));
}

TEST(BoundaryShare, SplitsAFloorBetweenTwoRanksWithAHalo) {
  const Floor floor = floor_of(100);
  const double reach = 0.03;
  const BoundaryShare left =
      select_share(floor.view(101), box_2d(0.0, 0.0, 0.5, 0.2), reach, SharePeriodicity{});
  const BoundaryShare right =
      select_share(floor.view(101), box_2d(0.5, 0.0, 1.0, 0.2), reach, SharePeriodicity{});
  // Each holds its half and the 3 segments within reach beyond its edge (4 with the boundary
  // one touching): 53 or 54 of 100, not the whole.
  EXPECT_GE(left.elements.size(), 53u);
  EXPECT_LE(left.elements.size(), 54u);
  EXPECT_GE(right.elements.size(), 53u);
  EXPECT_LE(right.elements.size(), 54u);
  // Together they hold every element.
  std::vector<bool> held(100, false);
  for (const std::uint32_t e : left.elements)
    held[e] = true;
  for (const std::uint32_t e : right.elements)
    held[e] = true;
  EXPECT_EQ(std::count(held.begin(), held.end(), true), 100);
}

TEST(BoundaryShare, RenumbersItsMeshAndCarriesValuesBothWays) {
  const Floor floor = floor_of(10);
  std::vector<double> velocities(floor.positions.size());
  for (std::size_t i = 0; i < velocities.size(); ++i)
    velocities[i] = 100.0 + static_cast<double>(i);
  const BoundaryShare share =
      select_share(floor.view(11), box_2d(0.42, 0.0, 0.58, 0.2), 0.05, SharePeriodicity{});
  const LocalMesh local = local_mesh(floor.view(11), velocities, share);
  EXPECT_EQ(local.elements, (std::vector<std::uint32_t>{0, 1, 1, 2, 2, 3, 3, 4}));
  ASSERT_EQ(local.positions.size(), 10u);
  EXPECT_DOUBLE_EQ(local.positions[0], 0.3);
  EXPECT_DOUBLE_EQ(local.velocities[0], 106.0);  // vertex 3, x
  EXPECT_DOUBLE_EQ(local.velocities[9], 115.0);  // vertex 7, y
  // Forces of the share's 5 vertices added onto the whole mesh's 11.
  std::vector<double> whole(22, 1.0);
  add_share_values(std::vector<double>(10, 0.5), share.vertices, share.dynamic_vertices, 2, whole);
  EXPECT_DOUBLE_EQ(whole[6], 1.5);   // vertex 3
  EXPECT_DOUBLE_EQ(whole[15], 1.5);  // vertex 7, y
  EXPECT_DOUBLE_EQ(whole[16], 1.0);  // vertex 8 is not in the share
  EXPECT_EQ(share_values(whole, share.vertices, 2, 2), (std::vector<double>{1.5, 1.5, 1.5, 1.5}));
}

TEST(BoundaryShare, SelectsTrianglesIn3DAndTheWholeMeshOnRequest) {
  // Two triangles: one at z = 0, one at z = 1.
  const std::vector<double> positions{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1};
  const std::vector<std::uint32_t> triangles{0, 1, 2, 3, 4, 5};
  const WholeMesh mesh{3, positions, triangles, 3};
  ShareBox low;
  low.include(std::vector<double>{0.0, 0.0, 0.05}, 3);
  low.include(std::vector<double>{1.0, 1.0, 0.2}, 3);
  const BoundaryShare share = select_share(mesh, low, 0.1, SharePeriodicity{});
  EXPECT_EQ(share.elements, (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(share.dynamic_vertices, 3u);
  const BoundaryShare all = whole_share(mesh);
  EXPECT_EQ(all.elements, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(all.vertices.size(), 6u);
  EXPECT_EQ(all.dynamic_vertices, 3u);
}

TEST(BoundaryShare, RejectsABadMeshOrReach) {
  const Floor floor = floor_of(2);
  EXPECT_THROW(select_share(floor.view(3), box_2d(0, 0, 1, 1), -1.0, SharePeriodicity{}),
               std::invalid_argument);
  const std::vector<std::uint32_t> bad{0, 7};
  EXPECT_THROW(select_share(WholeMesh{2, floor.positions, bad, 3}, box_2d(0, 0, 1, 1), 0.1,
                            SharePeriodicity{}),
               std::invalid_argument);
  EXPECT_THROW(select_share(WholeMesh{4, floor.positions, floor.segments, 3}, box_2d(0, 0, 1, 1),
                            0.1, SharePeriodicity{}),
               std::invalid_argument);
}

TEST(BoundaryShare, MeasuresTheLargestDisplacement) {
  EXPECT_DOUBLE_EQ(
      largest_displacement(std::vector<double>{0, 0, 1, 1}, std::vector<double>{0, 0, 4, 5}, 2),
      5.0);
  EXPECT_DOUBLE_EQ(largest_displacement(std::vector<double>{}, std::vector<double>{}, 3), 0.0);
}

}  // namespace
}  // namespace fsi::client
