// Lattice fills of boxes, polygons and closed triangle surfaces; the STL reader.

#include "fsi/scene/fluid_region.hpp"
#include "fsi/common/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <sstream>

#include "fsi/common/error.hpp"

namespace fsi::scene {
namespace {

std::string number(double value) {
  return significant(value, 6);
}

void check_options(const LatticeOptions& options, const std::string& what) {
  if (!(options.spacing > 0.0) || !std::isfinite(options.spacing)) {
    throw Error(what + ": the lattice spacing must be positive, not " + number(options.spacing), "",
                "give spacing = d > 0");
  }
  if (!(options.random_displacement >= 0.0 && options.random_displacement <= 0.5)) {
    throw Error(what + ": the random displacement must lie in [0, 0.5] (a fraction of d), not " +
                    number(options.random_displacement),
                "", "write e.g. random_displacement = 0.1");
  }
}

// Lattice counts along one axis of the extent [lower, upper].
long count_along(double lower, double upper, double d) {
  return static_cast<long>(std::floor((upper - lower) / d + 1e-9));
}

// Adds the displacement to every coordinate of `points` (dimension `dim`), in point order.
void displace(std::vector<double>& points, const LatticeOptions& options) {
  if (options.random_displacement <= 0.0) return;
  const double jitter = options.random_displacement * options.spacing;
  std::mt19937_64 random(options.seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  for (double& x : points)
    x += offset(random);
}

void check_count(double count, std::size_t max_points, const std::string& what) {
  if (count > static_cast<double>(max_points)) {
    throw Error(what + " would hold about " + number(count) + " lattice points (limit " +
                    std::to_string(max_points) + ")",
                "", "increase the spacing");
  }
}

// The lattice over the bounding box [lower, upper] of a region: its points lower + (i + 1/2) d
// per axis, x fastest, are the candidates every fill tests.
template <std::size_t Dim>
struct Lattice {
  std::array<double, Dim> lower{};
  std::array<long, Dim> counts{};
  double spacing = 0.0;

  Lattice(const std::array<double, Dim>& low, const std::array<double, Dim>& high, double d)
      : lower(low), spacing(d) {
    for (std::size_t k = 0; k < Dim; ++k)
      counts[k] = count_along(low[k], high[k], d);
  }

  double size() const {
    double points = 1.0;
    for (const long count : counts)
      points *= static_cast<double>(count);
    return points;
  }
  bool empty() const {
    return std::any_of(counts.begin(), counts.end(), [](long count) { return count < 1; });
  }

  // The coordinates of every point `keep` accepts, point after point, before any displacement.
  template <class Keep>
  std::vector<double> points(Keep keep) const {
    std::vector<double> kept;
    const auto total = empty() ? 0L : static_cast<long>(size());
    for (long flat = 0; flat < total; ++flat) {
      std::array<double, Dim> point{};
      long rest = flat;
      for (std::size_t k = 0; k < Dim; ++k) {
        point[k] = lower[k] + (static_cast<double>(rest % counts[k]) + 0.5) * spacing;
        rest /= counts[k];
      }
      if (keep(point)) kept.insert(kept.end(), point.begin(), point.end());
    }
    return kept;
  }
};

// The lattice over the bounding box of `vertices`.
template <std::size_t Dim>
Lattice<Dim> lattice_around(const std::vector<std::array<double, Dim>>& vertices, double d) {
  std::array<double, Dim> lower = vertices.front(), upper = lower;
  for (const auto& vertex : vertices) {
    for (std::size_t k = 0; k < Dim; ++k) {
      lower[k] = std::min(lower[k], vertex[k]);
      upper[k] = std::max(upper[k], vertex[k]);
    }
  }
  return Lattice<Dim>(lower, upper, d);
}

// What to say when a region holds no lattice point, and how to fix it.
struct EmptyRegion {
  std::string message;
  std::string fix;
};

// The points of the lattice around `vertices` that `contains` accepts, displaced; `what` names the
// region when it would hold too many.
template <std::size_t Dim, class Contains>
std::vector<double> fill_inside(const std::vector<std::array<double, Dim>>& vertices,
                                const LatticeOptions& options, std::size_t max_points,
                                const std::string& what, Contains contains,
                                const EmptyRegion& empty) {
  const Lattice<Dim> lattice = lattice_around(vertices, options.spacing);
  check_count(lattice.size(), max_points, what);
  std::vector<double> points = lattice.points(contains);
  if (points.empty()) throw Error(empty.message, "", empty.fix);
  displace(points, options);
  return points;
}

// Every point of the box's lattice; `axes` names them in the message of an empty box.
template <std::size_t Dim>
std::vector<double> fill_box_lattice(const std::array<double, Dim>& lower,
                                     const std::array<double, Dim>& upper,
                                     const LatticeOptions& options, std::size_t max_points,
                                     const std::string& axes) {
  check_options(options, "the fluid box");
  const Lattice<Dim> lattice(lower, upper, options.spacing);
  if (lattice.empty()) {
    throw Error(
        "the fluid box holds no lattice point (upper must exceed lower by at least one "
        "spacing" +
            axes + ")",
        "", "check lower, upper and spacing");
  }
  check_count(lattice.size(), max_points, "the fluid box");
  std::vector<double> points = lattice.points([](const auto&) { return true; });
  displace(points, options);
  return points;
}

// Even-odd crossing test of one ring (horizontal ray to +x).
bool crosses_odd(const std::vector<Point2>& ring, const Point2& p) {
  bool odd = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Point2& a = ring[i];
    const Point2& b = ring[j];
    if ((a[1] > p[1]) != (b[1] > p[1])) {
      const double x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
      if (p[0] < x) odd = !odd;
    }
  }
  return odd;
}

double signed_area(const std::vector<Point2>& ring) {
  double twice = 0.0;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    twice += ring[j][0] * ring[i][1] - ring[i][0] * ring[j][1];
  return 0.5 * twice;
}

double cross(const Point2& o, const Point2& a, const Point2& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Whether the segments pq and rs cross at a point inside both (not merely touch or overlap).
bool segments_cross(const Point2& p, const Point2& q, const Point2& r, const Point2& s) {
  const double d1 = cross(r, s, p), d2 = cross(r, s, q), d3 = cross(p, q, r), d4 = cross(p, q, s);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// Whether the closed segments pq and rs share a point.
bool segments_meet(const Point2& p, const Point2& q, const Point2& r, const Point2& s) {
  if (segments_cross(p, q, r, s)) return true;
  auto on = [](const Point2& a, const Point2& b, const Point2& c) {
    return cross(a, b, c) == 0.0 && std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) &&
           std::min(a[1], b[1]) <= c[1] && c[1] <= std::max(a[1], b[1]);
  };
  return on(r, s, p) || on(r, s, q) || on(p, q, r) || on(p, q, s);
}

double point_segment_distance(const Point2& point, const Point2& a, const Point2& b) {
  const double ab_x = b[0] - a[0], ab_y = b[1] - a[1];
  const double length2 = ab_x * ab_x + ab_y * ab_y;
  const double s =
      length2 > 0.0
          ? std::clamp(((point[0] - a[0]) * ab_x + (point[1] - a[1]) * ab_y) / length2, 0.0, 1.0)
          : 0.0;
  return std::hypot(a[0] + s * ab_x - point[0], a[1] + s * ab_y - point[1]);
}

std::string edge_name(std::size_t first, std::size_t count) {
  return std::to_string(first) + "-" + std::to_string((first + 1) % count);
}

// What is wrong with a polygon and what to do about it; an empty message when it can be filled.
struct PolygonFault {
  std::string message;
  std::string fix;
};

constexpr const char* kInOrder = "give the vertices in order around the region";

PolygonFault ring_fault(const std::vector<Point2>& ring, const std::string& name) {
  if (ring.size() < 3) {
    return {name + " has " + std::to_string(ring.size()) + " vertices, needs 3",
            "give at least 3 vertices, in order around the region"};
  }
  for (const Point2& p : ring) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]))
      return {name + " has a non-finite vertex", "check the expressions of the vertices"};
  }
  if (signed_area(ring) == 0.0) return {name + " encloses no area", kInOrder};
  // Edges may touch (a vertex on another edge) and overlap along a line, never cross: water on
  // both sides of a baffle that reaches the surface is one polygon notched up to the surface,
  // its notch's top lying on the surface's edge (a user's rolling tank, 2026-12-06, was refused
  // as crossing). The even-odd fill leaves the notch empty.
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool neighbours = j == i + 1 || (i == 0 && j == n - 1);
      if (neighbours) continue;
      if (segments_cross(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n])) {
        return {name + ": edges " + edge_name(i, n) + " and " + edge_name(j, n) +
                    " cross (the polygon must not intersect itself)",
                kInOrder};
      }
    }
  }
  return {};
}

