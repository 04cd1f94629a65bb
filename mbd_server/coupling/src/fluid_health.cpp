#include "fsi/coupling/fluid_health.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fsi/common/text.hpp"
#include "fsi/scene/physics_checks.hpp"

namespace fsi::coupling {
namespace {

// dt c / h measured stable here (docs/user-guide.md, "Physics checks": below the thesis' 0.25).
constexpr double kStableCourant = 0.125;

// Beyond the measured-stable ratio by more than the three digits printed (else the advice would
// read "reduce from 6.67e-06 s to at most 6.67e-06 s").
bool beyond_stable(double courant) {
  return courant > kStableCourant * (1.0 + 1e-3);
}

// dt c / h measured stable through a dam break's impact on a wall (examples/dam_break/
// stability_map.json, docs/validation.md "Stability maps": the coarse Martin & Moyce dam break
// ran at 0.092 with |rho/rho0 - 1| <= 0.4 % and stopped at 3 % at 0.115, whatever the wall).
constexpr double kImpactStableCourant = 0.092;
// A wall law whose reach r_c is shorter than this many h is named first when the wall breaks.
constexpr double kShortWallReach = 1.0;
// Weakly compressible SPH aims at |rho/rho0 - 1| <= 1 % (Monaghan 1994: c >= 10 v_max).
constexpr double kDensityAim = 0.01;

std::string number(double value) {
  return significant(value, 3);
}

// A value the advice compares with a limit or a present value: enough significant digits (up to
// 6) that it does not print as that reference (0.01004 against the 1 % aim, not "0.01").
std::string number_beside(double value, double reference) {
  for (int digits = 3; digits <= 6; ++digits) {
    std::string text = significant(value, digits);
    if (text != significant(reference, digits)) return text;
  }
  return number(value);
}

// A speed to reach at least: rounded up to 3 significant digits (20.08 -> 20.1, never down).
std::string number_up(double value) {
  if (!(value > 0.0) || !std::isfinite(value)) return number(value);
  const double scale = std::pow(10.0, std::floor(std::log10(value)) - 2.0);
  return number(std::ceil(value / scale - 1e-9) * scale);
}

std::string at_step(std::uint64_t step) {
  return step == 0 ? std::string("at release (step 0)") : "at step " + std::to_string(step);
}

bool finite_forces(const FluidForces& forces) {
  const auto& d = forces.diagnostics;
  auto finite = [](double value) { return std::isfinite(value); };
  return std::all_of(forces.forces.begin(), forces.forces.end(), finite) &&
         std::all_of(d.force_on_fluid.begin(), d.force_on_fluid.end(), finite) &&
         std::all_of(d.force_on_structure.begin(), d.force_on_structure.end(), finite) &&
         std::isfinite(d.pair_force_magnitude_sum) && !std::isnan(d.closest_approach_over_r0);
}

std::optional<double> sph_number(const scene::Scene& scene, const std::string& name) {
  for (const auto& [key, value] : scene.liggghts.variables) {
    if (key != name) continue;
    try {
      std::size_t used = 0;
      const double parsed = std::stod(value, &used);
      if (used == value.size() && std::isfinite(parsed)) return parsed;
    } catch (const std::exception&) {
    }
  }
  return std::nullopt;
}

}  // namespace

FluidHealthMonitor::FluidHealthMonitor(const scene::FluidHealthLimits& limits,
                                       std::uint64_t allowed_lost_particles, FluidScales scales)
    : limits_(limits), allowed_lost_(allowed_lost_particles), scales_(std::move(scales)) {
  closest_over_r0_ = std::numeric_limits<double>::infinity();
}

HealthVerdict FluidHealthMonitor::judge(std::uint64_t step, const FluidForces& forces) {
  HealthVerdict verdict;
  const double closest = forces.diagnostics.closest_approach_over_r0;
  if (!std::isnan(closest)) closest_over_r0_ = std::min(closest_over_r0_, closest);
  auto first = [&](std::optional<HealthFinding> finding) {
    if (!verdict.stop && finding) verdict.stop = std::move(finding);
  };
  first(non_finite(step, forces));
  first(wall_distance(step, closest));
  if (forces.health) {
    ++record_.steps_checked;
    first(density(step, *forces.health, verdict.warnings));
    first(mach(step, *forces.health, verdict.warnings));
  }
  const std::uint64_t count =
      forces.health ? forces.health->particle_count : forces.diagnostics.particle_count;
  first(lost(step, count, verdict.warnings));
  if (verdict.stop) record_.failed_check = verdict.stop->check;
  for (const HealthFinding& warning : verdict.warnings)
    record_.warnings.push_back(warning.message);
  return verdict;
}

std::optional<double> FluidHealthMonitor::courant_number() const {
  if (!scales_.speed_of_sound || !scales_.smoothing_length || !(scales_.time_step > 0.0))
    return std::nullopt;
  return scales_.time_step * *scales_.speed_of_sound / *scales_.smoothing_length;
}

std::string FluidHealthMonitor::time_step_advice() const {
  const std::optional<double> known = courant_number();
  if (!known) return {};
  const double courant = *known;
  std::string text = "dt c / h = " + number(courant);
  if (beyond_stable(courant)) {
    text += " exceeds the " + number(kStableCourant) +
            " measured stable: reduce SolverOptions.Timeint.step_size from " +
            number(scales_.time_step) + " s to at most " +
            number(scales_.time_step * kStableCourant / courant) + " s";
  } else {
    text += " (stable up to " + number(kStableCourant) + ")";
  }
  return text;
}

std::string FluidHealthMonitor::step_with_new_speed_of_sound() const {
  if (scales_.step_follows_speed_of_sound)
    return " (the step follows c by the Fluid block's time-step rule and keeps dt c / h)";
  return " and reduce SolverOptions.Timeint.step_size by the same factor to keep dt c / h";
}

std::optional<HealthFinding> FluidHealthMonitor::non_finite(std::uint64_t step,
                                                            const FluidForces& forces) const {
  std::string what;
  if (forces.health && forces.health->non_finite_particles > 0) {
    what = std::to_string(forces.health->non_finite_particles) + " of " +
           std::to_string(forces.health->particle_count) +
           " particles have a NaN or infinite position, velocity or density " + at_step(step);
  } else if (!finite_forces(forces)) {
    what = "the fluid forces of step " + std::to_string(step) +
           " are not finite (NaN or infinite forces on the structure)";
  } else if (forces.health && forces.health->particle_count > 0 &&
             !(std::isfinite(forces.health->max_speed) &&
               std::isfinite(forces.health->max_density) &&
               std::isfinite(forces.health->min_density))) {
    what = "the fluid's extremes are NaN or infinite " + at_step(step);
  }
  if (what.empty()) return std::nullopt;
  std::string fix = "the fluid blew up within one step, faster than the other checks could see; ";
  const std::string advice = time_step_advice();
  fix += "halve SolverOptions.Timeint.step_size" + (advice.empty() ? "" : " (now " + advice + ")");
  fix += ", and check the wall repulsion SPH_wall_rep (fsi-server --check prints the limits)";
  return HealthFinding{kCheckNonFinite, what, fix};
}

std::optional<HealthFinding> FluidHealthMonitor::wall_distance(std::uint64_t step,
                                                               double closest_over_r0) const {
  if (!(limits_.min_wall_distance > 0.0) || !(closest_over_r0 < limits_.min_wall_distance))
    return std::nullopt;
  HealthFinding finding;
  finding.check = kCheckWallDistance;
  finding.message =
      "a particle is " + number(closest_over_r0) + " r0 from a wall " + at_step(step) +
      ", closer than FluidHealth.min_wall_distance = " + number(limits_.min_wall_distance) +
      " r0: it has broken through the wall law (a fluid at rest keeps about 0.5 r0)";
  // The wall law's force at a given distance scales with k: a particle pressed to d/r0 by its
  // load stays near the distance it keeps at rest only if k grows by about the ratio of the two.
  const double factor = std::max(2.0, 0.5 / std::max(closest_over_r0, 0.05));
  // A reach shorter than h: the particles feel the wall only once their neighbours already push
  // them into it (measured on the water column: r_c = 0.25 h breaks through, 0.5 h holds, the
  // examples' 2 h keeps 0.5 r0). That is changed first.
  if (scales_.wall_cutoff && scales_.smoothing_length &&
      *scales_.wall_cutoff < kShortWallReach * *scales_.smoothing_length) {
    finding.fix = "the wall's reach r_c = " + number(*scales_.wall_cutoff) + " m is only " +
                  number(*scales_.wall_cutoff / *scales_.smoothing_length) +
                  " h: raise SPH_wall_cutoff (the fix's cutoff) to 2h = " +
                  number(2.0 * *scales_.smoothing_length) +
                  " m first (the examples' value); if the run still breaks through, ";
  }
  if (scales_.true_shape_pressure) {
    // The true-shape wall's repulsion scale is proportional to its reference pressure.
    finding.fix +=
        "raise the true-shape wall's reference pressure (fix fsi/sph pressure: "
        "Fluid.wall_pressure or SPH_wall_pressure) by a factor of " +
        number(factor) + ", from " + number(*scales_.true_shape_pressure) + " to " +
        number(factor * *scales_.true_shape_pressure) + " Pa";
  } else {
    finding.fix += "raise the wall repulsion SPH_wall_rep (k) by a factor of " + number(factor);
    if (scales_.wall_repulsion)
      finding.fix += ", from " + number(*scales_.wall_repulsion) + " to " +
                     number(factor * *scales_.wall_repulsion);
  }
  const std::string advice = time_step_advice();
  finding.fix += ", and keep the step below the contact limit of fsi-server --check" +
                 (advice.empty() ? std::string() : " (" + advice + ")");
  return finding;
}

std::string FluidHealthMonitor::settle_first(const std::string& fix, std::uint64_t step) const {
  if (unsettled_release_.empty()) return fix;
  if (scales_.settling_time > 0.0 &&
      static_cast<double>(step) * scales_.time_step > scales_.settling_time)
    return fix;
  return "the water was not at rest when the bodies were released (" + unsettled_release_ +
         "; the release warning says how to let it settle): settle it first, with "
         "LIGGGHTS.equilibration_steps (or equilibration_time); if the finding persists from a "
         "settled start: " +
         fix;
}

std::optional<HealthFinding> FluidHealthMonitor::density(std::uint64_t step,
                                                         const protocol::FluidHealth& health,
                                                         std::vector<HealthFinding>& warnings) {
  const double rho0 = scales_.rest_density;
  if (!(rho0 > 0.0) || health.particle_count == health.non_finite_particles) return std::nullopt;
  const double deviation =
      std::max(health.max_density / rho0 - 1.0, 1.0 - health.min_density / rho0);
  if (deviation > record_.max_density_deviation) {
    record_.max_density_deviation = deviation;
    record_.max_density_deviation_step = step;
  }
  const bool stops = deviation > limits_.max_density_deviation;
  const bool warns = deviation > limits_.warn_density_deviation && !density_warned_;
  if (!stops && !warns) return std::nullopt;  // the texts below only for a finding
  const std::string what = "max |rho/rho0 - 1| = " +
                           number_beside(deviation, stops ? limits_.max_density_deviation
                                                          : limits_.warn_density_deviation) +
                           " " + at_step(step) + " (rho from " + number(health.min_density) +
                           " to " + number(health.max_density) + " kg/m^3, rho0 = " + number(rho0) +
                           ")";
  // In a weakly compressible fluid the deviation goes as (v/c)^2 + g H / c^2: raising c by
  // sqrt(deviation / 1 %) brings it back to the aim.
  const double factor = std::sqrt(deviation / kDensityAim);
  std::string fix;
  const std::string advice = time_step_advice();
  const double courant = courant_number().value_or(0.0);
  if (beyond_stable(courant)) {
    fix = "the time step is too large for the speed of sound: " + advice;
  } else {
    if (courant > kImpactStableCourant) {
      fix = "dt c / h = " + number(courant) + " is within the " + number(kStableCourant) +
            " measured stable for the static tank under compression but above " +
            number(kImpactStableCourant) +
            ", the largest measured stable through a dam break's impact (docs/validation.md, "
            "\"Stability maps\"): first reduce SolverOptions.Timeint.step_size from " +
            number(scales_.time_step) + " s to at most " +
            number(scales_.time_step * kImpactStableCourant / courant) +
            " s; if the deviation persists, ";
    }
    fix += "the speed of sound is too low for this flow (rho/rho0 - 1 goes as 1/c^2): raise " +
           scales_.speed_of_sound_name;
    if (scales_.speed_of_sound) {
      fix += " from " + number(*scales_.speed_of_sound) + " to at least " +
             number_up(factor * *scales_.speed_of_sound) + " m/s";
    } else {
      fix += " by a factor of " + number(factor);
    }
    fix += step_with_new_speed_of_sound();
    if (!advice.empty()) fix += " (now " + advice + ")";
  }
  fix = settle_first(fix, step);
  if (stops) {
    return HealthFinding{kCheckDensityDeviation,
                         what + " exceeds FluidHealth.max_density_deviation = " +
                             number(limits_.max_density_deviation) +
                             " (weakly compressible SPH aims at " + number(kDensityAim) + ")",
                         fix};
  }
  if (warns) {
    density_warned_ = true;
    warnings.push_back({kCheckDensityDeviation,
                        what + " exceeds FluidHealth.warn_density_deviation = " +
                            number(limits_.warn_density_deviation) +
                            " (warned once; the figures are this first value's, the run's end "
                            "restates them from the largest reached)",
                        fix});
  }
  return std::nullopt;
}

std::optional<HealthFinding> FluidHealthMonitor::mach(std::uint64_t step,
                                                      const protocol::FluidHealth& health,
                                                      std::vector<HealthFinding>& warnings) {
  if (health.max_speed > record_.max_particle_speed) {
    record_.max_particle_speed = health.max_speed;
    record_.max_particle_speed_step = step;
  }
  if (!scales_.speed_of_sound || !(*scales_.speed_of_sound > 0.0)) return std::nullopt;
  const double c = *scales_.speed_of_sound;
  const double mach_number = health.max_speed / c;
  const std::string what = "the fastest particle moves at " + number(health.max_speed) +
                           " m/s = " + number(mach_number) +
                           " c (c = " + scales_.speed_of_sound_name + " = " + number(c) + " m/s) " +
                           at_step(step);
  // c >= 10 v_max keeps the density within 1 % (thesis §6.2).
  std::string fix = "raise " + scales_.speed_of_sound_name + " from " + number(c) +
                    " to at least 10 v_max = " + number(10.0 * health.max_speed) + " m/s" +
                    step_with_new_speed_of_sound();
  const std::string advice = time_step_advice();
  if (!advice.empty()) fix += " (now " + advice + ")";
  fix +=
      "; a speed far above sqrt(2 g H) of the flow means a wall or the time step kicked the "
      "fluid: halve the step first";
  fix = settle_first(fix, step);
  if (mach_number > limits_.max_mach) {
    return HealthFinding{kCheckMach,
                         what + ", above FluidHealth.max_mach = " + number(limits_.max_mach), fix};
  }
  if (mach_number > limits_.warn_mach && !mach_warned_) {
    mach_warned_ = true;
    warnings.push_back(
        {kCheckMach,
         what + ", above FluidHealth.warn_mach = " + number(limits_.warn_mach) + " (warned once)",
         fix});
  }
  return std::nullopt;
}

std::optional<HealthFinding> FluidHealthMonitor::lost(std::uint64_t step, std::uint64_t count,
                                                      std::vector<HealthFinding>& warnings) {
  if (count >= initial_particles_) return std::nullopt;
  const std::uint64_t lost_now = initial_particles_ - count;
  record_.particles_lost = std::max(record_.particles_lost, lost_now);
  const std::string what = std::to_string(lost_now) + " of " + std::to_string(initial_particles_) +
                           " particles have left the LIGGGHTS box " + at_step(step) +
                           "; the scene allows " + std::to_string(allowed_lost_) +
                           " (LIGGGHTS.allowed_lost_particles)";
  std::string fix = "the LIGGGHTS box in script 1 is too small for the flow: enlarge " +
                    scales_.box_description +
                    " beyond every wall and above the highest splash, or declare "
                    "LIGGGHTS.allowed_lost_particles = " +
                    std::to_string(lost_now) + " if losing them is intended";
  if (std::isfinite(closest_over_r0_)) {
    fix += " (if they left through a wall instead: the closest approach so far was " +
           number(closest_over_r0_) + " r0; raise SPH_wall_rep)";
  }
  if (lost_now > allowed_lost_) return HealthFinding{kCheckLostParticles, what, fix};
  if (!lost_warned_) {
    lost_warned_ = true;
    warnings.push_back({kCheckLostParticles, what + " (warned once)", fix});
  }
  return std::nullopt;
}

std::string describe_liggghts_box(const std::string& script_name, const std::string& script_text) {
  std::istringstream lines(script_text);
  std::string line, region_id;
  std::vector<std::pair<int, std::string>> regions;
  int number_of_line = 0;
  while (std::getline(lines, line)) {
    ++number_of_line;
    std::istringstream words(line.substr(0, line.find('#')));
    std::string command, id;
    words >> command >> id;
    if (command == "region") {
      std::string rest;
      std::getline(words, rest);
      regions.emplace_back(number_of_line, id + "|" + rest);
    } else if (command == "create_box") {
      std::string region;
      words >> region;
      region_id = region;
    }
  }
  for (const auto& [at, text] : regions) {
    const std::string id = text.substr(0, text.find('|'));
    if (id != region_id) continue;
    std::string shape = text.substr(text.find('|') + 1);
    shape.erase(0, shape.find_first_not_of(" \t"));
    return "region " + id + " at " + script_name + ":" + std::to_string(at) + " (" + shape + ")";
  }
  return "the region of create_box in " + script_name;
}

FluidScales fluid_scales(const scene::Scene& scene) {
  FluidScales scales;
  scales.rest_density = scene.fluid.density;
  scales.speed_of_sound = scene::speed_of_sound(scene);
  scales.smoothing_length = scene::smoothing_length(scene);
  scales.time_step = scene.solver.step_size;
  scales.wall_repulsion = sph_number(scene, "SPH_wall_rep");
  scales.wall_cutoff = scene::wall_cutoff(scene);
  scales.true_shape_pressure = scene::true_shape_pressure(scene);
  scales.box_description =
      describe_liggghts_box(scene.liggghts.script1_name, scene.liggghts.script1_text);
  if (scene.fluid_parameters) scales.speed_of_sound_name = "Fluid.speed_of_sound";
  scales.step_follows_speed_of_sound = scene.solver.step_size_derived;
  const double gravity = std::hypot(scene.gravity[0], scene.gravity[1], scene.gravity[2]);
  if (scene.fluid.column_height > 0.0 && gravity > 0.0)
    scales.settling_time = 2.0 * std::sqrt(scene.fluid.column_height / gravity);
  return scales;
}

std::vector<std::string> FluidHealthMonitor::near_limits() const {
  constexpr double kNear = 0.8;  // of a stop limit (for the wall distance: 1 / 0.8 of it)
  std::vector<std::string> near;
  if (record_.steps_checked == 0) return near;
  // Past the warning too: the warning's advice came from the first value past its level (a
  // speed of sound barely above the run's), the end restates it from the largest reached.
  if (scales_.rest_density > 0.0 && limits_.max_density_deviation > 0.0 &&
      (record_.max_density_deviation >= kNear * limits_.max_density_deviation || density_warned_)) {
    const bool close_to_stop =
        record_.max_density_deviation >= kNear * limits_.max_density_deviation;
    std::string figure =
        "max |rho/rho0 - 1| = " + number(record_.max_density_deviation) + " at step " +
        std::to_string(record_.max_density_deviation_step) +
        (close_to_stop ? " (within 20 % of the stop: above " + number(limits_.max_density_deviation)
                       : " (past the warning level " + number(limits_.warn_density_deviation) +
                             "; the stop: above " + number(limits_.max_density_deviation)) +
        ")";
    const double deviation = record_.max_density_deviation;
    if (scales_.speed_of_sound && deviation > kDensityAim) {
      figure += ": " + scales_.speed_of_sound_name + " = " +
                number_up(std::sqrt(deviation / kDensityAim) * *scales_.speed_of_sound) +
                " m/s (now " + number(*scales_.speed_of_sound) + ") would keep the largest at " +
                number(kDensityAim);
    }
    near.push_back(figure);
  }
  if (scales_.speed_of_sound && *scales_.speed_of_sound > 0.0 && limits_.max_mach > 0.0) {
    const double mach = record_.max_particle_speed / *scales_.speed_of_sound;
    if (mach >= kNear * limits_.max_mach) {
      near.push_back("max |v| / c = " + number(mach) + " at step " +
                     std::to_string(record_.max_particle_speed_step) + " (the stop: above " +
                     number(limits_.max_mach) + ")");
    }
  }
  if (std::isfinite(closest_over_r0_) && limits_.min_wall_distance > 0.0 &&
      closest_over_r0_ * kNear <= limits_.min_wall_distance) {
    near.push_back("closest particle-wall distance " + number(closest_over_r0_) +
                   " r0 (the stop: below " + number(limits_.min_wall_distance) + " r0)");
  }
  return near;
}

void FluidHealthMonitor::save_state(output::StateWriter& out) const {
  out.section("fluid health");
  out.put(initial_particles_);
  out.put(closest_over_r0_);
  out.put(density_warned_);
  out.put(mach_warned_);
  out.put(lost_warned_);
  out.put(record_.steps_checked);
  out.put(record_.max_density_deviation);
  out.put(record_.max_density_deviation_step);
  out.put(record_.max_particle_speed);
  out.put(record_.max_particle_speed_step);
  out.put(record_.particles_lost);
  out.put(record_.failed_check.has_value());
  out.put(record_.failed_check.value_or(""));
  out.put(static_cast<std::uint64_t>(record_.warnings.size()));
  for (const std::string& warning : record_.warnings)
    out.put(warning);
  out.put(unsettled_release_);
}

void FluidHealthMonitor::restore_state(output::StateReader& in) {
  in.section("fluid health");
  initial_particles_ = in.u64("initial particles");
  closest_over_r0_ = in.f64("closest approach");
  density_warned_ = in.boolean("density warned");
  mach_warned_ = in.boolean("Mach warned");
  lost_warned_ = in.boolean("loss warned");
  record_.steps_checked = in.u64("steps checked");
  record_.max_density_deviation = in.f64("largest density deviation");
  record_.max_density_deviation_step = in.u64("its step");
  record_.max_particle_speed = in.f64("largest speed");
  record_.max_particle_speed_step = in.u64("its step");
  record_.particles_lost = in.u64("particles lost");
  const bool failed = in.boolean("failed check");
  std::string check = in.text("failed check");
  record_.failed_check = failed ? std::optional<std::string>(std::move(check)) : std::nullopt;
  record_.warnings.resize(in.count("warnings"));
  for (std::string& warning : record_.warnings)
    warning = in.text("warning");
  unsettled_release_ = in.text("unsettled release");
}

}  // namespace fsi::coupling
