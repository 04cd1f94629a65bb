#include "fsi/coupling/release_check.hpp"

#include <spdlog/fmt/fmt.h>

#include <cmath>

namespace fsi::coupling {
ReleaseCheck check_release(const protocol::ReleaseState& release,
                           const std::array<double, 3>& force_on_structure,
                           const std::array<double, 3>& gravity, std::uint64_t equilibration_steps,
                           std::optional<double> scene_settling_drag) {
  ReleaseCheck check;
  check.settling_drag = release.drag_rate;
  check.column_height = release.column_height;
  check.fluid_mass = release.fluid_mass;
  check.kinetic_energy = release.kinetic_energy;
  check.potential_energy = release.potential_energy;
  const double g = std::hypot(gravity[0], gravity[1], gravity[2]);
  check.weight = release.fluid_mass * g;
  if (g > 0.0) {
    for (int k = 0; k < 3; ++k)
      check.carried += force_on_structure[k] * gravity[k] / g;
  }
  if (check.weight > 0.0) check.weight_fraction = check.carried / check.weight;
  if (release.potential_energy > 0.0) {
    check.kinetic_over_potential = release.kinetic_energy / release.potential_energy;
  }

  std::string problems;
  if (check.weight_fraction && (*check.weight_fraction < kRestWeightFractionLow ||
                                *check.weight_fraction > kRestWeightFractionHigh)) {
    problems += "the structure carries " + fmt::format("{:.1f}", 100.0 * *check.weight_fraction) +
                " % of the fluid's weight (99 to 101 % at rest)";
  }
  if (check.kinetic_over_potential && *check.kinetic_over_potential > kRestKineticOverPotential) {
    if (!problems.empty()) problems += ", and ";
    problems += "its kinetic energy is " + fmt::format("{:.2e}", *check.kinetic_over_potential) +
                " of its potential energy above the lowest particle (at most " +
                fmt::format("{:.0e}", kRestKineticOverPotential) + " at rest)";
  }
  if (problems.empty()) return check;
  check.at_rest = false;
  // Still water a few per cent short of (or over) its weight. The settling drag carries lambda M
  // <v> along g of water still creeping down; <v> is at most the particles' rms speed, so the
  // drag's share of the weight is at most lambda v_rms / g. Below the gap, time cannot close it
  // (something else holds the rest); above it, the water may still be sinking (a user's flume,
  // 2026-12-06: 98.3 % after 4 000 steps, 99.67 % after 20 000) or creeping for good as the
  // lattice packs closer at the floor (a user's baffle tank: 98.8 % after 5 000 steps, 98.5 % after
  // 10 000): only a longer settling tells them apart.
  const bool still =
      check.kinetic_over_potential && *check.kinetic_over_potential <= kStillKineticOverPotential;
  const bool near_miss =
      check.weight_fraction && std::abs(*check.weight_fraction - 1.0) <= kNearMissWeightFraction;
  if (still && near_miss) {
    const double rms_speed = release.fluid_mass > 0.0
                                 ? std::sqrt(2.0 * release.kinetic_energy / release.fluid_mass)
                                 : 0.0;
    const double drag_share = g > 0.0 ? release.drag_rate * rms_speed / g : 0.0;
    const double gap = std::abs(*check.weight_fraction - 1.0);
    const std::string head =
        "the fluid is still when the bodies are released (its kinetic energy is " +
        fmt::format("{:.2e}", *check.kinetic_over_potential) +
        " of its potential energy above the lowest particle), but " + problems;
    const std::string share = fmt::format(
        "the settling drag of {:.4g} 1/s carries at most lambda v_rms / g = {:.2f} % of the "
        "weight (v_rms = sqrt(2 E_kin / M) = {:.3g} mm/s)",
        release.drag_rate, 100.0 * drag_share, 1e3 * rms_speed);
    if (drag_share < gap) {
      check.warning = head + ": more settling time will not close this: " + share +
                      ", less than the gap. The rest is carried by what the server does not see: "
                      "a LIGGGHTS wall, region or fix of the scripts. The structure takes up the "
                      "difference at the release (docs/user-guide.md, \"Equilibration\")";
    } else {
      check.warning =
          head + ": " + share +
          ", enough to hold the rest if the water is still creeping down. Settle it twice as "
          "long (LIGGGHTS { equilibration_steps }, now " +
          std::to_string(equilibration_steps) +
          ", or equilibration_time) and compare: a share that rises towards 100 % was still "
          "sinking; one that stays is the lattice packing closer at the floor, which more time "
          "does not end (a finer spacing narrows it; docs/user-guide.md, \"Equilibration\")";
    }
    return check;
  }
  const std::string steps = std::to_string(equilibration_steps);
  std::string drag;
  if (!scene_settling_drag) {
    drag = "the automatic settling drag of " + fmt::format("{:.4g}", release.drag_rate) +
           " 1/s did not suffice in that time";
  } else if (*scene_settling_drag == 0.0) {
    drag =
        "LIGGGHTS { settling_drag = 0 } turns the settling drag off: remove it to get the "
        "automatic one";
  } else {
    drag = "LIGGGHTS { settling_drag = " + fmt::format("{:.4g}", *scene_settling_drag) +
           " } may be far from critical: remove it to get the automatic one";
  }
  check.warning = "the fluid is not at rest when the bodies are released: " + problems +
                  ". Give it more time (LIGGGHTS { equilibration_steps }, now " + steps +
                  ", or equilibration_time in seconds); " + drag +
                  " (docs/user-guide.md, \"Equilibration\")";
  if (check.weight_fraction && *check.weight_fraction < kUnheldWeightFraction) {
    check.warning +=
        "; if no structure holds this fluid where it starts (a dam break's column), more time "
        "lets it flow away: hold it during the equilibration with a LIGGGHTS wall that script 2 "
        "removes (docs/user-guide.md, \"Holding water that the structure does not hold\"; "
        "examples/dam_break)";
  }
  return check;
}

}  // namespace fsi::coupling