// A hole that reaches out of the outline: the even-odd fill would put fluid outside the region.
PolygonFault hole_fault(const std::vector<Point2>& outer, const std::vector<Point2>& hole,
                        const std::string& name) {
  std::string crossing;
  for (std::size_t i = 0; i < hole.size() && crossing.empty(); ++i) {
    for (std::size_t j = 0; j < outer.size(); ++j) {
      if (segments_cross(hole[i], hole[(i + 1) % hole.size()], outer[j],
                         outer[(j + 1) % outer.size()])) {
        crossing = "the hole's edge " + edge_name(i, hole.size()) + " crosses the polygon's edge " +
                   edge_name(j, outer.size());
        break;
      }
    }
  }
  std::string message;
  for (std::size_t v = 0; v < hole.size() && message.empty(); ++v) {
    if (!crosses_odd(outer, hole[v])) {
      message = name + ": vertex " + std::to_string(v) + " lies outside the polygon" +
                (crossing.empty() ? "" : " (" + crossing + ")");
    }
  }
  if (message.empty() && !crossing.empty()) message = name + ": " + crossing;
  if (message.empty()) return {};
  return {message,
          "a hole must lie inside the polygon: move its vertices inwards, or the polygon's "
          "outwards"};
}

PolygonFault polygon_fault(const Polygon& polygon) {
  PolygonFault fault = ring_fault(polygon.outer, "the polygon");
  for (std::size_t h = 0; h < polygon.holes.size() && fault.message.empty(); ++h) {
    const std::string name = "hole " + std::to_string(h);
    fault = ring_fault(polygon.holes[h], name);
    if (fault.message.empty()) fault = hole_fault(polygon.outer, polygon.holes[h], name);
  }
  return fault;
}

