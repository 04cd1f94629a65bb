#pragma once
// SPH–wall force densities of thesis §4.2, per unit surface measure (per unit length of a 2D
// segment, per unit area of a 3D triangle).
//
// Repulsion, acting along (r_particle - r_surface), 0 beyond the repulsive cut-off r_c:
//   thesis (4.2)        f_rep(d) = k [(r_c - d)^4 - (r_c - r_0)^2 (r_c - d)^2] / [r_c^2 r_0 (2 r_c
//   - r_0)]
//                       f_rep(0) = k, f_rep(r_0) = 0, adhesion between r_0 and r_c when r_0 < r_c.
//   Lennard-Jones (4.3) f_rep(d) = k [(r_0/d)^p1 - (r_0/d)^p2], p1 > p2 >= 1; below the core
//                       radius r_0/10 the law is held at its value there so that it stays finite.
// Viscosity, f_visc = -t w(d) v_rel for d < r_v (the viscous cut-off, = r_c by default):
//   spiky (5.5)         w(d) = (1/2)(1/alpha) Laplacian W = 1 - d/r_v   (= (2 - d/h)/2 with r_v =
//   2h) cubic               w(d) = W_cubic(d)/W_cubic(0): the shape of the cubic spline kernel
//   (3.22)
//                       with support r_v, equal to the spiky weight at contact. (The literal
//                       Laplacian of (3.22) changes sign at d = 0.44 r_v in 2D and would push
//                       particles along the wall; it is not offered.)

#include <string>

namespace fsi::contact {

enum class RepulsionLaw { Thesis, LennardJones };
enum class ViscousKernel { Spiky, CubicSpline };

struct ForceLaw {
  double repulsion_scale = 0.0;  // k [N/m^2 in 2D]: force density at zero distance (thesis law)
  double viscous_scale = 0.0;    // t [N s/m^3 in 2D]: wall friction scale (thesis eq. 6.4)
  double equilibrium_distance = 0.0;  // r_0 [m], 0 < r_0 <= r_c
  double cutoff = 0.0;                // r_c = 2h [m]: range of the repulsion
  double viscous_cutoff = 0.0;        // r_v [m]: range of the viscous term; 0 = same as r_c
  RepulsionLaw repulsion_law = RepulsionLaw::Thesis;
  ViscousKernel viscous_kernel = ViscousKernel::Spiky;
  int lj_p1 = 4;  // Lennard-Jones exponents (thesis: 4/2 or 12/6)
  int lj_p2 = 2;

  // Throws std::invalid_argument naming the offending parameter and its admissible range.
  void validate() const;

  double effective_viscous_cutoff() const { return viscous_cutoff > 0.0 ? viscous_cutoff : cutoff; }
  // Largest distance at which any part of the law acts: the radius for neighbour search.
  double range() const {
    const double viscous = effective_viscous_cutoff();
    return viscous > cutoff ? viscous : cutoff;
  }

  // Magnitude of the repulsive density at distance d (negative = attraction); 0 beyond r_c.
  double repulsion(double distance) const;
  // Factor w(d) such that the viscous density is -viscous_scale * w(d) * v_rel; 0 beyond r_v.
  double viscous_weight(double distance) const;
  // Largest |d f_rep / d d|, the stiffness of the wall against a particle pressed into it
  // [N/m^3 per unit depth in 2D]. Thesis law: at contact, d = 0, k (4 r_c^2 - 2 (r_c - r_0)^2) /
  // (r_c r_0 (2 r_c - r_0)), 4 k / r_c for r_0 = r_c. Lennard-Jones: at its core radius r_0/10.
  double steepest_repulsion_slope() const;
};

// The wall as the fluid's lattice sees it (docs/theory.md, "The true shape"). A particle in the
// first layer at distance z from a flat wall feels the wall's force integrated over the whole
// plane (2D: over a line), F(z); it rests where F equals the pressure p on the area it stands for
// (2D: p d per unit depth, 3D: p d^2).
//   2D: F(z) = 2 int_0^sqrt(r_c^2 - z^2) f(sqrt(z^2 + s^2)) z / sqrt(z^2 + s^2) ds
//   3D: F(z) = 2 pi z int_z^r_c f(r) dr
double flat_wall_force(const ForceLaw& law, double distance, int dimension);
// The z at which F(z) = p d^(dimension-1), searched from the cut-off inwards (the outermost
// rest point); 0 when the wall cannot hold the pressure at any distance.
double rest_distance(const ForceLaw& law, double pressure, double spacing, int dimension);

// The true-shape wall: the thesis law (r_0 = r_c, no adhesion) whose first particle layer rests
// at kTrueShapeRestFraction * d under the reference pressure, with r_c = kTrueShapeCutoffFraction
// * d. A lattice of spacing d whose first layer rests there fills the volume up to the mesh: the
// fluid sees the body's true outline (measured, docs/validation.md, "True shape").
inline constexpr double kTrueShapeRestFraction = 0.75;
inline constexpr double kTrueShapeCutoffFraction = 1.125;
struct TrueShape {
  double spacing = 0.0;   // d [m]: the particle lattice constant
  double pressure = 0.0;  // p_ref [Pa]: the pressure at which the first layer rests at 0.75 d
};
// Fills k, r_0 and r_c of `law` (its viscous part is kept); throws std::invalid_argument for a
// non-positive spacing or pressure.
void apply_true_shape(ForceLaw& law, const TrueShape& shape, int dimension);

std::string describe(const ForceLaw& law);
const char* name(RepulsionLaw law);
const char* name(ViscousKernel kernel);

}  // namespace fsi::contact
