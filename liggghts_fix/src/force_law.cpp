#include "fsi/contact/force_law.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
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
