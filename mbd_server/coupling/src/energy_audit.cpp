#include "fsi/coupling/energy_audit.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"

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
  return significant(value, 3);
}

}  // namespace

double audit_energy_scale(double fluid_mass, double speed_of_sound) {
  if (!(fluid_mass > 0.0) || !(speed_of_sound > 0.0)) return 0.0;
  const double design_speed = 0.1 * speed_of_sound;
  return 0.5 * fluid_mass * design_speed * design_speed;
}

double audit_noise_floor(double energy_scale) {
  return std::max(kAuditRoundOff, kAuditNoiseFraction * energy_scale);
}

EnergyAudit::EnergyAudit(double stop_growth, std::string remedy, double noise_floor)
    : stop_growth_(stop_growth),
      remedy_(remedy.empty() ? std::string(kGeneralRemedy) : std::move(remedy)),
      noise_floor_(std::max(kAuditRoundOff, noise_floor)) {}

void EnergyAudit::start(std::span<const double> positions, std::span<const double> velocities,
                        std::span<const double> forces) {
  require_size(velocities, positions.size(), "velocities", 0);
  require_size(forces, positions.size(), "forces", 0);
  positions_.assign(positions.begin(), positions.end());
  velocities_.assign(velocities.begin(), velocities.end());
  forces_.assign(forces.begin(), forces.end());
  applied_.clear();
  totals_ = {};
  for (Part& part : parts_) {
    part.totals = {};
    part.warned_at.reset();
    part.energy_at_warning = 0.0;
  }
  started_ = true;
}

void EnergyAudit::exchange(std::span<const double> positions, std::span<const double> velocities,
                           double dt, std::span<const double> forces, std::uint64_t step,
                           std::span<const double> applied) {
  if (!started_) {
    const std::vector<double> zero(positions.size(), 0.0);
    start(positions, velocities, zero);
  }
  require_size(positions, positions_.size(), "positions", step);
  require_size(velocities, positions_.size(), "velocities", step);
  require_size(forces, positions_.size(), "forces", step);
  if (!applied.empty()) require_size(applied, positions_.size(), "applied forces", step);
  if (!parts_.empty() && part_of_value_.size() != positions.size()) {
    throw Error("the energy audit knows the body of " + std::to_string(part_of_value_.size()) +
                    " values and got " + std::to_string(positions.size()) + " at step " +
                    std::to_string(step),
                "energy audit of the coupling", "this is a bug of fsi-server: please report it");
  }
  double fs = 0.0;
  double sf = 0.0;
  // The force the structure moved under: the predicted one if there was one, else f(n-1).
  const std::vector<double>& moved_under = applied_.empty() ? forces_ : applied_;
  for (std::size_t k = 0; k < positions.size(); ++k) {  // the works of f(n-1)
    fs += moved_under[k] * (positions[k] - positions_[k]);
    sf -= forces_[k] * velocities_[k] * dt;
  }
  last_fs_ = fs;
  last_sf_ = sf;
  const auto book = [](EnergyTotals& books, double work_fs, double work_sf) {
    books.work_fluid_on_structure += work_fs;
    books.work_structure_on_fluid += work_sf;
    books.coupling_energy = books.work_fluid_on_structure + books.work_structure_on_fluid;
    books.max_coupling_energy = std::max(books.max_coupling_energy, books.coupling_energy);
    books.traffic += std::abs(work_fs);
    ++books.exchanges;
  };
  book(totals_, fs, sf);
  if (parts_.size() > 1) {
    std::fill(part_fs_.begin(), part_fs_.end(), 0.0);
    std::fill(part_sf_.begin(), part_sf_.end(), 0.0);
    for (std::size_t k = 0; k < positions.size(); ++k) {
      const std::uint32_t part = part_of_value_[k];
      part_fs_[part] += moved_under[k] * (positions[k] - positions_[k]);
      part_sf_[part] -= forces_[k] * velocities_[k] * dt;
    }
    for (std::size_t p = 0; p < parts_.size(); ++p)
      book(parts_[p].totals, part_fs_[p], part_sf_[p]);
  }
  positions_.assign(positions.begin(), positions.end());
  velocities_.assign(velocities.begin(), velocities.end());
  forces_.assign(forces.begin(), forces.end());
  applied_.assign(applied.begin(), applied.end());  // empty: the structure moves under f(n)

  judge(totals_, warned_at_, energy_at_warning_, "", step);
  for (Part& part : parts_)
    judge(part.totals, part.warned_at, part.energy_at_warning, part.name, step);
}

