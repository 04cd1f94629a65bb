#include "fsi/scene/fluid_region.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "fsi/common/error.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

std::size_t count2(const std::vector<double>& xy) {
  return xy.size() / 2;
}

LatticeOptions lattice(double d, double displacement = 0.0, std::uint64_t seed = 1) {
  LatticeOptions options;
  options.spacing = d;
  options.random_displacement = displacement;
  options.seed = seed;
  return options;
}

using testing::message_thrown;

TEST(FluidRegion, TheColumnHeightIsTheExtentAlongGravityPlusOneSpacing) {
  const double d = 0.01;
  LatticeOptions options;
  options.spacing = d;
  // 0.2 m wide, 0.13 m high: 13 rows, whose centres span 12 d.
  const std::vector<double> box = fill_box({0.0, 0.0}, {0.2, 0.13}, options);
  EXPECT_NEAR(lattice_column_height(box, 2, d, {0.0, -9.81, 0.0}), 0.13, 1e-12);
  // Gravity along x sees the width; its sign does not matter.
  EXPECT_NEAR(lattice_column_height(box, 2, d, {3.0, 0.0, 0.0}), 0.2, 1e-12);
  // 3D with gravity along -z.
  const std::vector<double> cube = fill_box_3d({0, 0, 0}, {0.05, 0.05, 0.07}, options);
  EXPECT_NEAR(lattice_column_height(cube, 3, d, {0.0, 0.0, -9.81}), 0.07, 1e-12);
  EXPECT_EQ(lattice_column_height(box, 2, d, {0.0, 0.0, 0.0}), 0.0);
  EXPECT_EQ(lattice_column_height({}, 2, d, {0.0, -9.81, 0.0}), 0.0);
}

TEST(FluidRegion, HydrostaticDensitiesFollowTheTaitEquationBelowTheTop) {
  const double d = 0.01;
  LatticeOptions options;
  options.spacing = d;
  // 13 rows under g = 10: the top row's centre is d/2 below the surface, the bottom row's 12.5 d.
  const std::vector<double> column = fill_box({0.0, 0.0}, {0.02, 0.13}, options);
  TaitEquation tait;
  tait.rest_density = 1000.0;
  tait.speed_of_sound = 20.0;
  const std::vector<double> densities =
      hydrostatic_densities(column, 2, d, {0.0, -10.0, 0.0}, tait);
  ASSERT_EQ(densities.size(), column.size() / 2);
  const double stiffness = 1000.0 * 20.0 * 20.0 / 7.0;
  EXPECT_DOUBLE_EQ(tait.stiffness(), stiffness);
  for (std::size_t i = 0; i < densities.size(); ++i) {
    const double depth = 0.13 - column[2 * i + 1];
    const double pressure = 1000.0 * 10.0 * depth;
    // The Tait law of LIGGGHTS' fix sph/pressure gives back the hydrostatic pressure.
    EXPECT_NEAR(stiffness * (std::pow(densities[i] / 1000.0, 7.0) - 1.0), pressure,
                1e-9 * stiffness)
        << i;
  }
  // About rho0 (1 + rho0 g H / (gamma B))... at the bottom: 1000 * (1 + 1250/57142.86)^(1/7).
  EXPECT_NEAR(densities.front(), 1000.0 * std::pow(1.0 + 1250.0 / stiffness, 1.0 / 7.0), 1e-9);
  EXPECT_NEAR(densities.back(), 1000.0 * std::pow(1.0 + 50.0 / stiffness, 1.0 / 7.0), 1e-9);
}

TEST(FluidRegion, ARectangularPolygonFillsLikeTheBox) {
  const Polygon rectangle{{{0, 0}, {1, 0}, {1, 0.5}, {0, 0.5}}, {}};
  const auto polygon = fill_polygon(rectangle, lattice(0.1));
  const auto box = fill_box({0, 0}, {1, 0.5}, lattice(0.1));
  EXPECT_EQ(count2(box), 50u);  // 10 x 5
  EXPECT_EQ(polygon, box);
  EXPECT_DOUBLE_EQ(box[0], 0.05);
  EXPECT_DOUBLE_EQ(box[1], 0.05);
  EXPECT_DOUBLE_EQ(lattice_particle_mass(1000, 0.1, 2), 10.0);
  EXPECT_DOUBLE_EQ(lattice_particle_mass(1000, 0.1, 3), 1.0);
}