// ---- STL ----

struct VertexMerger {
  std::map<Point3, std::uint32_t> index;
  TriangleMesh* mesh;
  std::uint32_t operator()(const Point3& p) {
    const auto [it, added] = index.emplace(p, static_cast<std::uint32_t>(mesh->vertices.size()));
    if (added) mesh->vertices.push_back(p);
    return it->second;
  }
};

TriangleMesh parse_binary(const std::string& bytes, const std::string& name, std::uint32_t count) {
  TriangleMesh mesh;
  VertexMerger merge{{}, &mesh};
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + 84 + 50 * static_cast<std::size_t>(t);
    std::array<std::uint32_t, 3> triangle{};
    for (int v = 0; v < 3; ++v) {
      Point3 p{};
      for (int k = 0; k < 3; ++k) {
        float value = 0.0F;  // little-endian IEEE binary32, as the format defines
        std::memcpy(&value, record + 12 + 12 * v + 4 * k, sizeof value);
        if (!std::isfinite(value)) {
          throw Error("binary STL triangle " + std::to_string(t) + " has a non-finite coordinate",
                      name, "repair or re-export the file");
        }
        p[static_cast<std::size_t>(k)] = static_cast<double>(value);
      }
      triangle[static_cast<std::size_t>(v)] = merge(p);
    }
    mesh.triangles.push_back(triangle);
  }
  return mesh;
}

