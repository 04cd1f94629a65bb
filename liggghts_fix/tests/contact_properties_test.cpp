// Properties of the 2D SPH–wall contact the thesis states or implies (ch. 4): no holes at the
// recommended element length, convergence to the exact wall integral, invariance under rigid
// motions and element order, decomposition over ranks, and safe behaviour on degenerate input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_test_support.hpp"
#include "fsi/contact/wall_contact.hpp"

namespace fsi::contact {
namespace {

using Cloud = test_support::ParticleCloud;

double largest_magnitude(const std::vector<double>& values) {
  double m = 0.0;
  for (double value : values)
    m = std::max(m, std::abs(value));
  return m;
}

// Thesis Figs 4.5–4.8: k = 1000, r0 = 2h, 3 Gauss points, one unrefined segment of length l.
// Lengths are in units of h (h = 1, cut-off 2h = 2), so |F| = sum l w f is in units of k h and the
// thesis' criterion "a closed iso-line at 0.2 k" reads min over crossing paths of max |F| >= 0.2 k
// h. Every path perpendicular to the segment through a crossing point x in [0, l] is sampled; the
// particles do not interact with each other in the fix, so all path points go into one cloud.
double weakest_crossing_path(double length) {
  ContactSettings s;
  s.law.repulsion_scale = 1000.0;
  s.law.cutoff = 2.0;
  s.law.equilibrium_distance = 2.0;
  s.gauss_points = 3;
  s.refinement_resolution = 2.0 * length;  // no bisection: the segment as it is
  BoundaryMesh2D mesh{{0.0, 0.0, length, 0.0}, {0.0, 0.0, 0.0, 0.0}, {0, 1}};
  constexpr int kCrossings = 201;
  constexpr int kHeights = 1000;  // the field is symmetric: heights on one side suffice
  Cloud cloud;
  for (int i = 0; i < kCrossings; ++i)
    for (int j = 1; j <= kHeights; ++j)
      cloud.add(length * i / (kCrossings - 1), 2.0 * j / kHeights);
  std::vector<double> vertex_forces(4);
  WallContact2D(s).compute(mesh, cloud.arrays(), vertex_forces);
  double weakest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kCrossings; ++i) {
    double strongest = 0.0;
    for (int j = 0; j < kHeights; ++j) {
      const std::size_t p = static_cast<std::size_t>(i * kHeights + j);
      strongest = std::max(strongest, std::hypot(cloud.f[3 * p], cloud.f[3 * p + 1]));
    }
    weakest = std::min(weakest, strongest);
  }
  return weakest;
}

TEST(ContactProperties, NoHolesAtTheThesisElementLength) {
  // Measured: l = 2h: 287 k h/1000; l = 4h: 131; l = 8h: 3.4 (a hole midway between Gauss points).
  const double threshold = 0.2 * 1000.0;
  const double at_2h = weakest_crossing_path(2.0);
  EXPECT_GE(at_2h, threshold) << "l = 2h leaves a hole: weakest path meets |F| = " << at_2h;
  const double at_8h = weakest_crossing_path(8.0);
  EXPECT_LT(at_8h, threshold) << "l/(2h) = 4 should leave a hole, weakest path " << at_8h;
  EXPECT_LT(at_8h, 0.05 * threshold);
  RecordProperty("weakest_path_l_2h", std::to_string(at_2h));
  RecordProperty("weakest_path_l_8h", std::to_string(at_8h));
}

// Exact normal force of an infinite straight wall at distance d, by adaptive Gauss–Kronrod.
double exact_wall_force(const ForceLaw& law, double d) {
  return test_support::exact_wall_repulsion(law, d, 12, 1e-13);
}

// Largest relative error of the repulsive wall force over d in [0.05, 0.75] r_c and particle
// positions along the wall (the sampling points move relative to the particle).
double wall_force_error(int gauss_points, double resolution_over_cutoff) {
  ContactSettings s;
  s.law.repulsion_scale = 1000.0;
  s.law.cutoff = 1.0;
  s.law.equilibrium_distance = 1.0;
  s.gauss_points = gauss_points;
  s.refinement_resolution = resolution_over_cutoff;
  BoundaryMesh2D mesh{{-50.0, 0.0, 50.0, 0.0}, {0.0, 0.0, 0.0, 0.0}, {0, 1}};
  std::vector<double> distances;
  for (int k = 0; k <= 70; ++k)
    distances.push_back(0.05 + 0.01 * k);
  Cloud cloud;
  for (double d : distances)
    for (int offset = 0; offset < 50; ++offset)
      cloud.add(0.02 * offset, d);
  std::vector<double> vertex_forces(4);
  WallContact2D(s).compute(mesh, cloud.arrays(), vertex_forces);
  static const std::vector<double> exact_forces = [&] {
    std::vector<double> values;
    for (double d : distances)
      values.push_back(exact_wall_force(s.law, d));
    return values;
  }();
  double worst = 0.0;
  for (std::size_t k = 0; k < distances.size(); ++k) {
    const double exact = exact_forces[k];
    for (std::size_t offset = 0; offset < 50; ++offset) {
      const std::size_t p = 50 * k + offset;
      worst = std::max(worst, std::abs(cloud.f[3 * p + 1] - exact) / exact);
    }
  }
  return worst;
}

TEST(ContactProperties, ConvergesToTheExactWallIntegral) {
  // Measured relative errors, 3 Gauss points, resolution r_c ... r_c/32:
  //   8.2e-1, 2.1e-1, 2.7e-2, 1.3e-3, 2.2e-5, 2.5e-8  (5 points: 3.4e-1 ... 3.4e-11).
  // The thesis' l ~ 2h = r_c avoids holes but is far from the integral; 1e-3 needs r_c/16 with
  // 3 points or r_c/8 with 5 (docs/fix_fsi_sph.md, "Accuracy").
  for (int points : {3, 5}) {
    double previous = std::numeric_limits<double>::infinity();
    for (double resolution : {1.0, 0.5, 0.25, 0.125, 0.0625, 0.03125}) {
      const double error = wall_force_error(points, resolution);
      EXPECT_LT(error, 0.5 * previous) << points << " points, resolution r_c*" << resolution;
      previous = error;
      RecordProperty("error_g" + std::to_string(points) + "_res" + std::to_string(resolution),
                     std::to_string(error));
    }
  }
  EXPECT_LE(wall_force_error(3, 1.0 / 16.0), 1e-3);
  EXPECT_LE(wall_force_error(5, 1.0 / 8.0), 1e-3);
}

// A closed polygon with long and short segments, moving, and particles around and across it.
struct Scene {
  BoundaryMesh2D mesh;
  Cloud cloud;
};

Scene random_scene(std::mt19937& rng) {
  std::uniform_real_distribution<double> radius(0.03, 0.08), speed(-0.3, 0.3), place(-0.1, 0.1);
  Scene scene;
  const int vertices = 9;
  for (int i = 0; i < vertices; ++i) {
    const double angle = 2.0 * M_PI * i / vertices;
    const double r = radius(rng);
    scene.mesh.positions.insert(scene.mesh.positions.end(),
                                {r * std::cos(angle), r * std::sin(angle)});
    scene.mesh.velocities.insert(scene.mesh.velocities.end(), {speed(rng), speed(rng)});
    scene.mesh.segments.insert(
        scene.mesh.segments.end(),
        {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>((i + 1) % vertices)});
  }
  for (int i = 0; i < 3000; ++i)
    scene.cloud.add(place(rng), place(rng), speed(rng), speed(rng));
  return scene;
}

ContactSettings scene_settings() {
  ContactSettings s;
  s.law.repulsion_scale = 1000.0;
  s.law.viscous_scale = 0.7;
  s.law.cutoff = 0.01;
  s.law.equilibrium_distance = 0.008;
  s.gauss_points = 3;
  s.refinement_resolution = 0.01;
  return s;
}

TEST(ContactProperties, InvariantUnderRigidMotion) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI), shift(-0.1, 0.1);
  for (int trial = 0; trial < 5; ++trial) {
    Scene a = random_scene(rng);
    Scene b = a;
    const double phi = angle(rng), c = std::cos(phi), s = std::sin(phi);
    const double tx = shift(rng), ty = shift(rng);
    auto rotate = [&](double* p, bool translate) {
      const double x = p[0], y = p[1];
      p[0] = c * x - s * y + (translate ? tx : 0.0);
      p[1] = s * x + c * y + (translate ? ty : 0.0);
    };
    for (std::size_t k = 0; k < b.mesh.positions.size(); k += 2) {
      rotate(&b.mesh.positions[k], true);
      rotate(&b.mesh.velocities[k], false);
    }
    for (std::size_t k = 0; k < b.cloud.x.size(); k += 3) {
      rotate(&b.cloud.x[k], true);
      rotate(&b.cloud.v[k], false);
    }
    std::vector<double> fa(a.mesh.positions.size()), fb(fa.size());
    const auto da = WallContact2D(scene_settings()).compute(a.mesh, a.cloud.arrays(), fa);
    const auto db = WallContact2D(scene_settings()).compute(b.mesh, b.cloud.arrays(), fb);
    ASSERT_GT(da.pair_count, 1000u);
    EXPECT_EQ(da.pair_count, db.pair_count);
    // Shifts up to 10 cut-offs: coordinates keep their digits, the bound is 1e-12 as stated.
    // (Far larger shifts lose digits of the particle–wall distances to round-off: at 5 m, i.e.
    // 500 cut-offs, the difference reaches 2e-12 of the largest force, measured.)
    const double scale = largest_magnitude(a.cloud.f) * 1e-12;
    for (std::size_t k = 0; k < fa.size(); k += 2) {
      rotate(&fa[k], false);
      EXPECT_NEAR(fa[k], fb[k], scale) << "vertex " << k / 2;
      EXPECT_NEAR(fa[k + 1], fb[k + 1], scale) << "vertex " << k / 2;
    }
    for (std::size_t k = 0; k < a.cloud.f.size(); k += 3) {
      rotate(&a.cloud.f[k], false);
      ASSERT_NEAR(a.cloud.f[k], b.cloud.f[k], scale) << "particle " << k / 3;
      ASSERT_NEAR(a.cloud.f[k + 1], b.cloud.f[k + 1], scale) << "particle " << k / 3;
    }
  }
}