TEST(FluidRegion, A3DBoxFillsLikeItsStlSurface) {
  // The box [0, 1] x [0, 0.5] x [0, 0.3] as a closed surface: the same lattice, the same order.
  TriangleMesh surface;
  for (double z : {0.0, 0.3})
    for (double y : {0.0, 0.5})
      for (double x : {0.0, 1.0})
        surface.vertices.push_back({x, y, z});
  surface.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                       {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  const auto box = fill_box_3d({0, 0, 0}, {1, 0.5, 0.3}, lattice(0.1));
  EXPECT_EQ(box.size(), 3u * 10u * 5u * 3u);
  EXPECT_EQ(fill_closed_surface(surface, lattice(0.1)), box);
  EXPECT_DOUBLE_EQ(box[2], 0.05);
  EXPECT_NE(message_thrown([] {
              fill_box_3d({0, 0, 0}, {1, 1, 0.05}, lattice(0.1));
            }).find("holds no lattice point"),
            std::string::npos);
}

TEST(FluidRegion, AConcavePolygonInEitherOrientation) {
  // An L: the unit square without [0.4, 1]^2. 100 lattice points minus 6 x 6 = 64.
  Polygon l_shape{{{0, 0}, {1, 0}, {1, 0.4}, {0.4, 0.4}, {0.4, 1}, {0, 1}}, {}};
  EXPECT_EQ(polygon_problem(l_shape), "");
  EXPECT_TRUE(inside(l_shape, {0.2, 0.8}));
  EXPECT_TRUE(inside(l_shape, {0.8, 0.2}));
  EXPECT_FALSE(inside(l_shape, {0.7, 0.7}));
  EXPECT_FALSE(inside(l_shape, {1.2, 0.2}));
  EXPECT_FALSE(inside(l_shape, {-0.1, 0.5}));
  const auto points = fill_polygon(l_shape, lattice(0.1));
  EXPECT_EQ(count2(points), 64u);
  for (std::size_t i = 0; i < count2(points); ++i)
    EXPECT_FALSE(points[2 * i] > 0.4 && points[2 * i + 1] > 0.4) << i;
  std::reverse(l_shape.outer.begin(), l_shape.outer.end());
  EXPECT_EQ(count2(fill_polygon(l_shape, lattice(0.1))), 64u);
}

TEST(FluidRegion, HolesAreLeftEmpty) {
  // Unit square with the hole [0.3, 0.7]^2: lattice points 0.35 ... 0.65 (4 x 4) fall out.
  const Polygon ring{{{0, 0}, {1, 0}, {1, 1}, {0, 1}},
                     {{{0.3, 0.3}, {0.3, 0.7}, {0.7, 0.7}, {0.7, 0.3}}}};
  EXPECT_EQ(polygon_problem(ring), "");
  EXPECT_FALSE(inside(ring, {0.5, 0.5}));
  EXPECT_TRUE(inside(ring, {0.2, 0.5}));
  EXPECT_EQ(count2(fill_polygon(ring, lattice(0.1))), 84u);
}

TEST(FluidRegion, ACircleHoldsItsAreaOverDSquared) {
  Polygon circle;
  const int n = 400;
  for (int k = 0; k < n; ++k) {
    const double phi = 2 * std::numbers::pi * k / n;
    circle.outer.push_back({0.5 + 0.5 * std::cos(phi), 0.5 + 0.5 * std::sin(phi)});
  }
  const double d = 0.005;
  const double area = static_cast<double>(count2(fill_polygon(circle, lattice(d)))) * d * d;
  // Lattice-point counting error is O(perimeter d) = O(1e-2) relative; measured below 0.2 %.
  EXPECT_NEAR(area / (std::numbers::pi * 0.25), 1.0, 2e-3);
}

TEST(FluidRegion, RandomDisplacementIsBoundedSeededAndKeepsTheCount) {
  const Polygon square{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {}};
  const auto plain = fill_polygon(square, lattice(0.1));
  const auto moved = fill_polygon(square, lattice(0.1, 0.2, 7));
  ASSERT_EQ(moved.size(), plain.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < plain.size(); ++i)
    largest = std::max(largest, std::fabs(moved[i] - plain[i]));
  EXPECT_LE(largest, 0.2 * 0.1);
  EXPECT_GT(largest, 0.1 * 0.1);  // 200 draws: one beyond half the bound
  EXPECT_EQ(fill_polygon(square, lattice(0.1, 0.2, 7)), moved);
  EXPECT_NE(fill_polygon(square, lattice(0.1, 0.2, 8)), moved);
}

TEST(FluidRegion, BadPolygonsAreExplained) {
  EXPECT_NE(polygon_problem({{{0, 0}, {1, 0}}, {}}).find("has 2 vertices, needs 3"),
            std::string::npos);
  EXPECT_NE(polygon_problem({{{0, 0}, {1, 0}, {2, 0}}, {}}).find("encloses no area"),
            std::string::npos);
  // A bow tie: edges 0-1 and 2-3 cross.
  EXPECT_NE(polygon_problem({{{0, 0}, {2, 2}, {2, 0}, {0, 1}}, {}}).find("edges 0-1 and 2-3 cross"),
            std::string::npos);
  EXPECT_NE(
      polygon_problem({{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{{0.5, 0.5}, {1.5, 0.5}, {0.5, 0.7}}}})
          .find("hole 0: vertex 1 lies outside the polygon"),
      std::string::npos);
  const Polygon square{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {}};
  EXPECT_NE(
      message_thrown([&] { fill_polygon(square, lattice(0.0)); }).find("spacing must be positive"),
      std::string::npos);
  EXPECT_NE(message_thrown([&] { fill_polygon(square, lattice(0.1, 0.6)); }).find("[0, 0.5]"),
            std::string::npos);
  EXPECT_NE(message_thrown([&] {
              fill_polygon(square, lattice(1e-5), 1000);
            }).find("increase the spacing"),
            std::string::npos);
}

// Water on both sides of a baffle reaching the surface: one polygon notched up to the surface,
// the notch's top on the surface's edge (touching, not crossing; a user's rolling tank was
// refused as "edges 1-2 and 6-7 cross"). Both sides fill, the notch stays empty.
TEST(FluidRegion, APolygonMayTouchItselfAndFillsBothSides) {
  const Polygon notched{
      {{-1, 0}, {-0.1, 0}, {-0.1, 1}, {0.1, 1}, {0.1, 0}, {1, 0}, {1, 1}, {-1, 1}}, {}};
  EXPECT_EQ(polygon_problem(notched), "");
  const std::vector<double> points = fill_polygon(notched, lattice(0.05));
  std::size_t left = 0, right = 0, notch = 0;
  for (std::size_t k = 0; k + 1 < points.size(); k += 2) {
    const double x = points[k];
    if (x < -0.1) ++left;
    if (x > 0.1) ++right;
    if (std::abs(x) < 0.1) ++notch;
  }
  EXPECT_EQ(left, 18u * 20u);
  EXPECT_EQ(right, 18u * 20u);
  EXPECT_EQ(notch, 0u);
  // A vertex on another edge (a pinch) is a touch as well.
  EXPECT_EQ(polygon_problem({{{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1}}, {}}), "");
}

TEST(FluidRegion, AHoleCrossingTheOutlineIsNamedAsSuch) {
  // A hole poking out of the unit square through its right edge (vertex 1 outside).
  const Polygon poking{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{{0.5, 0.5}, {1.5, 0.5}, {0.5, 0.7}}}};
  const std::string poking_error = message_thrown([&] { fill_polygon(poking, lattice(0.1)); });
  EXPECT_NE(poking_error.find("hole 0: vertex 1 lies outside the polygon (the hole's edge 0-1 "
                              "crosses the polygon's edge 1-2)"),
            std::string::npos)
      << poking_error;
  EXPECT_NE(poking_error.find("a hole must lie inside the polygon"), std::string::npos)
      << poking_error;
  // Its vertices are in order: the message must not send the user to reorder them.
  EXPECT_EQ(poking_error.find("in order"), std::string::npos) << poking_error;
  // Every vertex inside an L, one edge across its notch: the even-odd fill would put fluid into
  // the notch, outside the region.
  const Polygon across{{{0, 0}, {1, 0}, {1, 0.4}, {0.4, 0.4}, {0.4, 1}, {0, 1}},
                       {{{0.2, 0.2}, {0.8, 0.2}, {0.8, 0.3}, {0.3, 0.8}, {0.2, 0.8}}}};
  EXPECT_EQ(polygon_problem(across), "hole 0: the hole's edge 2-3 crosses the polygon's edge 2-3");
  const std::string across_error = message_thrown([&] { fill_polygon(across, lattice(0.1)); });
  EXPECT_NE(across_error.find("a hole must lie inside the polygon"), std::string::npos)
      << across_error;
  // A polygon that crosses itself is still told to order its vertices.
  const Polygon bow_tie{{{0, 0}, {2, 2}, {2, 0}, {0, 1}}, {}};
  EXPECT_NE(message_thrown([&] { fill_polygon(bow_tie, lattice(0.1)); }).find("in order"),
            std::string::npos);
}

