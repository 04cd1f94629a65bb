#pragma once
// Is the water at rest when the bodies are released (docs/user-guide.md, "Equilibration")? Judged
// from the fluid's state after the equilibration and script 2 (what fsi-client reports in its
// ReleaseState) and the fluid's force on every mesh at t = 0: a fluid at rest rests its whole
// weight on the structure and has almost no kinetic energy.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "fsi/protocol/messages.hpp"

namespace fsi::coupling {

// Limits of "at rest" (docs/user-guide.md, "Equilibration"): the structure carries the fluid's
// weight within 1 %, and the kinetic energy is at most 1e-3 of the potential energy above the
// lowest particle. Measured (docs/validation.md): settled columns 2e-6 to 1.3e-4, a 13 cm column
// without the settling drag 4e-3 after 0.1 s and 1.7e-2 after 0.025 s of equilibration.
inline constexpr double kRestWeightFractionLow = 0.99;
inline constexpr double kRestWeightFractionHigh = 1.01;
inline constexpr double kRestKineticOverPotential = 1e-3;
// A fluid this still (kinetic over potential energy) with its weight within kNearMissWeightFraction
// of the structure's load has settled as far as it will: the warning then says that more time
// does not help, and what carries the rest.
inline constexpr double kStillKineticOverPotential = 1e-4;
inline constexpr double kNearMissWeightFraction = 0.05;
// Below this fraction of the weight the structure may not hold the fluid where it is at all (a
// dam break's column with nothing at its open side collapsed to 59 % in 0.28 s of settling):
// the warning adds how to hold such water.
inline constexpr double kUnheldWeightFraction = 0.9;

struct ReleaseCheck {
  double settling_drag = 0.0;             // [1/s] applied during the equilibration
  double column_height = 0.0;             // [m]
  double fluid_mass = 0.0;                // [kg; 2D kg/m]
  double weight = 0.0;                    // M |g| [N; 2D N/m]
  double carried = 0.0;                   // fluid force on all meshes along g [N; 2D N/m]
  std::optional<double> weight_fraction;  // carried / weight; none without weight
  double kinetic_energy = 0.0;
  double potential_energy = 0.0;
  std::optional<double> kinetic_over_potential;  // none without potential energy
  bool at_rest = true;
  std::string warning;  // empty when at rest: otherwise what is wrong and what to change
};

// force_on_structure: the fluid's force on every mesh at t = 0 (walls included); gravity: the
// scene's. equilibration_steps and the scene's settling_drag word the advice.
ReleaseCheck check_release(const protocol::ReleaseState& release,
                           const std::array<double, 3>& force_on_structure,
                           const std::array<double, 3>& gravity, std::uint64_t equilibration_steps,
                           std::optional<double> scene_settling_drag);

}  // namespace fsi::coupling
