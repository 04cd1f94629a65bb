#pragma once
// SPH–wall force densities of thesis eq. (4.2) with the renormalised spiky-kernel Laplacian (5.5).
//
// With the cut-off r_c = 2h, a particle at distance d from a surface point feels, per unit surface
// measure (per unit length of a 2D segment),
//   repulsion  f_rep(d)  = k [(r_c - d)^4 - (r_c - r_0)^2 (r_c - d)^2] / [r_c^2 r_0 (2 r_c - r_0)]
//   viscosity  f_visc    = -(t/2) (2 - d/h) v_rel = -t (1 - d/r_c) v_rel
// for 0 <= d <= r_c and zero beyond. f_rep(0) = k, f_rep(r_0) = 0 and, for r_0 < r_c, the law is
// attractive (adhesion) between r_0 and r_c. The repulsion acts along (r_particle - r_surface).

#include <string>

namespace fsi::contact {

struct ForceLaw {
  double repulsion_scale = 0.0;       // k [N/m^2 in 2D]: force density at zero distance
  double viscous_scale = 0.0;         // t [N s/m^3 in 2D]: wall friction scale (thesis eq. 6.4)
  double equilibrium_distance = 0.0;  // r_0 [m], 0 < r_0 <= r_c
  double cutoff = 0.0;                // r_c = 2h [m]

  // Throws std::invalid_argument naming the offending parameter and its admissible range.
  void validate() const;

  // Largest distance at which any part of the law acts: the radius for neighbour search.
  double range() const { return cutoff; }

  // Magnitude of the repulsive density at distance d (negative = attraction); 0 beyond r_c.
  double repulsion(double distance) const;
  // Factor w(d) such that the viscous density is -viscous_scale * w(d) * v_rel; 0 beyond r_c.
  double viscous_weight(double distance) const;
};

std::string describe(const ForceLaw& law);

}  // namespace fsi::contact
