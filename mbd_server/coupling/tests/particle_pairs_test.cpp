#include "fsi/coupling/particle_pairs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace fsi::coupling {
namespace {

// Every pair, the slow way.
ParticlePairs all_pairs_closer_than(const std::vector<double>& x, int dimension, double radius) {
  const auto dim = static_cast<std::size_t>(dimension);
  ParticlePairs pairs;
  for (std::size_t i = 0; i < x.size() / dim; ++i) {
    for (std::size_t j = i + 1; j < x.size() / dim; ++j) {
      double squared = 0.0;
      for (std::size_t k = 0; k < dim; ++k)
        squared += (x[dim * i + k] - x[dim * j + k]) * (x[dim * i + k] - x[dim * j + k]);
      if (squared >= radius * radius) continue;
      ++pairs.count;
      if (!pairs.closest || std::sqrt(squared) < *pairs.closest) pairs.closest = std::sqrt(squared);
    }
  }
  return pairs;
}

TEST(ParticlePairs, ALatticeHasNoneAndASecondParticleOnASiteIsFoundWhereItIs) {
  const double d = 0.025;
  std::vector<double> lattice;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 16; ++j) {
      lattice.push_back((i + 0.5) * d);
      lattice.push_back((j + 0.5) * d);
    }
  }
  const ParticlePairs none = particle_pairs_closer_than(lattice, 2, 0.5 * d);
  EXPECT_EQ(none.count, 0u);
  EXPECT_FALSE(none.closest.has_value());
  // The corner pair of a settled tank (docs/theory.md): a second particle 0.13 d from the
  // corner's site.
  lattice.push_back(0.5 * d + 0.13 * d);
  lattice.push_back(0.5 * d);
  const ParticlePairs one = particle_pairs_closer_than(lattice, 2, 0.5 * d);
  EXPECT_EQ(one.count, 1u);
  ASSERT_TRUE(one.closest.has_value());
  EXPECT_NEAR(*one.closest, 0.13 * d, 1e-15);
  ASSERT_EQ(one.where.size(), 2u);
  EXPECT_NEAR(one.where[0], 0.565 * d, 1e-15);
  EXPECT_NEAR(one.where[1], 0.5 * d, 1e-15);
}

TEST(ParticlePairs, TheNearestParticleOfOne) {
  // 3D: three particles on a line.
  const std::vector<double> x{0.0, 0.0, 0.0, 0.3, 0.0, 0.0, 0.0, 0.0, -0.1};
  EXPECT_DOUBLE_EQ(*nearest_particle_distance(x, 3, 0), 0.1);
  EXPECT_DOUBLE_EQ(*nearest_particle_distance(x, 3, 1), 0.3);  // not the third, 0.316 away
  EXPECT_DOUBLE_EQ(*nearest_particle_distance(x, 3, 2), 0.1);
  EXPECT_FALSE(nearest_particle_distance(std::vector<double>{1.0, 2.0}, 2, 0).has_value());
}

TEST(ParticlePairs, TheCellListFindsWhatComparingEveryPairFinds) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(-0.3, 0.5);  // cells on both sides of 0
  for (int dimension : {2, 3}) {
    for (double radius : {0.01, 0.03, 0.2}) {
      std::vector<double> x(static_cast<std::size_t>(dimension) * 400);
      for (double& value : x)
        value = coordinate(random);
      const ParticlePairs fast = particle_pairs_closer_than(x, dimension, radius);
      const ParticlePairs slow = all_pairs_closer_than(x, dimension, radius);
      EXPECT_EQ(fast.count, slow.count) << dimension << "D, radius " << radius;
      ASSERT_EQ(fast.closest.has_value(), slow.closest.has_value());
      if (slow.closest) {
        EXPECT_DOUBLE_EQ(*fast.closest, *slow.closest);
      }
      EXPECT_GT(slow.count, 0u) << "the test must have pairs to find";
    }
  }
}

}  // namespace
}  // namespace fsi::coupling