// ---- STL ----

struct Facet {
  Point3 a, b, c;
};

// The unit cube [0, 1]^3 (scaled and shifted), outward-oriented, 12 triangles.
std::vector<Facet> cube(double size = 1.0, Point3 at = {0, 0, 0}) {
  const auto p = [&](double x, double y, double z) {
    return Point3{at[0] + size * x, at[1] + size * y, at[2] + size * z};
  };
  const Point3 v000 = p(0, 0, 0), v100 = p(1, 0, 0), v110 = p(1, 1, 0), v010 = p(0, 1, 0);
  const Point3 v001 = p(0, 0, 1), v101 = p(1, 0, 1), v111 = p(1, 1, 1), v011 = p(0, 1, 1);
  return {{v000, v010, v110}, {v000, v110, v100},   // z = 0, normal -z
          {v001, v101, v111}, {v001, v111, v011},   // z = 1, normal +z
          {v000, v100, v101}, {v000, v101, v001},   // y = 0, normal -y
          {v010, v011, v111}, {v010, v111, v110},   // y = 1, normal +y
          {v000, v001, v011}, {v000, v011, v010},   // x = 0, normal -x
          {v100, v110, v111}, {v100, v111, v101}};  // x = 1, normal +x
}

std::string ascii_stl(const std::vector<Facet>& facets) {
  std::ostringstream out;
  out.precision(17);
  out << "solid test\n";
  for (const Facet& f : facets) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (const Point3& v : {f.a, f.b, f.c})
      out << "      vertex " << v[0] << " " << v[1] << " " << v[2] << "\n";
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid test\n";
  return out.str();
}

