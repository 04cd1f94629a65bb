#include "fsi/contact/wall_contact.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "contact_test_support.hpp"

namespace fsi::contact {
namespace {

using Particles = test_support::ParticleCloud;

ContactSettings settings(double cutoff = 0.01, double viscous = 0.5) {
  ContactSettings s;
  s.law = test_support::adhesive_law(cutoff, viscous);
  s.gauss_points = 3;
  s.refinement_resolution = 2.0 * cutoff;
  return s;
}

// A closed, moving, rotating polygon with some long and some short segments.
BoundaryMesh2D random_mesh(std::mt19937& rng, int vertices) {
  std::uniform_real_distribution<double> radius(0.03, 0.08), speed(-0.3, 0.3);
  BoundaryMesh2D mesh;
  for (int i = 0; i < vertices; ++i) {
    const double angle = 2.0 * M_PI * i / vertices;
    const double r = radius(rng);
    mesh.positions.insert(mesh.positions.end(), {r * std::cos(angle), r * std::sin(angle)});
    mesh.velocities.insert(mesh.velocities.end(), {speed(rng), speed(rng)});
    mesh.segments.insert(mesh.segments.end(), {static_cast<std::uint32_t>(i),
                                               static_cast<std::uint32_t>((i + 1) % vertices)});
  }
  return mesh;
}

Particles random_particles(std::mt19937& rng, int count, double extent) {
  std::uniform_real_distribution<double> position(-extent, extent), speed(-1.0, 1.0);
  Particles p;
  for (int i = 0; i < count; ++i)
    p.add(position(rng), position(rng), speed(rng), speed(rng));
  return p;
}

TEST(BisectionLevels, PiecesEndShorterThanTheResolution) {
  EXPECT_EQ(bisection_levels(0.2, 0.3), 0);
  EXPECT_EQ(bisection_levels(0.3, 0.3), 1);  // "shorter than", not "at most"
  EXPECT_EQ(bisection_levels(1.0, 0.3), 2);
  EXPECT_EQ(bisection_levels(1.0, 0.25), 3);
  EXPECT_EQ(bisection_levels(0.0, 0.1), 0);
}

TEST(WallContact, ForcesOnStructureBalanceForcesOnParticles) {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 20; ++trial) {
    BoundaryMesh2D mesh = random_mesh(rng, 5 + trial);
    Particles p = random_particles(rng, 2000, 0.09);
    std::vector<double> vertex_forces(mesh.positions.size());
    WallContact2D contact(settings());
    const auto diagnostics = contact.compute(mesh, p.arrays(), vertex_forces);
    ASSERT_GT(diagnostics.pair_count, 100u);
    double on_particles[2] = {0, 0}, on_structure[2] = {0, 0};
    for (std::size_t i = 0; i < p.x.size(); i += 3) {
      on_particles[0] += p.f[i];
      on_particles[1] += p.f[i + 1];
    }
    for (std::size_t k = 0; k < vertex_forces.size(); k += 2) {
      on_structure[0] += vertex_forces[k];
      on_structure[1] += vertex_forces[k + 1];
    }
    const double scale = diagnostics.pair_force_magnitude_sum;
    for (int k = 0; k < 2; ++k) {
      EXPECT_LE(std::abs(on_particles[k] + on_structure[k]), 1e-12 * scale) << "trial " << trial;
      EXPECT_NEAR(diagnostics.force_on_particles[k], on_particles[k], 1e-12 * scale);
      EXPECT_NEAR(diagnostics.force_on_structure[k], on_structure[k], 1e-12 * scale);
    }
  }
}

TEST(WallContact, MomentsBalanceForCentralForces) {
  // Without friction every pair force is central, so its moment about the origin is the same at
  // the particle and at the sampling point; the redistribution (4.11) must keep that moment.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    BoundaryMesh2D mesh = random_mesh(rng, 7);
    Particles p = random_particles(rng, 2000, 0.09);
    std::vector<double> vertex_forces(mesh.positions.size());
    WallContact2D contact(settings(0.01, 0.0));
    contact.compute(mesh, p.arrays(), vertex_forces);
    double moment_particles = 0.0, moment_structure = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < p.x.size(); i += 3) {
      moment_particles += p.x[i] * p.f[i + 1] - p.x[i + 1] * p.f[i];
      scale += std::hypot(p.x[i], p.x[i + 1]) * std::hypot(p.f[i], p.f[i + 1]);
    }
    for (std::size_t k = 0; k < vertex_forces.size(); k += 2) {
      moment_structure +=
          mesh.positions[k] * vertex_forces[k + 1] - mesh.positions[k + 1] * vertex_forces[k];
    }
    ASSERT_GT(scale, 0.0);
    EXPECT_LE(std::abs(moment_particles + moment_structure), 1e-12 * scale) << "trial " << trial;
  }
}

