#pragma once
// Symmetric quadrature rules on a triangle in barycentric coordinates (thesis §4.3, 3D remark:
// "7-point Gauss integration over a triangular area"). The weights of a rule sum to 1, so a
// triangle of area A contributes A * sum_k weight_k * f(point_k).
//
//   1 point : the centroid, exact for polynomials of degree 1
//   3 points: (2/3, 1/6, 1/6) and its permutations (Strang–Fix), degree 2
//   7 points: the centroid and two orbits of three points (Radon's rule, listed by Strang–Fix and
//             Dunavant), degree 5
//
// Every rule is invariant under permutations of the three vertices, so the sampling of a triangle
// does not depend on the order in which its vertices are listed.

#include <array>
#include <span>

namespace fsi::contact {

struct TrianglePoint {
  std::array<double, 3> barycentric;  // non-negative, sum to 1
  double weight;                      // weights of one rule sum to 1
};

// The point counts for which a rule exists.
inline constexpr std::array<int, 3> kTriangleRulePoints = {1, 3, 7};

// Polynomial degree integrated exactly by the rule with this many points (1 -> 1, 3 -> 2, 7 -> 5).
// Throws std::invalid_argument like triangle_rule().
int triangle_rule_degree(int points);

// Throws std::invalid_argument naming the requested count and the available ones (1, 3, 7).
std::span<const TrianglePoint> triangle_rule(int points);

}  // namespace fsi::contact