TEST(ContactProperties, InvariantUnderRotationAboutTheOriginToRoundOff) {
  // Without the large translation the 1e-12 relative bound holds as stated.
  std::mt19937 rng(5);
  Scene a = random_scene(rng);
  Scene b = a;
  const double c = std::cos(0.7), s = std::sin(0.7);
  auto rotate = [&](double* p) {
    const double x = p[0], y = p[1];
    p[0] = c * x - s * y;
    p[1] = s * x + c * y;
  };
  for (std::size_t k = 0; k < b.mesh.positions.size(); k += 2) {
    rotate(&b.mesh.positions[k]);
    rotate(&b.mesh.velocities[k]);
  }
  for (std::size_t k = 0; k < b.cloud.x.size(); k += 3) {
    rotate(&b.cloud.x[k]);
    rotate(&b.cloud.v[k]);
  }
  std::vector<double> fa(a.mesh.positions.size()), fb(fa.size());
  WallContact2D(scene_settings()).compute(a.mesh, a.cloud.arrays(), fa);
  WallContact2D(scene_settings()).compute(b.mesh, b.cloud.arrays(), fb);
  const double scale = 1e-12 * largest_magnitude(fa);
  for (std::size_t k = 0; k < fa.size(); k += 2) {
    rotate(&fa[k]);
    EXPECT_NEAR(fa[k], fb[k], scale);
    EXPECT_NEAR(fa[k + 1], fb[k + 1], scale);
  }
}