TEST(WallContact, RedistributesToVerticesByLinearWeighting) {
  // One Gauss point at g = 1/2 on an unrefined segment: each vertex takes half the counterforce.
  ContactSettings s = settings(1.0, 0.0);
  s.gauss_points = 1;
  s.refinement_resolution = 10.0;
  BoundaryMesh2D mesh{{0.0, 0.0, 1.0, 0.0}, {0.0, 0.0, 0.0, 0.0}, {0, 1}};
  Particles p;
  p.add(0.5, 0.25);
  std::vector<double> vertex_forces(4);
  WallContact2D(s).compute(mesh, p.arrays(), vertex_forces);
  const double expected = s.law.repulsion(0.25) * 1.0;  // length 1, weight 1
  EXPECT_NEAR(p.f[1], expected, 1e-12 * expected);
  EXPECT_NEAR(vertex_forces[1], -0.5 * expected, 1e-12 * expected);
  EXPECT_NEAR(vertex_forces[3], -0.5 * expected, 1e-12 * expected);
  EXPECT_NEAR(vertex_forces[0], 0.0, 1e-15);
}

void expect_same_forces(const std::vector<double>& a, const std::vector<double>& b, double scale,
                        const char* what) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_LE(std::abs(a[k] - b[k]), 1e-12 * scale) << what << " value " << k;
  }
}

TEST(WallContact, CellListEqualsAllPairs) {
  std::mt19937 rng(1234);
  const ContactSettings s = settings();
  for (int trial = 0; trial < 20; ++trial) {
    BoundaryMesh2D mesh = random_mesh(rng, 4 + trial % 7);
    Particles p = random_particles(rng, 1500, 0.1);
    // Particles exactly on cell borders of the grid (multiples of the cut-off from the lowest
    // particle) and far beyond the cut-off of every sampling point.
    const double low_x = *std::min_element(p.x.begin(), p.x.end());
    for (int k = -8; k <= 8; ++k)
      p.add(low_x + k * s.law.cutoff, 0.05, 0.1, 0.0);
    p.add(5.0, 5.0);
    p.add(-3.0, 0.0);
    Particles q = p;
    std::vector<double> grid_vertex(mesh.positions.size()), pairs_vertex(mesh.positions.size());
    WallContact2D contact(s);
    const auto with_grid = contact.compute(mesh, p.arrays(), grid_vertex);
    const auto all_pairs = compute_all_pairs(s, mesh, q.arrays(), pairs_vertex);
    ASSERT_EQ(with_grid.pair_count, all_pairs.pair_count) << "trial " << trial;
    ASSERT_EQ(with_grid.particles_in_range, all_pairs.particles_in_range);
    ASSERT_GT(with_grid.pair_count, 0u);
    double scale = 0.0;
    for (double value : q.f)
      scale = std::max(scale, std::abs(value));
    expect_same_forces(p.f, q.f, scale, "particle force");
    expect_same_forces(grid_vertex, pairs_vertex, scale, "vertex force");
    EXPECT_EQ(with_grid.closest_distance, all_pairs.closest_distance);
  }
}

// The closest approach is over every element a particle pairs with, not only the first: in the
// corner of an L two particles each pair with both legs, one nearer the first leg (4 mm against
// 5 mm), the other nearer the second (3 mm against 6 mm); each counts once among the particles in
// range.
TEST(WallContact, ClosestDistanceIsToTheNearestOfEveryElementAParticlePairsWith) {
  BoundaryMesh2D mesh;
  mesh.positions = {0.0, 0.0, 0.1, 0.0, 0.1, 0.1};
  mesh.velocities.assign(6, 0.0);
  mesh.segments = {0, 1, 1, 2};
  Particles p;
  p.add(0.095, 0.004);
  p.add(0.097, 0.006);
  std::vector<double> vertex_forces(mesh.positions.size());
  WallContact2D contact(settings(0.01));
  const ContactDiagnostics d = contact.compute(mesh, p.arrays(), vertex_forces);
  EXPECT_NEAR(d.closest_distance, 0.003, 1e-15);
  EXPECT_EQ(d.particles_in_range, 2u);
  EXPECT_GT(d.pair_count, 4u);  // several sampling points of each leg per particle
}

