#include "fsi/coupling/energy_audit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "fsi/common/error.hpp"

namespace fsi::coupling {

namespace {

void require_size(std::span<const double> values, std::size_t expected, const char* what,
                  std::uint64_t step) {
  if (values.size() == expected) return;
  throw Error(std::string("the energy audit got ") + std::to_string(values.size()) + " " + what +
                  " at step " + std::to_string(step) + ", expected " + std::to_string(expected),
              "energy audit of the coupling", "this is a bug of fsi-server: please report it");
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

}  // namespace

void EnergyAudit::start(std::span<const double> positions, std::span<const double> velocities,
                        std::span<const double> forces) {
  require_size(velocities, positions.size(), "velocities", 0);
  require_size(forces, positions.size(), "forces", 0);
  positions_.assign(positions.begin(), positions.end());
  velocities_.assign(velocities.begin(), velocities.end());
  forces_.assign(forces.begin(), forces.end());
  totals_ = {};
  started_ = true;
}

void EnergyAudit::exchange(std::span<const double> positions, std::span<const double> velocities,
                           double dt, std::span<const double> forces, std::uint64_t step) {
  if (!started_) {
    const std::vector<double> zero(positions.size(), 0.0);
    start(positions, velocities, zero);
  }
  require_size(positions, positions_.size(), "positions", step);
  require_size(velocities, positions_.size(), "velocities", step);
  require_size(forces, positions_.size(), "forces", step);
  double fs = 0.0;
  double sf = 0.0;
  for (std::size_t k = 0; k < positions.size(); ++k) {  // the works of f(n-1)
    fs += forces_[k] * (positions[k] - positions_[k]);
    sf -= forces_[k] * velocities_[k] * dt;
  }
  last_fs_ = fs;
  last_sf_ = sf;
  totals_.work_fluid_on_structure += fs;
  totals_.work_structure_on_fluid += sf;
  totals_.coupling_energy = totals_.work_fluid_on_structure + totals_.work_structure_on_fluid;
  totals_.max_coupling_energy = std::max(totals_.max_coupling_energy, totals_.coupling_energy);
  totals_.traffic += std::abs(fs);
  ++totals_.exchanges;
  positions_.assign(positions.begin(), positions.end());
  velocities_.assign(velocities.begin(), velocities.end());
  forces_.assign(forces.begin(), forces.end());

  const double limit = std::max(kInjectionWarningFraction * totals_.traffic, kAuditRoundOff);
  if (!warned_at_ && totals_.exchanges >= kAuditFirstJudgedExchange &&
      totals_.coupling_energy > limit) {
    warned_at_ = step;
    pending_ = "the coupling has created energy: by step " + std::to_string(step) +
               " the fluid did " + number(totals_.work_fluid_on_structure) +
               " J on the structure (2D: J/m) and the structure " +
               number(totals_.work_structure_on_fluid) + " J on the fluid, so the exchange made " +
               number(totals_.coupling_energy) + " J (more than " +
               number(100.0 * kInjectionWarningFraction) +
               " % of the energy moved through the interface), the signature of the added-mass "
               "instability of "
               "explicit partitioned coupling (a structure light against the fluid it moves); "
               "halve SolverOptions.Timeint.step_size (with substeps > 1: lower the substeps "
               "first), or make the structure heavier or stiffer "
               "(docs/theory.md, \"The energy audit\")";
  }
}

std::string EnergyAudit::take_warning() {
  return std::exchange(pending_, std::string());
}

}  // namespace fsi::coupling
