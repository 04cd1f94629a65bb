#pragma once
// Fluid regions filled with SPH particles on a square (2D) or cubic (3D) lattice of spacing d,
// with an optional uniform random displacement of every coordinate (thesis §6.2). Particle mass
// is rho0 d^dim. Pure geometry: no scene types, no I/O except the STL reader.
//
// Lattice convention (shared by every shape): the points are lower + (i + 1/2) d per axis, i >= 0,
// where `lower` is the region's lower corner (of its bounding box). A point is kept when the
// undisplaced lattice point lies inside the region; the displacement is added afterwards, so
// the count does not depend on the random numbers.
//
// 2D regions: a box, or a polygon (concave allowed) with optional holes, even-odd rule.
// 3D regions: a closed triangle surface read from an STL file (ASCII or binary); inside means a
// generalised winding number above 1/2 (the solid angle sum of van Oosterom and Strackee), which
// needs no ray and has no degenerate directions. Its cost is O(triangles) per lattice point.
// A scene with dimension = 3 uses the 3D box and the STL fill (docs/user-guide.md, "3D scenes").

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace fsi::scene {

using Point2 = std::array<double, 2>;
using Point3 = std::array<double, 3>;

struct LatticeOptions {
  double spacing = 0.0;              // d > 0
  double random_displacement = 0.0;  // uniform in [-f d, f d] per coordinate, 0 <= f <= 0.5
  std::uint64_t seed = 1;
};

// Particle mass rho0 d^dimension (2D: per unit depth).
double lattice_particle_mass(double density, double spacing, int dimension);

// Height of a lattice's column along -gravity: highest minus lowest point plus one spacing (each
// point stands for a cell of size d), the H of a box region filled to its top. 0 without points
// or without gravity. `positions` holds `dimension` values per point.
double lattice_column_height(const std::vector<double>& positions, int dimension, double spacing,
                             const std::array<double, 3>& gravity);

// The weakly compressible fluid's Tait equation p = B ((rho/rho0)^gamma - 1), B = rho0 c^2 / gamma
// (the law of LIGGGHTS' fix sph/pressure Tait).
struct TaitEquation {
  double rest_density = 0.0;    // rho0 [kg/m^3]
  double speed_of_sound = 0.0;  // c [m/s]
  double exponent = 7.0;        // gamma
  double stiffness() const { return rest_density * speed_of_sound * speed_of_sound / exponent; }
  // rho at pressure p (the inverse of the law).
  double density_at(double pressure) const;
};

// One density per lattice point: the Tait density of the hydrostatic pressure rho0 |g| (top - z),
// z the height along -g and top the lattice's top (highest point plus d/2): the free surface at
// the top of the region.
std::vector<double> hydrostatic_densities(const std::vector<double>& positions, int dimension,
                                          double spacing, const std::array<double, 3>& gravity,
                                          const TaitEquation& tait);

// ---- 2D ----

// A simple polygon (no two edges cross) and holes inside it; either orientation.
struct Polygon {
  std::vector<Point2> outer;
  std::vector<std::vector<Point2>> holes;
};

// Even-odd rule over the outer ring and the holes. Points on an edge count as inside or outside
// arbitrarily (the lattice offset of d/2 keeps them off axis-aligned edges at lattice values).
bool inside(const Polygon& polygon, const Point2& point);
// Why the polygon cannot be filled ("" if it can): fewer than 3 vertices, zero area, two edges
// that cross (named by their vertex indices, 0-based), a hole that reaches out of the outer ring
// (a vertex outside it, or an edge across it: both edges named).
std::string polygon_problem(const Polygon& polygon);
// How far the segment a-b stays from the region (inside the outer ring, outside the holes); 0
// when they share a point. For a polygon polygon_problem accepts.
double distance_to_region(const Polygon& region, const Point2& a, const Point2& b);

// x, y per particle. Throws fsi::Error for a bad polygon or spacing, or more than `max_points`.
std::vector<double> fill_box(const Point2& lower, const Point2& upper,
                             const LatticeOptions& options, std::size_t max_points = 50'000'000);
std::vector<double> fill_polygon(const Polygon& polygon, const LatticeOptions& options,
                                 std::size_t max_points = 50'000'000);

// ---- 3D ----

struct TriangleMesh {
  std::vector<Point3> vertices;  // identical coordinates merged
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// Reads an STL file, ASCII ("solid ... facet normal ... outer loop vertex ... endloop endfacet
// ... endsolid") or binary (80-byte header, uint32 count, 50 bytes per triangle). Binary is
// recognised by its exact size (84 + 50 n), so a binary header starting with "solid" is read
// correctly. Throws fsi::Error naming the file (and line, for ASCII) and what is wrong.
TriangleMesh read_stl(const std::string& path);
// The same from bytes in memory; `name` appears in messages.
TriangleMesh parse_stl(const std::string& bytes, const std::string& name);

// Why the surface does not enclose a volume ("" if it does): every edge must belong to exactly
// two triangles, used once in each direction (consistently oriented); no degenerate triangle.
std::string closed_surface_problem(const TriangleMesh& mesh);
// Generalised winding number of `point` (1 inside a closed, outward-oriented surface, 0
// outside; -1 inside an inward-oriented one).
double winding_number(const TriangleMesh& mesh, const Point3& point);
bool inside(const TriangleMesh& mesh, const Point3& point);  // |winding number| > 1/2
// Enclosed volume (divergence theorem; positive for outward orientation).
double enclosed_volume(const TriangleMesh& mesh);

// x, y, z per particle on the cubic lattice of the box. Throws fsi::Error like the 2D box.
std::vector<double> fill_box_3d(const Point3& lower, const Point3& upper,
                                const LatticeOptions& options, std::size_t max_points = 5'000'000);

// x, y, z per particle. Throws fsi::Error for an open surface, a bad spacing or too many points.
std::vector<double> fill_closed_surface(const TriangleMesh& mesh, const LatticeOptions& options,
                                        std::size_t max_points = 5'000'000);

}  // namespace fsi::scene
