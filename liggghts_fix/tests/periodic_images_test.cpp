#include "fsi/contact/periodic_images.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "contact_test_support.hpp"
#include "fsi/contact/wall_contact.hpp"

namespace fsi::contact {
namespace {

using Particles = test_support::ParticleCloud;

constexpr double kCutoff = 0.01;
constexpr double kPeriod = 0.1;

ContactSettings settings() {
  ContactSettings s;
  s.law = test_support::adhesive_law(kCutoff, 0.5);
  s.gauss_points = 3;
  s.refinement_resolution = kCutoff;
  return s;
}

// A straight wall along y = 0 made of `periods` segments of one period each, starting at x0.
BoundaryMesh2D wall(double x0, int periods, double wall_speed = 0.0) {
  BoundaryMesh2D mesh;
  for (int p = 0; p <= periods; ++p) {
    mesh.positions.insert(mesh.positions.end(), {x0 + p * kPeriod, 0.0});
    mesh.velocities.insert(mesh.velocities.end(), {wall_speed, 0.0});
  }
  for (int p = 0; p < periods; ++p)
    mesh.segments.insert(mesh.segments.end(),
                         {static_cast<std::uint32_t>(p), static_cast<std::uint32_t>(p + 1)});
  return mesh;
}

Periodicity periodic_x() {
  Periodicity box;
  box.dimension = 2;
  box.periodic = {true, false, true};  // z as LIGGGHTS' 2D runs have it: ignored
  box.low = {0.0, -0.05, -0.001};
  box.high = {kPeriod, 0.05, 0.001};
  return box;
}

// Forces on the particles of `cloud` from `mesh`, through the images of `box`; returns the sum
// of the vertex forces.
std::array<double, 2> evaluate_periodic(const BoundaryMesh2D& mesh, Particles& cloud,
                                        const Periodicity& box, std::size_t* images = nullptr) {
  WallContact2D contact(settings());
  PeriodicImages periodic;
  const ParticleArrays particles = cloud.arrays();
  const ParticleArrays extended =
      periodic.extend(particles, box, mesh.positions, settings().law.range());
  std::vector<double> vertex_forces(mesh.positions.size());
  contact.compute(mesh, extended, vertex_forces);
  periodic.fold_forces(particles);
  if (images) *images = periodic.image_count();
  std::array<double, 2> total{};
  for (std::size_t v = 0; v < vertex_forces.size(); v += 2) {
    total[0] += vertex_forces[v];
    total[1] += vertex_forces[v + 1];
  }
  return total;
}

// A particle close to the periodic boundary feels, through its image, exactly the wall that a
// mesh three periods long (the period and its two neighbours, the same segments) gives it.
TEST(PeriodicImages, ParticleNearTheBoundaryFeelsTheWallBeyondIt) {
  for (const double x : {0.2 * kCutoff, kPeriod - 0.3 * kCutoff, 0.5 * kPeriod}) {
    Particles periodic;
    periodic.add(x, 0.4 * kCutoff, 0.3, -0.1);
    const BoundaryMesh2D one_period = wall(0.0, 1, 0.05);
    evaluate_periodic(one_period, periodic, periodic_x());

    Particles reference;
    reference.add(x, 0.4 * kCutoff, 0.3, -0.1);
    WallContact2D contact(settings());
    const BoundaryMesh2D three_periods = wall(-kPeriod, 3, 0.05);
    std::vector<double> vertex_forces(three_periods.positions.size());
    contact.compute(three_periods, reference.arrays(), vertex_forces);

    for (int k = 0; k < 2; ++k)
      EXPECT_NEAR(periodic.f[k], reference.f[k], 1e-12 * std::abs(reference.f[1])) << "x = " << x;
    EXPECT_GT(std::abs(periodic.f[0]), 0.0);  // the friction of the moving wall acts along x
  }
}

// Without the images the particle at the boundary misses the half of the wall beyond it.
TEST(PeriodicImages, WithoutImagesTheBoundaryParticleFeelsHalfAWall) {
  Particles alone;
  alone.add(0.0, 0.4 * kCutoff);
  WallContact2D contact(settings());
  const BoundaryMesh2D one_period = wall(0.0, 1);
  std::vector<double> vertex_forces(one_period.positions.size());
  contact.compute(one_period, alone.arrays(), vertex_forces);

  Particles periodic;
  periodic.add(0.0, 0.4 * kCutoff);
  evaluate_periodic(one_period, periodic, periodic_x());
  EXPECT_NEAR(alone.f[1], 0.5 * periodic.f[1], 1e-9 * std::abs(periodic.f[1]));
}

// Action equals reaction with the images: the vertex forces sum to minus the particle forces.
TEST(PeriodicImages, VertexForcesBalanceTheParticleForces) {
  Particles cloud;
  for (int i = 0; i < 40; ++i)
    cloud.add(kPeriod * (i + 0.37) / 40.0, kCutoff * (0.2 + 0.02 * (i % 7)), 0.01 * (i % 5), 0.0);
  const auto structure = evaluate_periodic(wall(0.0, 1, -0.02), cloud, periodic_x());
  double fluid[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < cloud.count(); ++i) {
    fluid[0] += cloud.f[3 * i];
    fluid[1] += cloud.f[3 * i + 1];
  }
  for (int k = 0; k < 2; ++k)
    EXPECT_NEAR(structure[k], -fluid[k], 1e-12 * std::abs(fluid[1]));
}

// Only particles that come within range of the mesh through a shift get an image; a particle
// outside the group gets none.
TEST(PeriodicImages, ImagesOnlyWhereTheyReachTheMesh) {
  Particles cloud;
  cloud.add(0.5 * kCutoff, 0.5 * kCutoff);            // near x = 0: image at x + P
  cloud.add(kPeriod - 0.5 * kCutoff, 0.5 * kCutoff);  // near x = P: image at x - P
  cloud.add(0.5 * kPeriod, 0.5 * kCutoff);            // middle: none
  cloud.add(0.5 * kCutoff, 0.5 * kCutoff);
  cloud.mask[3] = 0;  // not in the group: none
  std::size_t images = 0;
  evaluate_periodic(wall(0.0, 1), cloud, periodic_x(), &images);
  EXPECT_EQ(images, 2u);
}

// Periodic along x and y: a particle in a corner gets the images across both boundaries and
// across the corner (mesh: a closed square around the whole period).
TEST(PeriodicImages, CornerParticleGetsThreeImages) {
  BoundaryMesh2D square;
  square.positions = {0.0, 0.0, kPeriod, 0.0, kPeriod, kPeriod, 0.0, kPeriod};
  square.velocities.assign(8, 0.0);
  square.segments = {0, 1, 1, 2, 2, 3, 3, 0};
  Periodicity box = periodic_x();
  box.periodic[1] = true;
  box.low[1] = 0.0;
  box.high[1] = kPeriod;
  Particles cloud;
  cloud.add(0.3 * kCutoff, 0.3 * kCutoff);
  std::size_t images = 0;
  evaluate_periodic(square, cloud, box, &images);
  EXPECT_EQ(images, 3u);
}

TEST(PeriodicImages, MeshLongerThanThePeriodIsRefused) {
  const Periodicity box = periodic_x();
  EXPECT_NO_THROW(check_periodic_mesh(box, wall(0.0, 1).positions, kCutoff));
  try {
    check_periodic_mesh(box, wall(-kPeriod, 3).positions, kCutoff);
    FAIL() << "a wall three periods long was accepted";
  } catch (const std::invalid_argument& refused) {
    const std::string text = refused.what();
    EXPECT_NE(text.find("periodic along x"), std::string::npos) << text;
    EXPECT_NE(text.find("draw each wall once per period"), std::string::npos) << text;
  }
  // Not periodic: any length.
  Periodicity closed = box;
  closed.periodic = {false, false, true};
  EXPECT_NO_THROW(check_periodic_mesh(closed, wall(-kPeriod, 3).positions, kCutoff));
}

TEST(PeriodicImages, RangeOfHalfAPeriodIsRefused) {
  EXPECT_THROW(check_periodic_mesh(periodic_x(), wall(0.0, 1).positions, 0.5 * kPeriod),
               std::invalid_argument);
}

}  // namespace
}  // namespace fsi::contact
