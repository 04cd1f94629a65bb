#pragma once
// The reference the 2D contact's accuracy is measured against: the exact line integral of the
// repulsive density over an infinite straight wall at distance d (adaptive Gauss–Kronrod).

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>

#include "fsi/contact/force_law.hpp"

namespace fsi::contact::test_support {

inline double exact_wall_repulsion(const ForceLaw& law, double d, unsigned max_depth,
                                   double tolerance) {
  if (d >= law.cutoff) return 0.0;
  const double reach = std::sqrt(law.cutoff * law.cutoff - d * d);
  auto normal_density = [&](double s) {
    const double rho = std::hypot(d, s);
    return law.repulsion(rho) * d / rho;
  };
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(normal_density, -reach,
                                                                       reach, max_depth, tolerance);
}

}  // namespace fsi::contact::test_support