// A rank samples only the pieces of the wall within the range of its particles (thesis §7.1):
// a floor 1 m long whose water sits over its left tenth generates the sampling points of little
// more than that tenth, with the forces of the evaluation that samples everything.
TEST(WallContact, SamplesOnlyThePiecesWithinReachOfTheParticles) {
  const ContactSettings s = settings();
  const BoundaryMesh2D floor{{0.0, 0.0, 1.0, 0.0}, {0.0, 0.0, 0.0, 0.0}, {0, 1}};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(0.0, 0.1), y(0.001, 0.012), speed(-0.5, 0.5);
  Particles p;
  for (int i = 0; i < 400; ++i)
    p.add(x(rng), y(rng), speed(rng), speed(rng));
  Particles q = p;
  std::vector<double> share(4), reference(4);
  const auto d = WallContact2D(s).compute(floor, p.arrays(), share);
  WallSampleRecord record;
  record.enabled = true;
  const auto full = WallContact2D(s).compute(floor, q.arrays(), reference, &record);
  ASSERT_GT(d.pair_count, 500u);
  EXPECT_EQ(d.sampling_points, full.sampling_points);
  EXPECT_EQ(full.sampling_points_skipped, 0u);
  const double fraction = static_cast<double>(d.sampling_points - d.sampling_points_skipped) /
                          static_cast<double>(d.sampling_points);
  EXPECT_GT(fraction, 0.1);
  EXPECT_LT(fraction, 0.13);  // 0.1 m of water, the cut-off 0.01 m and one 0.0156 m piece
  EXPECT_EQ(share, reference);
  EXPECT_EQ(p.f, q.f);
  EXPECT_EQ(d.pair_count, full.pair_count);
}

TEST(WallContact, CellListHandlesDegenerateParticleClouds) {
  const ContactSettings s = settings();
  BoundaryMesh2D mesh{{-0.05, 0.0, 0.05, 0.0}, {0.0, 0.0, 0.0, 0.0}, {0, 1}};
  for (const auto& cloud : std::vector<std::vector<std::pair<double, double>>>{
           {},                               // no particles
           {{0.0, 0.005}},                   // one particle
           {{0.0, 0.005}, {0.0, 0.005}},     // two at the same place
           {{-0.01, 0.002}, {0.02, 0.002}},  // all on one line (zero extent in y)
           {{0.0, 0.005}, {1e9, 0.005}}}) {  // a stray particle very far away
    Particles p, q;
    for (auto [x, y] : cloud) {
      p.add(x, y);
      q.add(x, y);
    }
    std::vector<double> a(4), b(4);
    WallContact2D contact(s);
    const auto with_grid = contact.compute(mesh, p.arrays(), a);
    const auto all_pairs = compute_all_pairs(s, mesh, q.arrays(), b);
    EXPECT_EQ(with_grid.pair_count, all_pairs.pair_count) << cloud.size() << " particles";
    expect_same_forces(a, b, 1000.0, "vertex force");
  }
}

TEST(WallContact, OnlyParticlesOfTheGroupTakePart) {
  BoundaryMesh2D mesh{{-0.05, 0.0, 0.05, 0.0}, {0.0, 0.0, 0.0, 0.0}, {0, 1}};
  Particles p;
  p.add(0.0, 0.004);
  p.add(0.01, 0.004);
  p.mask[1] = 2;  // not in group bit 1
  std::vector<double> vertex_forces(4);
  const auto diagnostics = WallContact2D(settings()).compute(mesh, p.arrays(), vertex_forces);
  EXPECT_GT(p.f[1], 0.0);
  EXPECT_EQ(p.f[4], 0.0);
  EXPECT_EQ(diagnostics.particles_in_range, 1u);
}

double exact_wall_repulsion(const ForceLaw& law, double d) {
  return test_support::exact_wall_repulsion(law, d, 15, 1e-14);
}

double discrete_wall_force(const ContactSettings& s, double d, double* tangential, double speed) {
  const double half_length = 50.0 * s.law.cutoff;
  BoundaryMesh2D mesh{{-half_length, 0.0, half_length, 0.0}, {0.0, 0.0, 0.0, 0.0}, {0, 1}};
  Particles p;
  p.add(0.0123 * s.law.cutoff, d, speed, 0.0);  // off-centre: not symmetric to the sampling
  std::vector<double> vertex_forces(4);
  WallContact2D(s).compute(mesh, p.arrays(), vertex_forces);
  if (tangential) *tangential = p.f[0];
  return p.f[1];
}

// Measured convergence (d/rc = 0.05 ... 0.95, 3 Gauss points): the error is not monotone in the
// resolution because the sampling points move relative to the particle, but at pieces of rc/32
// the repulsion is within 3e-8 and the friction, whose density has a kink at the cut-off, within
// 2e-4 of the exact integrals.
TEST(WallContact, ConvergesToExactIntegralOverStraightWall) {
  ContactSettings s = settings(0.002, 3.0);
  s.law.equilibrium_distance = s.law.cutoff;  // thesis static test: no adhesion
  s.refinement_resolution = s.law.cutoff / 32.0;
  const double speed = 0.1;
  for (double fraction : {0.05, 0.25, 0.5, 0.75, 0.95}) {
    const double d = fraction * s.law.cutoff;
    const double reach = std::sqrt(s.law.cutoff * s.law.cutoff - d * d);
    const double exact_normal = exact_wall_repulsion(s.law, d);
    const double exact_tangential =
        -s.law.viscous_scale * speed *
        boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
            [&](double x) { return s.law.viscous_weight(std::hypot(d, x)); }, -reach, reach, 15,
            1e-14);
    double tangential = 0.0;
    const double normal = discrete_wall_force(s, d, &tangential, speed);
    EXPECT_NEAR(normal, exact_normal, 1e-7 * exact_normal) << "d/rc = " << fraction;
    EXPECT_LT(tangential, 0.0);
    EXPECT_NEAR(tangential, exact_tangential, 2e-4 * std::abs(exact_tangential))
        << "d/rc = " << fraction;
  }
}

