#include "fsi/contact/cell_grid.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <utility>
#include <vector>

namespace fsi::contact {
namespace {

std::vector<double> random_points(std::size_t count, int dimension, unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> coordinate(-0.3, 0.7);
  std::vector<double> points(count * static_cast<std::size_t>(dimension));
  for (double& x : points)
    x = coordinate(random);
  return points;
}

// Two different point sets, 2D and 3D, three radii: the grid finds exactly the pairs that
// comparing every point with every other finds, with their squared distances.
TEST(CellGrid, ClosePairsOfTwoSetsAreThoseOfComparingEveryPair) {
  for (int dimension : {2, 3}) {
    const auto dim = static_cast<std::size_t>(dimension);
    const std::vector<double> points = random_points(300, dimension, 7);
    const std::vector<double> others = random_points(500, dimension, 11);
    for (double radius : {0.01, 0.05, 0.2}) {
      std::set<std::pair<std::size_t, std::size_t>> expected;
      for (std::size_t i = 0; i < points.size() / dim; ++i)
        for (std::size_t j = 0; j < others.size() / dim; ++j) {
          double squared = 0.0;
          for (std::size_t k = 0; k < dim; ++k)
            squared += (points[dim * i + k] - others[dim * j + k]) *
                       (points[dim * i + k] - others[dim * j + k]);
          if (squared < radius * radius) expected.emplace(i, j);
        }
      std::set<std::pair<std::size_t, std::size_t>> found;
      std::size_t previous_point = 0;
      for_each_close_pair(points, others, dimension, radius,
                          [&](std::size_t i, std::size_t j, double squared) {
                            EXPECT_GE(i, previous_point) << "the points in order";
                            previous_point = i;
                            EXPECT_LT(squared, radius * radius);
                            EXPECT_TRUE(found.emplace(i, j).second) << "a pair twice";
                          });
      EXPECT_EQ(found, expected) << dimension << "D, radius " << radius;
      EXPECT_FALSE(expected.empty() && radius >= 0.05);
    }
  }
}

TEST(CellGrid, NoPointsNoPairs) {
  int calls = 0;
  for_each_close_pair({}, std::vector<double>{0.0, 0.0}, 2, 1.0,
                      [&](std::size_t, std::size_t, double) { ++calls; });
  for_each_close_pair(std::vector<double>{0.0, 0.0}, {}, 2, 1.0,
                      [&](std::size_t, std::size_t, double) { ++calls; });
  EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace fsi::contact