TriangleMesh parse_ascii(const std::string& text, const std::string& name) {
  TriangleMesh mesh;
  VertexMerger merge{{}, &mesh};
  std::istringstream lines(text);
  std::string line;
  int line_number = 0;
  std::vector<Point3> loop;
  bool in_loop = false, ended = false, started = false;
  auto fail = [&](const std::string& what, const std::string& fix) {
    throw Error(what, name + ":" + std::to_string(line_number), fix);
  };
  while (std::getline(lines, line)) {
    ++line_number;
    std::istringstream words(line);
    std::string word;
    if (!(words >> word)) continue;
    if (ended) fail("text after 'endsolid'", "remove it (one solid per file)");
    if (word == "solid") {
      if (started) fail("a second 'solid'", "put one solid per file");
      started = true;
    } else if (!started) {
      fail("an ASCII STL file starts with 'solid'", "check that this is an STL file");
    } else if (word == "facet" || word == "endfacet" || word == "outer") {
      // "facet normal nx ny nz": the normal is recomputed from the vertex order, not read.
    } else if (word == "loop") {
      fail("'loop' without 'outer'", "write 'outer loop'");
    } else if (word == "endloop") {
      if (!in_loop) fail("'endloop' without 'outer loop'", "check the facet structure");
      if (loop.size() != 3) {
        fail("a facet has " + std::to_string(loop.size()) + " vertices, STL facets have 3",
             "triangulate the surface before export");
      }
      mesh.triangles.push_back({merge(loop[0]), merge(loop[1]), merge(loop[2])});
      loop.clear();
      in_loop = false;
    } else if (word == "vertex") {
      Point3 p{};
      for (double& x : p) {
        if (!(words >> x) || !std::isfinite(x))
          fail("a vertex needs three numbers", "vertex x y z");
      }
      in_loop = true;
      loop.push_back(p);
    } else if (word == "endsolid") {
      ended = true;
    } else {
      fail("unknown word '" + word + "' in an ASCII STL file",
           "expected solid, facet, outer loop, vertex, endloop, endfacet, endsolid");
    }
  }
  if (!started) fail("the file is empty", "give an STL file");
  if (!ended) fail("the file ends without 'endsolid'", "the file may be truncated");
  return mesh;
}

}  // namespace

double lattice_particle_mass(double density, double spacing, int dimension) {
  return density * std::pow(spacing, dimension);
}

double lattice_column_height(const std::vector<double>& positions, int dimension, double spacing,
                             const std::array<double, 3>& gravity) {
  const double magnitude = std::hypot(gravity[0], gravity[1], gravity[2]);
  const std::size_t count = positions.size() / static_cast<std::size_t>(dimension);
  if (count == 0 || !(magnitude > 0.0)) return 0.0;
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -lowest;
  for (std::size_t i = 0; i < count; ++i) {
    double height = 0.0;
    for (int k = 0; k < dimension; ++k)
      height -= gravity[k] / magnitude * positions[i * dimension + k];
    lowest = std::min(lowest, height);
    highest = std::max(highest, height);
  }
  return highest - lowest + spacing;
}

double TaitEquation::density_at(double pressure) const {
  return rest_density * std::pow(1.0 + pressure / stiffness(), 1.0 / exponent);
}