std::string binary_stl(const std::vector<Facet>& facets) {
  std::string bytes(80, ' ');
  bytes.replace(0, 12, "solid binary");  // a header that starts like ASCII
  const auto count = static_cast<std::uint32_t>(facets.size());
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (const Facet& f : facets) {
    const float normal[3] = {0, 0, 0};
    bytes.append(reinterpret_cast<const char*>(normal), 12);
    for (const Point3& v : {f.a, f.b, f.c}) {
      for (double x : v) {
        const auto value = static_cast<float>(x);
        bytes.append(reinterpret_cast<const char*>(&value), 4);
      }
    }
    bytes.append(2, '\0');
  }
  return bytes;
}

TEST(FluidRegion, AsciiAndBinaryStlReadTheSameCube) {
  const TriangleMesh ascii = parse_stl(ascii_stl(cube()), "cube_ascii.stl");
  const TriangleMesh binary = parse_stl(binary_stl(cube()), "cube_binary.stl");
  for (const TriangleMesh* mesh : {&ascii, &binary}) {
    EXPECT_EQ(mesh->vertices.size(), 8u);  // shared corners merged
    EXPECT_EQ(mesh->triangles.size(), 12u);
    EXPECT_EQ(closed_surface_problem(*mesh), "");
    EXPECT_DOUBLE_EQ(enclosed_volume(*mesh), 1.0);
  }
  EXPECT_EQ(ascii.vertices, binary.vertices);
  EXPECT_EQ(ascii.triangles, binary.triangles);

  // Through a file as well.
  const auto path =
      std::filesystem::temp_directory_path() / ("fsi_cube_" + std::to_string(::getpid()) + ".stl");
  std::ofstream(path, std::ios::binary) << binary_stl(cube());
  EXPECT_EQ(read_stl(path.string()).triangles, binary.triangles);
  std::filesystem::remove(path);
}