TEST(WallContact, RejectsInconsistentInput) {
  BoundaryMesh2D mesh{{0.0, 0.0, 1.0, 0.0}, {0.0, 0.0, 0.0, 0.0}, {0, 2}};
  EXPECT_THROW(mesh.validate(), std::invalid_argument);
  mesh.segments = {0, 1};
  EXPECT_NO_THROW(mesh.validate());
  Particles p;
  std::vector<double> too_small(2);
  WallContact2D contact(settings());
  EXPECT_THROW(contact.compute(mesh, p.arrays(), too_small), std::invalid_argument);
  ContactSettings bad = settings();
  bad.refinement_resolution = 0.0;
  EXPECT_THROW(WallContact2D{bad}, std::invalid_argument);
}

// The wall-pressure probes read the force at every sampling point: those forces are the
// structure's share of every pair, so they sum to the vertex forces' total; every sample lies on
// its segment with the segment's unit normal, and the samples of a segment measure its length.
TEST(WallContact, RecordedSampleForcesSumToTheForceOnTheStructure) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    BoundaryMesh2D mesh = random_mesh(rng, 6 + trial);
    Particles p = random_particles(rng, 2000, 0.09);
    std::vector<double> plain_forces(mesh.positions.size()), vertex_forces(plain_forces.size());
    WallContact2D plain(settings()), recording(settings());
    const auto plain_diagnostics = plain.compute(mesh, p.arrays(), plain_forces);
    p.clear_forces();
    WallSampleRecord samples;
    samples.enabled = true;
    const auto diagnostics = recording.compute(mesh, p.arrays(), vertex_forces, &samples);
    EXPECT_EQ(vertex_forces, plain_forces) << "recording changes no force";
    EXPECT_EQ(diagnostics.pair_count, plain_diagnostics.pair_count);
    ASSERT_EQ(samples.count(), diagnostics.sampling_points);
    ASSERT_EQ(samples.dimension, 2);
    double total[2] = {0.0, 0.0};
    std::size_t pairs = 0;
    std::vector<double> length_of_samples(mesh.segment_count(), 0.0);
    for (std::size_t s = 0; s < samples.count(); ++s) {
      total[0] += samples.forces[2 * s];
      total[1] += samples.forces[2 * s + 1];
      pairs += samples.pairs[s];
      const std::uint32_t segment = samples.elements[s];
      ASSERT_LT(segment, mesh.segment_count());
      length_of_samples[segment] += samples.measures[s];
      const double* a = &mesh.positions[2 * mesh.segments[2 * segment]];
      const double* b = &mesh.positions[2 * mesh.segments[2 * segment + 1]];
      const double along[2] = {b[0] - a[0], b[1] - a[1]};
      const double length = std::hypot(along[0], along[1]);
      const double* n = &samples.normals[2 * s];
      EXPECT_NEAR(n[0], along[1] / length, 1e-14);
      EXPECT_NEAR(n[1], -along[0] / length, 1e-14);
      const double* x = &samples.positions[2 * s];
      EXPECT_NEAR((x[0] - a[0]) * n[0] + (x[1] - a[1]) * n[1], 0.0, 1e-14) << "on the segment";
    }
    const double scale = diagnostics.pair_force_magnitude_sum;
    for (int k = 0; k < 2; ++k)
      EXPECT_NEAR(total[k], diagnostics.force_on_structure[k], 1e-12 * scale) << "trial " << trial;
    EXPECT_EQ(pairs, diagnostics.pair_count);
    for (std::size_t e = 0; e < mesh.segment_count(); ++e) {
      const double* a = &mesh.positions[2 * mesh.segments[2 * e]];
      const double* b = &mesh.positions[2 * mesh.segments[2 * e + 1]];
      EXPECT_NEAR(length_of_samples[e], std::hypot(b[0] - a[0], b[1] - a[1]), 1e-14);
    }
    // A record that is not enabled stays empty.
    WallSampleRecord off;
    p.clear_forces();
    recording.compute(mesh, p.arrays(), vertex_forces, &off);
    EXPECT_EQ(off.count(), 0u);
  }
}

}  // namespace
}  // namespace fsi::contact