std::vector<double> hydrostatic_densities(const std::vector<double>& positions, int dimension,
                                          double spacing, const std::array<double, 3>& gravity,
                                          const TaitEquation& tait) {
  const double magnitude = std::hypot(gravity[0], gravity[1], gravity[2]);
  const std::size_t count = positions.size() / static_cast<std::size_t>(dimension);
  auto height = [&](std::size_t i) {
    double z = 0.0;
    for (int k = 0; k < dimension; ++k)
      z -= (magnitude > 0.0 ? gravity[k] / magnitude : 0.0) * positions[i * dimension + k];
    return z;
  };
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < count; ++i)
    top = std::max(top, height(i));
  top += 0.5 * spacing;
  std::vector<double> densities(count);
  for (std::size_t i = 0; i < count; ++i)
    densities[i] = tait.density_at(tait.rest_density * magnitude * (top - height(i)));
  return densities;
}

bool inside(const Polygon& polygon, const Point2& point) {
  bool odd = crosses_odd(polygon.outer, point);
  for (const auto& hole : polygon.holes) {
    if (crosses_odd(hole, point)) odd = !odd;
  }
  return odd;
}

std::string polygon_problem(const Polygon& polygon) {
  return polygon_fault(polygon).message;
}

double distance_to_region(const Polygon& region, const Point2& a, const Point2& b) {
  if (inside(region, a) || inside(region, b)) return 0.0;
  // Outside the region the segment can only come close to its edges.
  double distance = std::numeric_limits<double>::infinity();
  auto approach = [&](const std::vector<Point2>& ring) {
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const Point2& p = ring[j];
      const Point2& q = ring[i];
      if (segments_meet(a, b, p, q)) {
        distance = 0.0;
        return;
      }
      distance =
          std::min({distance, point_segment_distance(a, p, q), point_segment_distance(b, p, q),
                    point_segment_distance(p, a, b), point_segment_distance(q, a, b)});
    }
  };
  approach(region.outer);
  for (const auto& hole : region.holes)
    approach(hole);
  return distance;
}

std::vector<double> fill_box(const Point2& lower, const Point2& upper,
                             const LatticeOptions& options, std::size_t max_points) {
  return fill_box_lattice(lower, upper, options, max_points, "");
}

std::vector<double> fill_polygon(const Polygon& polygon, const LatticeOptions& options,
                                 std::size_t max_points) {
  check_options(options, "the fluid polygon");
  if (const PolygonFault fault = polygon_fault(polygon); !fault.message.empty())
    throw Error(fault.message, "", fault.fix);
  return fill_inside(polygon.outer, options, max_points, "the fluid polygon",
                     [&](const Point2& point) { return inside(polygon, point); },
                     {"the fluid polygon holds no lattice point",
                      "make the polygon larger or the spacing smaller"});
}

TriangleMesh parse_stl(const std::string& bytes, const std::string& name) {
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;  // little-endian, as the format defines
    std::memcpy(&count, bytes.data() + 80, sizeof count);
    if (bytes.size() == 84 + 50 * static_cast<std::size_t>(count)) {
      if (count == 0) throw Error("the binary STL file has no triangles", name, "");
      return parse_binary(bytes, name, count);
    }
  }
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  // Text has no NUL byte; a binary file with a wrong size does (or is not text at all).
  const bool text = bytes.find('\0') == std::string::npos;
  if (first == std::string::npos || bytes.compare(first, 5, "solid") != 0 || !text) {
    throw Error(
        "neither an ASCII STL file (starting with 'solid') nor a binary one (84 + 50 n "
        "bytes for n triangles; this file has " +
            std::to_string(bytes.size()) + " bytes)",
        name, "the file may be truncated; re-export it");
  }
  TriangleMesh mesh = parse_ascii(bytes, name);
  if (mesh.triangles.empty()) throw Error("the STL file has no facets", name, "");
  return mesh;
}

TriangleMesh read_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read the STL file '" + path + "'", path, "check the path");
  std::stringstream bytes;
  bytes << in.rdbuf();
  return parse_stl(bytes.str(), path);
}

