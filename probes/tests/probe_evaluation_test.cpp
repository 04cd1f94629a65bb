// Each probe kind on hand-made particle sets with known answers, and the reduction over ranks.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fsi/common/error.hpp"
#include "fsi/probes/evaluation.hpp"

namespace fsi::probes {
namespace {

// LIGGGHTS' spiky2d kernel: W(r) = 5 / (16 pi h^2) (2 - r/h)^3 for r < 2h, support 2h.
Kernel spiky2d(double h) {
  return {2.0 * h, [h](double r) {
            const double s = r / h;
            return s < 2.0 ? 5.0 / (16.0 * std::numbers::pi * h * h) * std::pow(2.0 - s, 3) : 0.0;
          }};
}

// Particles with every field owned (no ghosts) unless stated.
struct Particles {
  std::vector<double> positions, velocities, density, pressure, mass;
  std::size_t ghosts = 0;
  void add(double x, double y, double vx, double vy, double rho, double p, double m) {
    positions.insert(positions.end(), {x, y});
    velocities.insert(velocities.end(), {vx, vy});
    density.push_back(rho);
    pressure.push_back(p);
    mass.push_back(m);
  }
  void add_ghost(double x, double y) {
    positions.insert(positions.end(), {x, y});
    ++ghosts;
  }
  ParticleSet set() const {
    return {positions.size() / 2 - ghosts, positions, velocities, density, pressure, mass};
  }
};

constexpr double kRho0 = 1000.0;
constexpr double kSpacing = 0.001;
constexpr double kSmoothing = 1.9 * kSpacing;
const std::array<double, 3> kGravity{0.0, -9.81, 0.0};

// A lattice of spacing d filling [x0, x1] x [0, height] (cell centres), with u = (a + b y, c x),
// p = rho0 g (height - y).
Particles water_block(double x0, double x1, double height) {
  Particles particles;
  const double mass = kRho0 * kSpacing * kSpacing;
  for (double y = 0.5 * kSpacing; y < height; y += kSpacing) {
    for (double x = x0 + 0.5 * kSpacing; x < x1; x += kSpacing) {
      particles.add(x, y, 0.2 + 3.0 * y, -1.5 * x, kRho0, kRho0 * 9.81 * (height - y), mass);
    }
  }
  return particles;
}

TEST(FluidEnergyProbe, SumsKineticAndPotentialEnergyAboutTheDatum) {
  Particles particles;
  particles.add(0.0, 1.0, 3.0, 4.0, kRho0, 0.0, 2.0);   // v^2 = 25, 1 m above y = 0
  particles.add(5.0, -0.5, 0.0, 1.0, kRho0, 0.0, 4.0);  // v^2 = 1, 0.5 m below
  const ProbeSet set({fluid_energy_probe("e", {0.0, 0.25, 0.0})}, {2, kGravity, kSpacing});
  const auto values = set.values(set.partials(particles.set(), spiky2d(kSmoothing)));
  EXPECT_DOUBLE_EQ(values[0], 0.5 * 2.0 * 25.0 + 0.5 * 4.0 * 1.0);
  EXPECT_DOUBLE_EQ(values[1], 2.0 * 9.81 * 0.75 + 4.0 * 9.81 * (-0.75));
}

TEST(PointProbe, ReproducesALinearFieldInsideAUniformLattice) {
  const Particles block = water_block(0.0, 0.04, 0.03);
  const ProbeSet set({point_probe("at_node", {0.0205, 0.0105, 0.0}),
                      point_probe("at_centre", {0.020, 0.010, 0.0})},
                     {2, kGravity, kSpacing});
  const auto values = set.values(set.partials(block.set(), spiky2d(kSmoothing)));
  for (const auto& [offset, x, y] : {std::tuple{0, 0.0205, 0.0105}, std::tuple{5, 0.020, 0.010}}) {
    EXPECT_NEAR(values[offset + 0], 0.2 + 3.0 * y, 1e-12);
    EXPECT_NEAR(values[offset + 1], -1.5 * x, 1e-12);
    EXPECT_NEAR(values[offset + 2], kRho0 * 9.81 * (0.03 - y), 1e-9);
    EXPECT_EQ(values[offset + 4], 1.0);  // wet
  }
  // Particles within 2h = 3.8 d of a lattice node: the node itself and 44 around it.
  EXPECT_EQ(values[3], 45.0);
}

TEST(PointProbe, SaysDryWithZerosWhereNoParticleIsWithinTheSupport) {
  const Particles block = water_block(0.0, 0.04, 0.03);
  const ProbeSet set({point_probe("air", {0.02, 0.03 + 2.0 * kSmoothing, 0.0})},
                     {2, kGravity, kSpacing});
  const auto values = set.values(set.partials(block.set(), spiky2d(kSmoothing)));
  EXPECT_EQ(values, (std::vector<double>{0.0, 0.0, 0.0, 0.0, 0.0}));
}

TEST(FreeSurfaceProbe, FindsTheTopOfAWaterColumnWithinAQuarterSpacing) {
  for (const double height : {0.02, 0.0304, 0.0257}) {
    const Particles block = water_block(0.0, 0.04, height);
    const double top = 0.5 * kSpacing + std::floor((height - 0.5 * kSpacing) / kSpacing) * kSpacing;
    const double surface = top + 0.5 * kSpacing;  // the lattice's edge: half a spacing above
    const ProbeSet set({free_surface_probe("level", {0.0203, 0.0, 0.0}, 0.05, 201)},
                       {2, kGravity, kSpacing});
    const auto values = set.values(set.partials(block.set(), spiky2d(kSmoothing)));
    EXPECT_NEAR(values[0], surface, 0.25 * kSpacing) << "column of height " << height;
    EXPECT_EQ(values[1], 1.0);
  }
}

TEST(FreeSurfaceProbe, IgnoresAnIsolatedDropAndReportsADryLineAtItsBottom) {
  Particles block = water_block(0.0, 0.04, 0.02);
  block.add(0.0203, 0.035, 0.0, 0.0, kRho0, 0.0, kRho0 * kSpacing * kSpacing);
  const ProbeSet set({free_surface_probe("level", {0.0203, 0.0, 0.0}, 0.05, 201),
                      free_surface_probe("beside", {0.06, 0.001, 0.0}, 0.05, 201)},
                     {2, kGravity, kSpacing});
  const auto values = set.values(set.partials(block.set(), spiky2d(kSmoothing)));
  EXPECT_NEAR(values[0], 0.02, 0.25 * kSpacing);
  EXPECT_EQ(values[2], 0.001);
  EXPECT_EQ(values[3], 0.0);
}

TEST(FrontProbe, FindsTheForemostFluidAndIgnoresSpray) {
  Particles block = water_block(0.0, 0.0304, 0.01);
  // A drop 5 d ahead of the block, and a pair of drops (each one neighbour) further on.
  const double mass = kRho0 * kSpacing * kSpacing;
  block.add(0.0354, 0.005, 0.0, 0.0, kRho0, 0.0, mass);
  block.add(0.05, 0.005, 0.0, 0.0, kRho0, 0.0, mass);
  block.add(0.0505, 0.005, 0.0, 0.0, kRho0, 0.0, mass);
  const ProbeSet set({front_probe("surge", 0, 1, 3), front_probe("any", 0, 1, 0),
                      front_probe("pair", 0, 1, 1), front_probe("back", 0, -1, 3)},
                     {2, kGravity, kSpacing});
  const auto values = set.values(set.partials(block.set(), spiky2d(kSmoothing)));
  EXPECT_NEAR(values[0], 0.0295, 1e-12);  // last lattice column
  EXPECT_EQ(values[1], 1.0);
  EXPECT_DOUBLE_EQ(values[2], 0.0505);
  EXPECT_DOUBLE_EQ(values[4], 0.0505);
  EXPECT_DOUBLE_EQ(values[6], 0.0005);
}

TEST(FrontProbe, IsDryWithoutFluid) {
  const Particles none;
  const ProbeSet set({front_probe("surge", 0, 1, 3)}, {2, kGravity, kSpacing});
  EXPECT_EQ(set.values(set.partials(none.set(), spiky2d(kSmoothing))),
            (std::vector<double>{0.0, 0.0}));
}

TEST(FluxProbe, IntegratesALinearVelocityProfileThroughASegment) {
  // u = 0.2 + 3 y through the vertical segment x = 0.02 from y = 0.005 to 0.015, deep inside.
  const Particles block = water_block(0.0, 0.04, 0.03);
  const ProbeSet set({flux_probe("up", {{0.02, 0.005, 0.0}, {0.02, 0.015, 0.0}}, 40),
                      flux_probe("down", {{0.02, 0.015, 0.0}, {0.02, 0.005, 0.0}}, 40),
                      flux_probe("along", {{0.01, 0.01, 0.0}, {0.03, 0.01, 0.0}}, 40)},
                     {2, kGravity, kSpacing});
  const auto values = set.values(set.partials(block.set(), spiky2d(kSmoothing)));
  const double exact = 0.2 * 0.01 + 1.5 * (0.015 * 0.015 - 0.005 * 0.005);
  EXPECT_NEAR(values[0], exact, 0.01 * exact);
  EXPECT_DOUBLE_EQ(values[1], -values[0]);  // drawn downwards: flow in -x counts
  // A horizontal segment drawn in +x counts flow in -y: v = -1.5 x through y = 0.01.
  const double along = 1.5 * 0.5 * (0.03 * 0.03 - 0.01 * 0.01);
  EXPECT_NEAR(values[2], along, 0.01 * along);
}

TEST(FluxProbe, CountsOnlyTheWetPartOfASection) {
  // Uniform u = 1 m/s in a column 0.02 m high; the segment reaches 0.01 m above the surface.
  Particles block;
  const double mass = kRho0 * kSpacing * kSpacing;
  for (double y = 0.5 * kSpacing; y < 0.02; y += kSpacing) {
    for (double x = 0.5 * kSpacing; x < 0.04; x += kSpacing)
      block.add(x, y, 1.0, 0.0, kRho0, 0.0, mass);
  }
  const ProbeSet set({flux_probe("q", {{0.02, 0.0, 0.0}, {0.02, 0.03, 0.0}}, 120),
                      flux_probe("dry", {{0.06, 0.0, 0.0}, {0.06, 0.03, 0.0}}, 120)},
                     {2, kGravity, kSpacing});
  const auto values = set.values(set.partials(block.set(), spiky2d(kSmoothing)));
  // The kernel sum falls off within h of the floor and of the surface alike: half a support
  // of the section is missing at the floor (no fluid below y = 0), so the flux lies between
  // u (H - h) and u H.
  EXPECT_GT(values[0], 1.0 * (0.02 - kSmoothing));
  EXPECT_LT(values[0], 1.0 * 0.02);
  EXPECT_EQ(values[1], 0.0);
}

// LIGGGHTS' spiky kernel in 3D: W(r) = 15 / (64 pi h^3) (2 - r/h)^3 for r < 2h.
Kernel spiky3d(double h) {
  return {2.0 * h, [h](double r) {
            const double s = r / h;
            return s < 2.0 ? 15.0 / (64.0 * std::numbers::pi * h * h * h) * std::pow(2.0 - s, 3)
                           : 0.0;
          }};
}

TEST(FluxProbe, ThroughAPlanarPolygonIn3D) {
  // A cube of fluid moving at v = (0.5, 0, -0.25); a square 4 mm x 4 mm in the plane x = 0.01
  // (normal +x by the vertex order) and the same square tilted by its points' order.
  const double d = kSpacing;
  std::vector<double> positions, velocities, density, pressure, mass;
  for (double z = 0.5 * d; z < 0.02; z += d) {
    for (double y = 0.5 * d; y < 0.02; y += d) {
      for (double x = 0.5 * d; x < 0.02; x += d) {
        positions.insert(positions.end(), {x, y, z});
        velocities.insert(velocities.end(), {0.5, 0.0, -0.25});
        density.push_back(kRho0);
        pressure.push_back(0.0);
        mass.push_back(kRho0 * d * d * d);
      }
    }
  }
  const ParticleSet particles{density.size(), positions, velocities, density, pressure, mass};
  const ProbeSet set(
      {flux_probe(
           "x_plane",
           {{0.01, 0.008, 0.008}, {0.01, 0.012, 0.008}, {0.01, 0.012, 0.012}, {0.01, 0.008, 0.012}},
           8),
       flux_probe("z_plane", {{0.008, 0.008, 0.01}, {0.008, 0.012, 0.01}, {0.012, 0.008, 0.01}},
                  8)},
      {3, kGravity, d});
  const auto values = set.values(set.partials(particles, spiky3d(1.9 * d)));
  EXPECT_NEAR(values[0], 0.5 * 0.004 * 0.004, 0.02 * 0.5 * 0.004 * 0.004);
  // Points (0,0), (0,1), (1,0) in x, y turn clockwise seen from +z: normal -z, flow -z counts +.
  EXPECT_NEAR(values[1], 0.25 * 0.5 * 0.004 * 0.004, 0.02 * 0.25 * 0.5 * 0.004 * 0.004);
}

// Two ranks splitting the fluid at x = split, each with the other's particles within 2 h as ghosts.
std::vector<Particles> split_in_two(const Particles& all, double split) {
  std::vector<Particles> ranks(2);
  const double halo = 2.0 * kSmoothing;
  for (std::size_t i = 0; i < all.mass.size(); ++i) {
    const double x = all.positions[2 * i], y = all.positions[2 * i + 1];
    ranks[x < split ? 0 : 1].add(x, y, all.velocities[2 * i], all.velocities[2 * i + 1],
                                 all.density[i], all.pressure[i], all.mass[i]);
  }
  for (std::size_t i = 0; i < all.mass.size(); ++i) {
    const double x = all.positions[2 * i], y = all.positions[2 * i + 1];
    if (x >= split && x < split + halo) ranks[0].add_ghost(x, y);
    if (x < split && x >= split - halo) ranks[1].add_ghost(x, y);
  }
  return ranks;
}

TEST(ProbeReduction, TwoRanksGiveWhatOneRankGives) {
  Particles block = water_block(0.0, 0.03, 0.02);
  block.add(0.0302, 0.0005, 0.0, 0.0, kRho0, 0.0, kRho0 * kSpacing * kSpacing);
  const ProbeSet set(
      {fluid_energy_probe("e", {}), point_probe("p", {0.0151, 0.01, 0.0}),
       free_surface_probe("s", {0.0151, 0.0, 0.0}, 0.03, 121), front_probe("f", 0, 1, 3)},
      {2, kGravity, kSpacing});
  const Kernel kernel = spiky2d(kSmoothing);
  const auto one_rank = set.values(set.partials(block.set(), kernel));
  // The split runs through the point's and the line's support: both ranks contribute.
  const auto ranks = split_in_two(block, 0.015);
  Partials reduced = set.partials(ranks[0].set(), kernel);
  const Partials second = set.partials(ranks[1].set(), kernel);
  for (std::size_t k = 0; k < reduced.sums.size(); ++k)
    reduced.sums[k] += second.sums[k];
  for (std::size_t k = 0; k < reduced.maxima.size(); ++k)
    reduced.maxima[k] = std::max(reduced.maxima[k], second.maxima[k]);
  const auto two_ranks = set.values(reduced);
  ASSERT_EQ(two_ranks.size(), one_rank.size());
  for (std::size_t k = 0; k < one_rank.size(); ++k)
    EXPECT_NEAR(two_ranks[k], one_rank[k], 1e-9 * (1.0 + std::abs(one_rank[k]))) << "column " << k;
  // The particle 0.7 d off the block's side has neighbours enough: it is the front.
  const std::size_t front = two_ranks.size() - 3;
  EXPECT_DOUBLE_EQ(two_ranks[front] * two_ranks[front + 1], 0.0302);
  EXPECT_GT(two_ranks.back(), 0.0);  // the flux sees flow through the split
}

// A probe that moves with a body (protocol 1.4): placed, it reads the field where the body took it.
TEST(MovingProbe, APlacedPointProbeReadsTheFieldWhereTheBodyTookIt) {
  const Particles block = water_block(0.0, 0.04, 0.03);
  ProbeSet set({point_probe("on_body", {0.010, 0.005, 0.0})}, {2, kGravity, kSpacing});
  // The body turned by 90 degrees about z and moved: (0.010, 0.005) -> (0.025 - 0.005, 0.010).
  RigidPlacement placement;
  placement.rotation = {0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  placement.translation = {0.025, 0.0, 0.0};
  set.move(0, placed(set.probes()[0], placement).parameters);
  const auto values = set.values(set.partials(block.set(), spiky2d(kSmoothing)));
  EXPECT_NEAR(values[0], 0.2 + 3.0 * 0.010, 1e-12);
  EXPECT_NEAR(values[1], -1.5 * 0.020, 1e-12);
  EXPECT_NEAR(values[2], kRho0 * 9.81 * (0.03 - 0.010), 1e-9);
}

TEST(MovingProbe, APlacedFreeSurfaceLineStaysVerticalAndFindsTheSurfaceBesideIt) {
  // Water only over x in [0, 0.02]: the line at x = 0.03 is dry until the body carries it in.
  const Particles block = water_block(0.0, 0.02, 0.02);
  ProbeSet set({free_surface_probe("gauge", {0.03, 0.0, 0.0}, 0.05, 201)}, {2, kGravity, kSpacing});
  EXPECT_EQ(set.values(set.partials(block.set(), spiky2d(kSmoothing)))[1], 0.0);
  RigidPlacement placement;
  placement.translation = {-0.02, 0.0, 0.0};
  set.move(0, placed(set.probes()[0], placement).parameters);
  const auto values = set.values(set.partials(block.set(), spiky2d(kSmoothing)));
  EXPECT_NEAR(values[0], 0.02, 0.25 * kSpacing);
  EXPECT_EQ(values[1], 1.0);
}

TEST(MovingProbe, AMoveThatDoesNotFitIsRefusedAndTheProbeStaysWhereItWas) {
  ProbeSet set({point_probe("p", {0.01, 0.01, 0.0}), fluid_energy_probe("e", {})},
               {2, kGravity, kSpacing});
  EXPECT_THROW(set.move(0, {0.01, 0.01}), Error);               // too few numbers
  EXPECT_THROW(set.move(0, {0.01, std::nan(""), 0.0}), Error);  // not finite
  EXPECT_THROW(set.move(1, {0.0, 0.0, 0.0}), Error);            // cannot move
  EXPECT_THROW(set.move(2, {0.0, 0.0, 0.0}), Error);            // no such probe
  EXPECT_EQ(set.probes()[0].parameters, (std::vector<double>{0.01, 0.01, 0.0}));
}

}  // namespace
}  // namespace fsi::probes
