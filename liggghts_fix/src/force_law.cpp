#include "fsi/contact/force_law.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace fsi::contact {

void ForceLaw::validate() const {
  auto require = [](bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument(message);
  };
  require(std::isfinite(cutoff) && cutoff > 0.0,
          "cutoff r_c must be a positive length (typically 2h), got " + std::to_string(cutoff));
  require(std::isfinite(equilibrium_distance) && equilibrium_distance > 0.0 &&
              equilibrium_distance <= cutoff,
          "equilibrium distance r0 must satisfy 0 < r0 <= cutoff (" + std::to_string(cutoff) +
              "), got " + std::to_string(equilibrium_distance));
  require(std::isfinite(repulsion_scale) && repulsion_scale >= 0.0,
          "repulsion scale k must be >= 0, got " + std::to_string(repulsion_scale));
  require(std::isfinite(viscous_scale) && viscous_scale >= 0.0,
          "viscous scale t must be >= 0, got " + std::to_string(viscous_scale));
}

double ForceLaw::repulsion(double distance) const {
  if (distance >= cutoff) return 0.0;
  const double gap = cutoff - distance;
  const double rest = cutoff - equilibrium_distance;
  const double gap2 = gap * gap;
  return repulsion_scale * (gap2 * gap2 - rest * rest * gap2) /
         (cutoff * cutoff * equilibrium_distance * (2.0 * cutoff - equilibrium_distance));
}

double ForceLaw::viscous_weight(double distance) const {
  if (distance >= cutoff) return 0.0;
  return 1.0 - distance / cutoff;
}

std::string describe(const ForceLaw& law) {
  char text[256];
  std::snprintf(text, sizeof text, "k = %.6g, t = %.6g, r0 = %.6g, cutoff = %.6g",
                law.repulsion_scale, law.viscous_scale, law.equilibrium_distance, law.cutoff);
  return text;
}

}  // namespace fsi::contact