std::string closed_surface_problem(const TriangleMesh& mesh) {
  if (mesh.triangles.size() < 4) return "a closed surface needs at least 4 triangles";
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      return "triangle " + std::to_string(t) + " is degenerate (two corners coincide)";
    }
    for (int k = 0; k < 3; ++k)
      ++directed[{tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)]}];
  }
  auto edge_text = [&](const std::pair<std::uint32_t, std::uint32_t>& edge) {
    const Point3& a = mesh.vertices[edge.first];
    const Point3& b = mesh.vertices[edge.second];
    return "the edge (" + number(a[0]) + ", " + number(a[1]) + ", " + number(a[2]) + ") - (" +
           number(b[0]) + ", " + number(b[1]) + ", " + number(b[2]) + ") ";
  };
  auto back_of = [&](const std::pair<std::uint32_t, std::uint32_t>& edge) {
    const auto reverse = directed.find({edge.second, edge.first});
    return reverse == directed.end() ? 0 : reverse->second;
  };
  // Holes and non-manifold edges first (triangles per undirected edge), then orientation.
  for (const auto& [edge, uses] : directed) {
    const int triangles = uses + back_of(edge);
    if (triangles == 1)
      return edge_text(edge) + "belongs to one triangle only: the surface has a hole";
    if (triangles > 2) {
      return edge_text(edge) + "belongs to " + std::to_string(triangles) +
             " triangles (the surface is not a manifold)";
    }
  }
  for (const auto& [edge, uses] : directed) {
    if (uses != 1) {
      return edge_text(edge) +
             "is not shared by two consistently oriented triangles (a flipped triangle)";
    }
  }
  return "";
}

double winding_number(const TriangleMesh& mesh, const Point3& point) {
  double solid_angle = 0.0;
  for (const auto& tri : mesh.triangles) {
    std::array<Point3, 3> r{};
    std::array<double, 3> length{};
    for (std::size_t v = 0; v < 3; ++v) {
      for (std::size_t k = 0; k < 3; ++k)
        r[v][k] = mesh.vertices[tri[v]][k] - point[k];
      length[v] = std::sqrt(r[v][0] * r[v][0] + r[v][1] * r[v][1] + r[v][2] * r[v][2]);
    }
    auto dot = [](const Point3& a, const Point3& b) {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    const double triple = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                          r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                          r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    const double denominator = length[0] * length[1] * length[2] + dot(r[0], r[1]) * length[2] +
                               dot(r[1], r[2]) * length[0] + dot(r[2], r[0]) * length[1];
    solid_angle += 2.0 * std::atan2(triple, denominator);
  }
  return solid_angle / (4.0 * std::numbers::pi);
}

bool inside(const TriangleMesh& mesh, const Point3& point) {
  return std::fabs(winding_number(mesh, point)) > 0.5;
}

double enclosed_volume(const TriangleMesh& mesh) {
  double six_volume = 0.0;
  for (const auto& tri : mesh.triangles) {
    const Point3& a = mesh.vertices[tri[0]];
    const Point3& b = mesh.vertices[tri[1]];
    const Point3& c = mesh.vertices[tri[2]];
    six_volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                  a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return six_volume / 6.0;
}

std::vector<double> fill_box_3d(const Point3& lower, const Point3& upper,
                                const LatticeOptions& options, std::size_t max_points) {
  return fill_box_lattice(lower, upper, options, max_points, " in x, y and z");
}

std::vector<double> fill_closed_surface(const TriangleMesh& mesh, const LatticeOptions& options,
                                        std::size_t max_points) {
  check_options(options, "the fluid surface region");
  if (const std::string problem = closed_surface_problem(mesh); !problem.empty()) {
    throw Error("the STL surface does not enclose a volume: " + problem, "",
                "close and orient the surface (every edge shared by two triangles)");
  }
  return fill_inside(mesh.vertices, options, max_points, "the fluid surface region",
                     [&](const Point3& point) { return inside(mesh, point); },
                     {"the STL region holds no lattice point", "make the spacing smaller"});
}

}  // namespace fsi::scene
