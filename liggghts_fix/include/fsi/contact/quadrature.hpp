#pragma once
// Gauss–Legendre rules on the unit interval [0, 1] (thesis Table 4.1 for three points). The
// weights sum to 1, so a segment of length l contributes l * sum_k weight_k * f(g_k).

#include <span>

namespace fsi::contact {

struct QuadraturePoint {
  double position;  // g in [0, 1] along the segment
  double weight;    // weights of one rule sum to 1
};

inline constexpr int kMinGaussPoints = 1;
inline constexpr int kMaxGaussPoints = 5;

// Throws std::invalid_argument unless 1 <= points <= 5.
std::span<const QuadraturePoint> gauss_legendre(int points);

}  // namespace fsi::contact
