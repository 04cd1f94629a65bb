// The wall pressure probe on hand-made sets of sampling points with known forces.

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "fsi/common/error.hpp"
#include "fsi/probes/evaluation.hpp"

namespace fsi::probes {
namespace {

// Sampling points as fix fsi/sph records them (dimension values per sample).
struct Samples {
  int dimension = 2;
  std::vector<double> positions, normals, forces, measures;
  std::vector<std::uint32_t> elements, pairs;
  void add(const std::array<double, 3>& x, const std::array<double, 3>& n,
           const std::array<double, 3>& f, double measure, std::uint32_t element,
           std::uint32_t pair_count) {
    for (int k = 0; k < dimension; ++k) {
      positions.push_back(x[k]);
      normals.push_back(n[k]);
      forces.push_back(f[k]);
    }
    measures.push_back(measure);
    elements.push_back(element);
    pairs.push_back(pair_count);
  }
  WallSamples view() const {
    return {measures.size(), positions, normals, forces, measures, elements, pairs};
  }
};

constexpr double kRho0 = 1000.0, kG = 9.81, kLevel = 0.08;
constexpr double kSegment = 0.01;  // the wall's segments
// The 3-point Gauss-Legendre rule on [0, 1].
const std::array<double, 3> kGaussPosition{0.5 - 0.5 * std::sqrt(0.6), 0.5,
                                           0.5 + 0.5 * std::sqrt(0.6)};
const std::array<double, 3> kGaussWeight{5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};

double hydrostatic(double y) {
  return y < kLevel ? kRho0 * kG * (kLevel - y) : 0.0;
}

// The left wall x = 0 of a tank, 10 segments from y = 0 to 0.1 (elements 0-9), water (x > 0) up
// to y = 0.08 in hydrostatic equilibrium: each sampling point carries the force p(y) A of the
// water, towards -x. Odd segments are drawn downwards (their normal points into the wall): the
// probe turns every normal to the fluid's side. Above the water the points are dry. Elements
// 10-11: a thin plate at x = 0.002 along the same heights (another body) with a large force, which
// the wall's probes must not see.
Samples tank_wall() {
  Samples samples;
  for (std::uint32_t segment = 0; segment < 10; ++segment) {
    const double normal_x = segment % 2 == 0 ? 1.0 : -1.0;
    for (int q = 0; q < 3; ++q) {
      const double y = kSegment * (segment + kGaussPosition[q]);
      const double measure = kSegment * kGaussWeight[q];
      const double p = hydrostatic(y);
      samples.add({0.0, y, 0.0}, {normal_x, 0.0, 0.0}, {-p * measure, 0.0, 0.0}, measure, segment,
                  p > 0.0 ? 7u : 0u);
    }
  }
  for (std::uint32_t plate = 10; plate < 12; ++plate) {
    for (int q = 0; q < 3; ++q) {
      const double y = 0.04 + 0.01 * (plate - 10 + kGaussPosition[q]);
      samples.add({0.002, y, 0.0}, {1.0, 0.0, 0.0}, {-1e6, 0.0, 0.0}, 0.01 * kGaussWeight[q], plate,
                  3u);
    }
  }
  return samples;
}

const ProbeContext kPlane{2, {0.0, -kG, 0.0}, 0.001};
const std::array<double, 3> kIntoTheTank{1.0, 0.0, 0.0};

ProbeDefinition gauge(const std::string& name, double y, double radius) {
  return wall_pressure_probe(name, {0.0, y, 0.0}, radius, kIntoTheTank, {{0u, 10u}});
}

std::vector<double> evaluate(const ProbeSet& set, const Samples& samples) {
  return set.values(set.partials({}, {}, samples.view()));
}

TEST(WallPressureProbe, NamesItsColumnsWithUnits) {
  const auto probe = gauge("p1", 0.05, 0.01);
  const auto two = columns(probe, 2), three = columns(probe, 3);
  ASSERT_EQ(two.size(), 3u);
  EXPECT_EQ(two[0].name + " [" + two[0].unit + "]", "p1_pressure [Pa]");
  EXPECT_EQ(two[1].name + " [" + two[1].unit + "]", "p1_force [N/m]");
  EXPECT_EQ(two[2].name + " [" + two[2].unit + "]", "p1_pairs [-]");
  EXPECT_EQ(three[1].unit, "N");
  EXPECT_EQ(kind_name(ProbeKind::WallPressure), "wall_pressure");
}

TEST(WallPressureProbe, GivesTheHydrostaticPressureOverWholeSegments) {
  // Centre 0.05, radius 0.02: the sampling points of the four segments from 0.03 to 0.07 (the
  // next ones lie 0.0211 away). Over whole segments the Gauss rule integrates the linear p exactly.
  const ProbeSet set({gauge("middle", 0.05, 0.02)}, kPlane);
  const auto values = evaluate(set, tank_wall());
  EXPECT_NEAR(values[0], hydrostatic(0.05), 1e-9 * hydrostatic(0.05));
  EXPECT_NEAR(values[1], hydrostatic(0.05) * 0.04, 1e-9 * hydrostatic(0.05) * 0.04);
  EXPECT_EQ(values[2], 4 * 3 * 7);
}

TEST(WallPressureProbe, ResolvesAPatchSmallerThanASegment) {
  // Radius 3 mm around y = 0.055: only the middle Gauss point of the segment 0.05-0.06.
  const ProbeSet set({gauge("point", 0.055, 0.003)}, kPlane);
  const auto values = evaluate(set, tank_wall());
  EXPECT_NEAR(values[0], hydrostatic(0.055), 1e-9 * hydrostatic(0.055));
  EXPECT_EQ(values[2], 7);
}

TEST(WallPressureProbe, SaysDryAboveTheWater) {
  const ProbeSet set({gauge("air", 0.095, 0.004)}, kPlane);
  const auto values = evaluate(set, tank_wall());
  EXPECT_EQ(values, (std::vector<double>{0.0, 0.0, 0.0}));
}

TEST(WallPressureProbe, ReadsOnlyItsOwnMeshAndSignsSuctionNegative) {
  // The plate's elements 10-11 lie within the patch, but only the wall's elements count.
  const ProbeSet wall({gauge("wall", 0.05, 0.02)}, kPlane);
  const ProbeSet plate(
      {wall_pressure_probe("plate", {0.0, 0.05, 0.0}, 0.02, kIntoTheTank, {{10u, 12u}})}, kPlane);
  const Samples samples = tank_wall();
  EXPECT_NEAR(evaluate(wall, samples)[0], hydrostatic(0.05), 1e-9 * hydrostatic(0.05));
  EXPECT_NEAR(evaluate(plate, samples)[0], 3e8, 1e-9 * 3e8);
  // The fluid pulling the wall towards itself (+x): a negative pressure.
  Samples pulled = samples;
  for (std::size_t s = 0; s < pulled.measures.size(); ++s)
    pulled.forces[2 * s] = -pulled.forces[2 * s];
  EXPECT_NEAR(evaluate(wall, pulled)[0], -hydrostatic(0.05), 1e-9 * hydrostatic(0.05));
}

TEST(WallPressureProbe, AtACornerReadsTheWallItIsOnNotTheFloor) {
  // The tank's floor y = 0 in the same mesh as the wall (elements 10-12, 1 cm segments from the
  // corner, drawn both ways), loaded with ten times the water's pressure at the bottom. A gauge
  // 2 mm above the floor with a 1 cm radius reaches three floor segments; it reads the wall's
  // Gauss points within its radius only (before 2026-12-06 it averaged the floor in: 5.3 times
  // the wall's pressure).
  Samples samples = tank_wall();
  samples.forces.resize(2 * 30);
  samples.positions.resize(2 * 30);
  samples.normals.resize(2 * 30);
  samples.measures.resize(30);
  samples.elements.resize(30);
  samples.pairs.resize(30);
  const double bottom = 10.0 * hydrostatic(0.0);
  for (std::uint32_t segment = 0; segment < 3; ++segment) {
    for (int q = 0; q < 3; ++q) {
      const double x = kSegment * (segment + kGaussPosition[q]);
      const double measure = kSegment * kGaussWeight[q];
      samples.add({x, 0.0, 0.0}, {0.0, segment % 2 == 0 ? 1.0 : -1.0, 0.0},
                  {0.0, -bottom * measure, 0.0}, measure, 10 + segment, 7u);
    }
  }
  const ProbeSet corner(
      {wall_pressure_probe("corner", {0.0, 0.002, 0.0}, 0.01, kIntoTheTank, {{0u, 13u}})}, kPlane);
  // The wall's Gauss points within 1 cm of y = 0.002: the first segment's three and the second
  // one's first (y = 0.0113).
  double force = 0.0, length = 0.0;
  for (std::uint32_t s = 0; s < 30; ++s) {
    const double y = samples.positions[2 * s + 1];
    if (std::abs(y - 0.002) > 0.01) continue;
    force -= samples.forces[2 * s];
    length += samples.measures[s];
  }
  const auto values = evaluate(corner, samples);
  EXPECT_NEAR(values[0], force / length, 1e-9 * hydrostatic(0.0));
  EXPECT_NEAR(values[0], hydrostatic(0.004), 0.05 * hydrostatic(0.0));
  EXPECT_EQ(values[2], 4 * 7);
  // A patch on the floor alone (its fluid side up) reads the floor.
  const ProbeSet floor(
      {wall_pressure_probe("floor", {0.015, 0.0, 0.0}, 0.004, {0.0, 1.0, 0.0}, {{0u, 13u}})},
      kPlane);
  EXPECT_NEAR(evaluate(floor, samples)[0], bottom, 1e-9 * bottom);
}

// The one rule of which elements a probe reads (the scene's check and the evaluation share it):
// within 45 degrees of the fluid side, either orientation, whatever the normal's length.
TEST(WallPressureProbe, AnElementFacesItsFluidSideToWithin45Degrees) {
  const double side[3] = {1.0, 0.0, 0.0};
  const double wall[3] = {-3.0, 0.0, 0.0}, floor[3] = {0.0, 2.0, 0.0};
  const double at_44[3] = {std::cos(0.767945), std::sin(0.767945), 0.0};  // 44 degrees
  const double at_46[3] = {std::cos(0.802851), std::sin(0.802851), 0.0};  // 46 degrees
  EXPECT_TRUE(probes::faces_fluid_side(wall, side, 2));
  EXPECT_FALSE(probes::faces_fluid_side(floor, side, 3));
  EXPECT_TRUE(probes::faces_fluid_side(at_44, side, 3));
  EXPECT_FALSE(probes::faces_fluid_side(at_46, side, 3));
}

TEST(WallPressureProbe, TwoRanksGiveWhatOneRankGives) {
  // Each rank holds every sampling point with the forces of its own particles.
  const Samples whole = tank_wall();
  Samples first = whole, second = whole;
  for (std::size_t s = 0; s < whole.measures.size(); ++s) {
    const double share = 0.3 + 0.05 * static_cast<double>(s % 5);
    first.forces[2 * s] = share * whole.forces[2 * s];
    second.forces[2 * s] = (1.0 - share) * whole.forces[2 * s];
    first.pairs[s] = whole.pairs[s] / 2;
    second.pairs[s] = whole.pairs[s] - first.pairs[s];
  }
  const ProbeSet set({gauge("a", 0.05, 0.02), gauge("b", 0.015, 0.004), gauge("dry", 0.09, 0.01)},
                     kPlane);
  const auto one_rank = evaluate(set, whole);
  Partials reduced = set.partials({}, {}, first.view());
  const Partials other = set.partials({}, {}, second.view());
  for (std::size_t k = 0; k < reduced.sums.size(); ++k)
    reduced.sums[k] += other.sums[k];
  for (std::size_t k = 0; k < reduced.maxima.size(); ++k)
    reduced.maxima[k] = std::max(reduced.maxima[k], other.maxima[k]);
  const auto two_ranks = set.values(reduced);
  ASSERT_EQ(two_ranks.size(), 9u);
  for (std::size_t k = 0; k < one_rank.size(); ++k)
    EXPECT_NEAR(two_ranks[k], one_rank[k], 1e-9 * (1.0 + std::abs(one_rank[k]))) << "column " << k;
  EXPECT_GT(one_rank[3], 0.0);
}

TEST(WallPressureProbe, AveragesOverAPatchOfTrianglesIn3D) {
  // The floor z = 0 of a 3D tank in 1 cm squares of two triangles each (either orientation),
  // under water of depth 0.1 m: the force rho0 g 0.1 A on every sampling point (one per triangle,
  // at its centroid), towards -z. A disc of radius 0.025 m around the origin takes the centroids
  // within it.
  Samples samples;
  samples.dimension = 3;
  const double p = kRho0 * kG * 0.1;
  const double area = 0.5e-4;
  std::uint32_t element = 0;
  double inside = 0.0;
  for (int i = -5; i < 5; ++i) {
    for (int j = -5; j < 5; ++j) {
      for (int half = 0; half < 2; ++half) {
        const double x = 0.01 * (i + (half == 0 ? 1.0 / 3.0 : 2.0 / 3.0));
        const double y = 0.01 * (j + (half == 0 ? 1.0 / 3.0 : 2.0 / 3.0));
        samples.add({x, y, 0.0}, {0.0, 0.0, half == 0 ? 1.0 : -1.0}, {0.0, 0.0, -p * area}, area,
                    element++, 5u);
        if (x * x + y * y <= 0.025 * 0.025) inside += area;
      }
    }
  }
  const ProbeSet set(
      {wall_pressure_probe("floor", {0.0, 0.0, 0.0}, 0.025, {0.0, 0.0, 1.0}, {{0u, element}})},
      {3, {0.0, 0.0, -kG}, 0.001});
  const auto values = evaluate(set, samples);
  EXPECT_NEAR(values[0], p, 1e-9 * p);
  EXPECT_NEAR(values[1], p * inside, 1e-9 * p * inside);
}

TEST(WallPressureProbe, ASetKnowsItReadsTheWallAndNamesAnEmptyPatch) {
  const ProbeSet without({point_probe("p", {})}, kPlane);
  EXPECT_FALSE(without.needs_wall_samples());
  EXPECT_EQ(without.wall_problems(tank_wall().view()), "");
  const ProbeSet set(
      {gauge("good", 0.05, 0.02), gauge("between", 0.05, 0.0005), gauge("far", 0.5, 0.01)}, kPlane);
  EXPECT_TRUE(set.needs_wall_samples());
  const std::string problems = set.wall_problems(tank_wall().view());
  EXPECT_EQ(problems.find("'good'"), std::string::npos);
  EXPECT_NE(problems.find("wall_pressure probe 'between': no sampling point of the wall law lies "
                          "in its patch (of 36 on the boundary mesh)"),
            std::string::npos)
      << problems;
  EXPECT_NE(problems.find("'far'"), std::string::npos);
}

TEST(WallPressureProbe, DefinitionProblemsNameWhatToFix) {
  EXPECT_EQ(definition_problem(gauge("g", 0.05, 0.01), 2), "");
  EXPECT_EQ(definition_problem(gauge("g", 0.05, 0.0), 2),
            "wall pressure probe 'g' needs a positive radius");
  EXPECT_EQ(
      definition_problem(wall_pressure_probe("g", {}, 0.01, {}, {{0u, 1u}}), 2),
      "wall pressure probe 'g' needs a fluid side (a direction from the wall into the fluid)");
  EXPECT_EQ(definition_problem(wall_pressure_probe("g", {}, 0.01, kIntoTheTank, {}), 2),
            "wall pressure probe 'g' needs 1 to 10^6 element ranges");
  EXPECT_NE(definition_problem(wall_pressure_probe("g", {}, 0.01, kIntoTheTank, {{3u, 3u}}), 2)
                .find("not [first, end)"),
            std::string::npos);
  ProbeDefinition cut = gauge("g", 0.05, 0.01);
  cut.parameters.pop_back();
  EXPECT_EQ(definition_problem(cut, 2), "a wall_pressure probe has 10 parameters, 'g' has 9");
  EXPECT_THROW(ProbeSet({gauge("g", 0.05, -1.0)}, kPlane), Error);
}

}  // namespace
}  // namespace fsi::probes