TEST(FluidRegion, InsideAStlSurfaceByWindingNumber) {
  const TriangleMesh mesh = parse_stl(ascii_stl(cube()), "cube.stl");
  EXPECT_NEAR(winding_number(mesh, {0.5, 0.5, 0.5}), 1.0, 1e-12);
  EXPECT_NEAR(winding_number(mesh, {1.5, 0.5, 0.5}), 0.0, 1e-12);
  EXPECT_TRUE(inside(mesh, {0.999, 0.001, 0.5}));
  EXPECT_FALSE(inside(mesh, {1.001, 0.5, 0.5}));
  EXPECT_FALSE(inside(mesh, {0.5, 0.5, -0.001}));
  // A point on the line through a vertex and an edge (where a ray test can miscount).
  EXPECT_TRUE(inside(mesh, {0.5, 0.5, 0.25}));
  EXPECT_FALSE(inside(mesh, {2.0, 2.0, 2.0}));
}

TEST(FluidRegion, FillingAStlCubeAndAnOctahedron) {
  const TriangleMesh box = parse_stl(binary_stl(cube(1.0, {0.2, 0, 0})), "cube.stl");
  EXPECT_EQ(fill_closed_surface(box, lattice(0.1)).size() / 3, 1000u);

  // An octahedron |x| + |y| + |z| <= 1: volume 4/3, faces oblique to the lattice.
  const Point3 px{1, 0, 0}, nx{-1, 0, 0}, py{0, 1, 0}, ny{0, -1, 0}, pz{0, 0, 1}, nz{0, 0, -1};
  const std::vector<Facet> octahedron = {{px, py, pz}, {py, nx, pz}, {nx, ny, pz}, {ny, px, pz},
                                         {py, px, nz}, {nx, py, nz}, {ny, nx, nz}, {px, ny, nz}};
  const TriangleMesh mesh = parse_stl(ascii_stl(octahedron), "octahedron.stl");
  EXPECT_EQ(closed_surface_problem(mesh), "");
  EXPECT_NEAR(enclosed_volume(mesh), 4.0 / 3.0, 1e-12);
  const double d = 0.05;
  const auto points = fill_closed_surface(mesh, lattice(d));
  const double volume = static_cast<double>(points.size() / 3) * d * d * d;
  EXPECT_NEAR(volume / (4.0 / 3.0), 1.0, 0.02);
  for (std::size_t i = 0; i < points.size(); i += 3)
    EXPECT_LT(std::fabs(points[i]) + std::fabs(points[i + 1]) + std::fabs(points[i + 2]), 1.0);
}

TEST(FluidRegion, BadStlFilesAreExplained) {
  std::vector<Facet> open = cube();
  open.pop_back();
  const TriangleMesh holed = parse_stl(ascii_stl(open), "open.stl");
  EXPECT_NE(closed_surface_problem(holed).find("belongs to one triangle only"), std::string::npos);
  EXPECT_NE(message_thrown([&] {
              fill_closed_surface(holed, lattice(0.1));
            }).find("does not enclose a volume"),
            std::string::npos);
  std::vector<Facet> flipped = cube();
  std::swap(flipped[0].b, flipped[0].c);
  EXPECT_NE(closed_surface_problem(parse_stl(ascii_stl(flipped), "f.stl"))
                .find("consistently oriented triangles (a flipped"),
            std::string::npos);

  std::string truncated = binary_stl(cube());
  truncated.resize(truncated.size() - 10);
  EXPECT_NE(message_thrown([&] { parse_stl(truncated, "t.stl"); }).find("this file has"),
            std::string::npos);
  std::string text = ascii_stl(cube());
  text.replace(text.find("vertex 0 0 0"), 12, "vertex 0 0 x");
  const std::string message = message_thrown([&] { parse_stl(text, "bad.stl"); });
  EXPECT_NE(message.find("bad.stl:4"), std::string::npos) << message;
  EXPECT_NE(message.find("a vertex needs three numbers"), std::string::npos) << message;
  EXPECT_NE(message_thrown([&] {
              parse_stl("solid x\n facet normal 0 0 1\n", "e.stl");
            }).find("without 'endsolid'"),
            std::string::npos);
  EXPECT_NE(
      message_thrown([&] { read_stl("/nonexistent/x.stl"); }).find("cannot read the STL file"),
      std::string::npos);
}

}  // namespace
}  // namespace fsi::scene
