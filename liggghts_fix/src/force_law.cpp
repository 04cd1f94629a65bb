#include "fsi/contact/force_law.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace fsi::contact {
namespace {

constexpr int kMaxExponent = 24;
constexpr double kCoreFraction = 0.1;  // Lennard-Jones core radius / r_0

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

}  // namespace

void ForceLaw::validate() const {
  require(std::isfinite(cutoff) && cutoff > 0.0,
          "cutoff r_c must be a positive length (typically 2h), got " + number(cutoff));
  require(std::isfinite(equilibrium_distance) && equilibrium_distance > 0.0 &&
              equilibrium_distance <= cutoff,
          "equilibrium distance r0 must satisfy 0 < r0 <= cutoff (" + number(cutoff) + "), got " +
              number(equilibrium_distance));
  require(std::isfinite(viscous_cutoff) && viscous_cutoff >= 0.0,
          "viscous cutoff must be a positive length (0 = same as cutoff), got " +
              number(viscous_cutoff));
  require(std::isfinite(repulsion_scale) && repulsion_scale >= 0.0,
          "repulsion scale k must be >= 0, got " + number(repulsion_scale));
  require(std::isfinite(viscous_scale) && viscous_scale >= 0.0,
          "viscous scale t must be >= 0, got " + number(viscous_scale));
  if (repulsion_law == RepulsionLaw::LennardJones) {
    require(lj_p2 >= 1 && lj_p1 > lj_p2 && lj_p1 <= kMaxExponent,
            "Lennard-Jones exponents must satisfy 1 <= p2 < p1 <= " + std::to_string(kMaxExponent) +
                " (thesis: 4 2 or 12 6), got p1 = " + std::to_string(lj_p1) +
                ", p2 = " + std::to_string(lj_p2));
  }
}

double ForceLaw::repulsion(double distance) const {
  if (!(distance < cutoff)) return 0.0;  // also NaN
  if (repulsion_law == RepulsionLaw::LennardJones) {
    const double ratio =
        equilibrium_distance / std::max(distance, kCoreFraction * equilibrium_distance);
    return repulsion_scale * (std::pow(ratio, lj_p1) - std::pow(ratio, lj_p2));
  }
  const double gap = cutoff - distance;
  const double rest = cutoff - equilibrium_distance;
  const double gap2 = gap * gap;
  return repulsion_scale * (gap2 * gap2 - rest * rest * gap2) /
         (cutoff * cutoff * equilibrium_distance * (2.0 * cutoff - equilibrium_distance));
}

double ForceLaw::steepest_repulsion_slope() const {
  if (repulsion_law == RepulsionLaw::LennardJones) {
    // Inside the core the law is constant; outside it the slope only falls off with distance.
    const double core = kCoreFraction * equilibrium_distance;
    const double ratio = equilibrium_distance / core;
    return repulsion_scale * (lj_p1 * std::pow(ratio, lj_p1) - lj_p2 * std::pow(ratio, lj_p2)) /
           core;
  }
  // d f_rep / d d = -k (4 g^3 - 2 (r_c - r_0)^2 g) / (r_c^2 r_0 (2 r_c - r_0)) with g = r_c - d is
  // steepest at g = r_c.
  const double rest = cutoff - equilibrium_distance;
  return repulsion_scale * (4.0 * cutoff * cutoff - 2.0 * rest * rest) /
         (cutoff * equilibrium_distance * (2.0 * cutoff - equilibrium_distance));
}

double ForceLaw::viscous_weight(double distance) const {
  const double support = effective_viscous_cutoff();
  if (!(distance < support)) return 0.0;
  if (viscous_kernel == ViscousKernel::CubicSpline) {
    const double q = 2.0 * distance / support;  // R = d/h with support 2h
    if (q < 1.0) return 1.0 - 1.5 * q * q + 0.75 * q * q * q;
    const double rest = 2.0 - q;
    return 0.25 * rest * rest * rest;
  }
  return 1.0 - distance / support;
}