TEST(ContactProperties, IndependentOfElementOrderAndOrientation) {
  std::mt19937 rng(3);
  Scene a = random_scene(rng);
  Scene b = a;
  // Reverse the segment list and the direction of every other segment.
  const std::size_t n = a.mesh.segment_count();
  for (std::size_t j = 0; j < n; ++j) {
    std::uint32_t first = a.mesh.segments[2 * (n - 1 - j)];
    std::uint32_t second = a.mesh.segments[2 * (n - 1 - j) + 1];
    if (j % 2 == 0) std::swap(first, second);
    b.mesh.segments[2 * j] = first;
    b.mesh.segments[2 * j + 1] = second;
  }
  std::vector<double> fa(a.mesh.positions.size()), fb(fa.size());
  WallContact2D(scene_settings()).compute(a.mesh, a.cloud.arrays(), fa);
  WallContact2D(scene_settings()).compute(b.mesh, b.cloud.arrays(), fb);
  const double scale = 1e-12 * largest_magnitude(fa);
  ASSERT_GT(scale, 0.0);
  for (std::size_t k = 0; k < fa.size(); ++k)
    EXPECT_NEAR(fa[k], fb[k], scale) << "value " << k;
  for (std::size_t k = 0; k < a.cloud.f.size(); ++k)
    ASSERT_NEAR(a.cloud.f[k], b.cloud.f[k], 1e-12 * largest_magnitude(a.cloud.f));
}

