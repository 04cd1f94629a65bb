#pragma once
// What the ANCF beam elements share (internal): Gauss-Legendre rules on [-1, 1] and the cubic
// Hermite shape functions of an element of length l, with their first and second derivatives
// along the undeformed arc length. The planar beam (ancf_beam_2d.cpp) and the spatial cable
// (ancf_cable_3d.cpp) interpolate r(x) = sum_k N_k(x) d_k over the nodal vectors
// d = (r_0, r'_0, r_1, r'_1).

#include <Eigen/Dense>

#include <array>
#include <string>

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

// The problems of an elastic line's parameters, each as " ...;" (empty if none): element count,
// EA, EI, rho A, non-negative damping.
std::string elastic_line_problems(int elements, double axial_stiffness, double bending_stiffness,
                                  double mass_per_length, double axial_damping,
                                  double bending_damping);

// The integrals of the shape functions over an element of length l: (l/2, l^2/12, l/2, -l^2/12).
inline Eigen::Vector4d hermite_integrals(double l) {
  return {0.5 * l, l * l / 12.0, 0.5 * l, -l * l / 12.0};
}

// rho A integral of S^T g over `elements` elements of length l (nodes of 2 D coordinates): the
// generalised force of a uniform field g, added.
template <int D>
void add_uniform_field_force(int elements, double l, double mass_per_length,
                             const Eigen::Matrix<double, D, 1>& g,
                             Eigen::Ref<Eigen::VectorXd> force) {
  const Eigen::Vector4d integral = hermite_integrals(l);
  for (int e = 0; e < elements; ++e) {
    for (int k = 0; k < 4; ++k)
      force.template segment<D>(2 * D * e + D * k) += mass_per_length * integral(k) * g;
  }
}

// The centre of the deformed line (of mass, for a uniform rho A): (1/L) integral r dx.
template <int D>
Eigen::Matrix<double, D, 1> line_centre(const Eigen::Ref<const Eigen::VectorXd>& q, int elements,
                                        double l) {
  const Eigen::Vector4d integral = hermite_integrals(l);
  Eigen::Matrix<double, D, 1> sum = Eigen::Matrix<double, D, 1>::Zero();
  for (int e = 0; e < elements; ++e) {
    for (int k = 0; k < 4; ++k)
      sum += integral(k) * q.template segment<D>(2 * D * e + D * k);
  }
  return sum / (elements * l);
}

}  // namespace fsi::mbd::detail