void EnergyAudit::judge(EnergyTotals& books, std::optional<std::uint64_t>& warned_at,
                        double& energy_at_warning, const std::string& where, std::uint64_t step) {
  const bool judged =
      books.exchanges >= kAuditFirstJudgedExchange && books.coupling_energy > noise_floor_;
  if (!judged) return;
  const double fraction = books.coupling_energy / std::max(books.traffic, kAuditRoundOff);
  books.max_coupling_fraction = std::max(books.max_coupling_fraction, fraction);
  const std::string at = where.empty() ? std::string() : " at " + where;
  const std::string interface =
      where.empty() ? std::string("the interface") : "the interface of " + where;
  // The texts are made only when the warning or the stop needs them.
  const auto text = [&] {
    return "by step " + std::to_string(step) + " the fluid did " +
           number(books.work_fluid_on_structure) + " J on " +
           (where.empty() ? std::string("the structure") : where) + " (2D: J/m) and " +
           (where.empty() ? std::string("the structure") : std::string("it")) + " " +
           number(books.work_structure_on_fluid) + " J on the fluid, so the exchange made " +
           number(books.coupling_energy) + " J, " + number(100.0 * fraction) +
           " % of the energy moved through " + interface;
  };
  if (!warned_at && fraction > kInjectionWarningFraction) {
    warned_at = step;
    energy_at_warning = books.coupling_energy;
    if (pending_.empty()) {
      pending_ = "the coupling has created energy" + at + ": " + text() + " (more than " +
                 number(100.0 * kInjectionWarningFraction) +
                 " %), the signature of the added-mass instability of explicit partitioned "
                 "coupling (a structure light against the fluid it moves); " +
                 remedy_;
    }
  }
  if (stop_growth_ > 0.0 && warned_at && !stopped_at_ &&
      books.coupling_energy > stop_growth_ * energy_at_warning) {
    stopped_at_ = step;
    stop_ = "the coupling keeps creating energy" + at + ": " + text() + "; it has grown " +
            number(books.coupling_energy / energy_at_warning) +
            " times since the warning at step " + std::to_string(*warned_at) + " (" +
            number(energy_at_warning) +
            " J), more than FluidHealth.max_coupling_energy_growth = " + number(stop_growth_) +
            ": the added-mass instability of explicit partitioned coupling (a structure light "
            "against the fluid it moves), which grows until the fluid breaks through a wall or "
            "blows up";
  }
}

void EnergyAudit::set_parts(std::vector<std::uint32_t> part_of_value,
                            std::vector<std::string> names) {
  for (std::uint32_t part : part_of_value)
    FSI_ASSERT(part < names.size(), "an energy audit part index beyond its names");
  part_of_value_ = std::move(part_of_value);
  parts_.clear();
  for (std::string& name : names)
    parts_.push_back(Part{std::move(name), {}, std::nullopt, 0.0});
  if (parts_.size() < 2) parts_.clear();  // the whole is the only book
  part_fs_.assign(parts_.size(), 0.0);
  part_sf_.assign(parts_.size(), 0.0);
}

std::string EnergyAudit::take_warning() {
  return std::exchange(pending_, std::string());
}

namespace {
void put_optional(output::StateWriter& out, const std::optional<std::uint64_t>& value) {
  out.put(value.has_value());
  out.put(value.value_or(0));
}
std::optional<std::uint64_t> optional_u64(output::StateReader& in, std::string_view what) {
  const bool present = in.boolean(what);
  const std::uint64_t value = in.u64(what);
  return present ? std::optional<std::uint64_t>(value) : std::nullopt;
}
}  // namespace

void EnergyAudit::save_state(output::StateWriter& out) const {
  out.section("energy audit");
  out.put(positions_);
  out.put(velocities_);
  out.put(forces_);
  out.put(applied_);
  for (double value : {totals_.work_fluid_on_structure, totals_.work_structure_on_fluid,
                       totals_.coupling_energy, totals_.max_coupling_energy, totals_.traffic,
                       totals_.max_coupling_fraction, last_fs_, last_sf_, energy_at_warning_})
    out.put(value);
  out.put(totals_.exchanges);
  out.put(started_);
  put_optional(out, warned_at_);
  out.put(pending_);
  put_optional(out, stopped_at_);
  out.put(stop_);
  out.put(static_cast<std::uint64_t>(parts_.size()));
  for (const Part& part : parts_) {
    const EnergyTotals& t = part.totals;
    for (double value :
         {t.work_fluid_on_structure, t.work_structure_on_fluid, t.coupling_energy,
          t.max_coupling_energy, t.traffic, t.max_coupling_fraction, part.energy_at_warning})
      out.put(value);
    out.put(t.exchanges);
    put_optional(out, part.warned_at);
  }
}

void EnergyAudit::restore_state(output::StateReader& in) {
  in.section("energy audit");
  positions_ = in.doubles("positions");
  velocities_ = in.doubles("velocities");
  forces_ = in.doubles("forces");
  applied_ = in.doubles("applied forces");
  totals_.work_fluid_on_structure = in.f64("work of the fluid");
  totals_.work_structure_on_fluid = in.f64("work of the structure");
  totals_.coupling_energy = in.f64("coupling energy");
  totals_.max_coupling_energy = in.f64("largest coupling energy");
  totals_.traffic = in.f64("traffic");
  totals_.max_coupling_fraction = in.f64("largest coupling fraction");
  last_fs_ = in.f64("last work of the fluid");
  last_sf_ = in.f64("last work of the structure");
  energy_at_warning_ = in.f64("energy at the warning");
  totals_.exchanges = in.u64("exchanges");
  started_ = in.boolean("started");
  warned_at_ = optional_u64(in, "warning step");
  pending_ = in.text("pending warning");
  stopped_at_ = optional_u64(in, "stop step");
  stop_ = in.text("stop");
  const std::uint64_t parts = in.u64("bodies audited");
  if (parts != parts_.size()) {
    throw Error("the checkpoint's energy audit has " + std::to_string(parts) +
                    " bodies, the scene's " + std::to_string(parts_.size()),
                "energy audit", "resume with the scene that wrote the checkpoint");
  }
  for (Part& part : parts_) {
    EnergyTotals& t = part.totals;
    t.work_fluid_on_structure = in.f64("body's work of the fluid");
    t.work_structure_on_fluid = in.f64("body's work on the fluid");
    t.coupling_energy = in.f64("body's coupling energy");
    t.max_coupling_energy = in.f64("body's largest coupling energy");
    t.traffic = in.f64("body's traffic");
    t.max_coupling_fraction = in.f64("body's largest coupling fraction");
    part.energy_at_warning = in.f64("body's energy at its warning");
    t.exchanges = in.u64("body's exchanges");
    part.warned_at = optional_u64(in, "body's warning step");
  }
}

}  // namespace fsi::coupling
