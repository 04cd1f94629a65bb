#include "fsi/contact/triangle_quadrature.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace fsi::contact {
namespace {

// The three points with barycentric coordinates (1 - 2a, a, a) and its cyclic permutations.
constexpr std::array<TrianglePoint, 3> orbit(double a, double weight) {
  const double b = 1.0 - 2.0 * a;
  return {TrianglePoint{{b, a, a}, weight}, TrianglePoint{{a, b, a}, weight},
          TrianglePoint{{a, a, b}, weight}};
}

const std::array<TrianglePoint, 1> kRule1{TrianglePoint{{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}, 1.0}};

const std::array<TrianglePoint, 3> kRule3 = orbit(1.0 / 6.0, 1.0 / 3.0);

// Degree-5 rule: centroid weight 9/40; the orbit near the vertices, a = (6 - sqrt 15)/21, weighs
// (155 - sqrt 15)/1200 each, the orbit near the edge midpoints, a = (6 + sqrt 15)/21,
// (155 + sqrt 15)/1200 each.
std::array<TrianglePoint, 7> make_rule7() {
  const double root15 = std::sqrt(15.0);
  const auto near_vertices = orbit((6.0 - root15) / 21.0, (155.0 - root15) / 1200.0);
  const auto near_edges = orbit((6.0 + root15) / 21.0, (155.0 + root15) / 1200.0);
  return {TrianglePoint{{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}, 9.0 / 40.0},
          near_vertices[0],
          near_vertices[1],
          near_vertices[2],
          near_edges[0],
          near_edges[1],
          near_edges[2]};
}

const std::array<TrianglePoint, 7> kRule7 = make_rule7();

[[noreturn]] void unavailable(int points) {
  throw std::invalid_argument("triangle quadrature with " + std::to_string(points) +
                              " points is not available; choose 1, 3 or 7 points");
}

}  // namespace

int triangle_rule_degree(int points) {
  switch (points) {
    case 1:
      return 1;
    case 3:
      return 2;
    case 7:
      return 5;
    default:
      unavailable(points);
  }
}

std::span<const TrianglePoint> triangle_rule(int points) {
  switch (points) {
    case 1:
      return kRule1;
    case 3:
      return kRule3;
    case 7:
      return kRule7;
    default:
      unavailable(points);
  }
}

}  // namespace fsi::contact