namespace {

// Composite Gauss-Legendre rule on [a, b], 32 panels of 5 points: the integrands below are smooth
// (the law is a polynomial in r), and this rule reproduces them to ~1e-12 relative.
template <class Integrand>
double integrate(Integrand&& integrand, double a, double b) {
  static constexpr double kNodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                       0.5384693101056831, 0.9061798459386640};
  static constexpr double kWeights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                         0.4786286704993665, 0.2369268850561891};
  constexpr int kPanels = 32;
  const double width = (b - a) / kPanels;
  double sum = 0.0;
  for (int panel = 0; panel < kPanels; ++panel) {
    const double centre = a + (panel + 0.5) * width;
    for (int node = 0; node < 5; ++node) {
      sum += kWeights[node] * integrand(centre + 0.5 * width * kNodes[node]);
    }
  }
  return 0.5 * width * sum;
}

void require_dimension(int dimension) {
  require(dimension == 2 || dimension == 3,
          "the wall's dimension must be 2 or 3, got " + std::to_string(dimension));
}

}  // namespace

double flat_wall_force(const ForceLaw& law, double distance, int dimension) {
  require_dimension(dimension);
  const double z = distance;
  if (!(z > 0.0) || !(z < law.cutoff)) return 0.0;
  if (dimension == 3) {
    return 2.0 * std::numbers::pi * z *
           integrate([&](double r) { return law.repulsion(r); }, z, law.cutoff);
  }
  // s = z sinh(u) takes the peak of z / r at s ~ z out of the integrand: F = 2 z int f(z cosh u)
  // du.
  const double reach = std::acosh(law.cutoff / z);
  return 2.0 * z * integrate([&](double u) { return law.repulsion(z * std::cosh(u)); }, 0.0, reach);
}

double rest_distance(const ForceLaw& law, double pressure, double spacing, int dimension) {
  require_dimension(dimension);
  const double load = pressure * (dimension == 3 ? spacing * spacing : spacing);
  // March inwards from the cut-off to the first distance where the wall holds the load, then
  // bisect: with adhesion (r_0 < r_c) F changes sign, and the outermost crossing is where a layer
  // pressed from outside comes to rest.
  constexpr int kMarch = 400;
  const double step = law.cutoff / kMarch;
  double outer = law.cutoff;
  double inner = -1.0;
  for (int i = 1; i < kMarch; ++i) {
    const double z = law.cutoff - i * step;
    if (flat_wall_force(law, z, dimension) >= load) {
      inner = z;
      break;
    }
    outer = z;
  }
  if (inner < 0.0) return 0.0;
  for (int i = 0; i < 60; ++i) {
    const double middle = 0.5 * (inner + outer);
    (flat_wall_force(law, middle, dimension) >= load ? inner : outer) = middle;
  }
  return 0.5 * (inner + outer);
}

void apply_true_shape(ForceLaw& law, const TrueShape& shape, int dimension) {
  require(std::isfinite(shape.spacing) && shape.spacing > 0.0,
          "the true-shape wall needs the particle spacing d > 0, got " + number(shape.spacing));
  require(std::isfinite(shape.pressure) && shape.pressure > 0.0,
          "the true-shape wall needs a reference pressure > 0 (e.g. rho0 g H / 2), got " +
              number(shape.pressure));
  law.repulsion_law = RepulsionLaw::Thesis;
  law.cutoff = kTrueShapeCutoffFraction * shape.spacing;
  law.equilibrium_distance = law.cutoff;
  law.repulsion_scale = 1.0;
  const double unit_force = flat_wall_force(law, kTrueShapeRestFraction * shape.spacing, dimension);
  const double load =
      shape.pressure * (dimension == 3 ? shape.spacing * shape.spacing : shape.spacing);
  law.repulsion_scale = load / unit_force;
}

const char* name(RepulsionLaw law) {
  return law == RepulsionLaw::LennardJones ? "lj" : "thesis";
}

const char* name(ViscousKernel kernel) {
  return kernel == ViscousKernel::CubicSpline ? "cubic" : "spiky";
}

std::string describe(const ForceLaw& law) {
  std::string text =
      std::string("law ") + name(law.repulsion_law) + ", k = " + number(law.repulsion_scale) +
      ", r0 = " + number(law.equilibrium_distance) + ", cutoff = " + number(law.cutoff);
  if (law.repulsion_law == RepulsionLaw::LennardJones) {
    text += ", p1 = " + std::to_string(law.lj_p1) + ", p2 = " + std::to_string(law.lj_p2);
  }
  text += std::string(", viscous kernel ") + name(law.viscous_kernel) +
          ", t = " + number(law.viscous_scale) +
          ", viscous cutoff = " + number(law.effective_viscous_cutoff());
  return text;
}

}  // namespace fsi::contact