TEST(ContactProperties, RanksSplittingTheParticlesGiveTheSameVertexForces) {
  // Each rank evaluates the pairs of its own particles; the client sums the vertex forces.
  std::mt19937 rng(17);
  for (int trial = 0; trial < 5; ++trial) {
    Scene whole = random_scene(rng);
    Cloud left, right;
    for (std::size_t i = 0; i < whole.cloud.count(); ++i) {
      Cloud& part = whole.cloud.x[3 * i] < 0.0 ? left : right;  // a subdomain border at x = 0
      part.add(whole.cloud.x[3 * i], whole.cloud.x[3 * i + 1], whole.cloud.v[3 * i],
               whole.cloud.v[3 * i + 1]);
    }
    const std::size_t values = whole.mesh.positions.size();
    std::vector<double> one(values), a(values), b(values);
    WallContact2D(scene_settings()).compute(whole.mesh, whole.cloud.arrays(), one);
    WallContact2D rank0(scene_settings()), rank1(scene_settings());
    auto d0 = rank0.compute(whole.mesh, left.arrays(), a);
    auto d1 = rank1.compute(whole.mesh, right.arrays(), b);
    d0.merge(d1);
    const double scale = 1e-12 * d0.pair_force_magnitude_sum;
    for (std::size_t k = 0; k < values; ++k)
      EXPECT_NEAR(a[k] + b[k], one[k], scale) << "trial " << trial << " value " << k;
  }
}

TEST(ContactProperties, DegenerateGeometryGivesFiniteForces) {
  ContactSettings s = scene_settings();
  // Vertex 0 and 1 coincide: a zero-length segment; a particle sits exactly on vertex 2 and one
  // exactly on the middle Gauss point of the unrefined segment 2-3 (length < resolution).
  BoundaryMesh2D mesh{{0.0, 0.0, 0.0, 0.0, 0.1, 0.0, 0.105, 0.0},
                      {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
                      {0, 1, 1, 2, 2, 3}};
  Cloud cloud;
  cloud.add(0.0, 0.0);     // on the zero-length segment
  cloud.add(0.1, 0.0);     // on a vertex
  cloud.add(0.1025, 0.0);  // on a sampling point (g = 1/2 of segment 2-3)
  cloud.add(0.1025, 0.0);  // twice at the same place
  std::vector<double> vertex_forces(8);
  const auto diagnostics = WallContact2D(s).compute(mesh, cloud.arrays(), vertex_forces);
  EXPECT_GT(diagnostics.pair_count, 0u);
  for (double value : cloud.f)
    EXPECT_TRUE(std::isfinite(value));
  for (double value : vertex_forces)
    EXPECT_TRUE(std::isfinite(value));
  EXPECT_EQ(diagnostics.closest_distance, 0.0);
}

TEST(ContactProperties, NonFiniteParticleIsRefusedBeforeAnyForceIsWritten) {
  BoundaryMesh2D mesh{{0.0, 0.0, 0.1, 0.0}, {0.0, 0.0, 0.0, 0.0}, {0, 1}};
  for (int field = 0; field < 2; ++field) {
    Cloud cloud;
    cloud.add(0.05, 0.002);
    cloud.add(0.05, 0.003);
    cloud.add(0.06, 0.001);
    (field == 0 ? cloud.x : cloud.v)[3 * 2 + 1] = std::nan("");
    std::vector<double> vertex_forces(4, 0.0);
    try {
      WallContact2D(scene_settings()).compute(mesh, cloud.arrays(), vertex_forces);
      FAIL() << "a NaN particle was accepted";
    } catch (const NonFiniteParticle& error) {
      EXPECT_EQ(error.index, 2u);
      EXPECT_NE(std::string(error.what()).find("particle 2"), std::string::npos) << error.what();
    }
    for (double value : cloud.f)
      EXPECT_EQ(value, 0.0);
  }
  BoundaryMesh2D bad = mesh;
  bad.positions[2] = std::numeric_limits<double>::infinity();
  try {
    bad.validate();
    FAIL() << "an infinite vertex was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("vertex 1"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace fsi::contact
