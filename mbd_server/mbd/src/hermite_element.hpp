#pragma once
// What the ANCF beam elements share (internal): Gauss-Legendre rules on [-1, 1] and the cubic
// Hermite shape functions of an element of length l, with their first and second derivatives
// along the undeformed arc length. The planar beam (ancf_beam_2d.cpp) and the spatial cable
// (ancf_cable_3d.cpp) interpolate r(x) = sum_k N_k(x) d_k over the nodal vectors
// d = (r_0, r'_0, r_1, r'_1).

#include <Eigen/Dense>

#include <array>

namespace fsi::mbd::detail {

struct GaussRule {
  std::array<double, 5> points{};
  std::array<double, 5> weights{};
  int size = 0;
};

// 3, 4 or 5 points (exact for polynomials of degree 5, 7, 9).
GaussRule gauss_rule(int size);

struct HermiteShape {
  Eigen::Vector4d value;
  Eigen::Vector4d first;
  Eigen::Vector4d second;
};

// At x in [0, l], in the order (r_0, r'_0, r_1, r'_1).
HermiteShape hermite_shape(double x, double l);

// The D x 4D matrix [N_1 I, N_2 I, N_3 I, N_4 I] that maps the element coordinates to a vector
// field (D = 2: the planar beam, D = 3: the spatial cable).
template <int D>
Eigen::Matrix<double, D, 4 * D> expand(const Eigen::Vector4d& n) {
  Eigen::Matrix<double, D, 4 * D> m = Eigen::Matrix<double, D, 4 * D>::Zero();
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i < D; ++i)
      m(i, D * k + i) = n(k);
  }
  return m;
}

}  // namespace fsi::mbd::detail
