#pragma once
// Test support of the contact core, shared by its unit tests and bench/contact_scaling.cpp:
// particles owned in LAMMPS' layout (3 values per particle, also in 2D), the force law the tests
// exercise, and the exact wall integral the 2D accuracy is measured against.

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <cstddef>
#include <vector>

#include "fsi/contact/contact_evaluation.hpp"
#include "fsi/contact/force_law.hpp"

namespace fsi::contact::test_support {

struct ParticleCloud {
  std::vector<double> x, v, f;
  std::vector<int> mask;  // group bit 1: every particle takes part until a test clears it

  void add(const std::array<double, 3>& position,
           const std::array<double, 3>& velocity = {0.0, 0.0, 0.0}) {
    x.insert(x.end(), position.begin(), position.end());
    v.insert(v.end(), velocity.begin(), velocity.end());
    f.insert(f.end(), {0.0, 0.0, 0.0});
    mask.push_back(1);
  }
  // A particle of a 2D run: z = 0, no z velocity.
  void add(double px, double py, double vx = 0.0, double vy = 0.0) {
    add({px, py, 0.0}, {vx, vy, 0.0});
  }
  std::size_t count() const { return mask.size(); }
  ParticleArrays arrays() {
    ParticleArrays a;
    a.count = count();
    a.positions = x.data();
    a.velocities = v.data();
    a.forces = f.data();
    a.group_mask = mask;
    a.group_bit = 1;
    return a;
  }
  void clear_forces() { std::fill(f.begin(), f.end(), 0.0); }
};

// k = 1000 with r0 = 0.8 r_c, so that both repulsion and adhesion are exercised.
inline ForceLaw adhesive_law(double cutoff, double viscous_scale) {
  ForceLaw law;
  law.repulsion_scale = 1000.0;
  law.viscous_scale = viscous_scale;
  law.cutoff = cutoff;
  law.equilibrium_distance = 0.8 * cutoff;
  return law;
}

// The exact line integral of the repulsive density over an infinite straight wall at distance d
// (adaptive Gauss–Kronrod).
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
