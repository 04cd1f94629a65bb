#pragma once
// The energy audit of the coupling (issue 15; docs/theory.md, "The energy audit"): at every
// exchange, the work the fluid did on the structure and the work the structure did on the fluid
// over the interval, from the vertex forces and the boundary motion both sides used. In the
// staggered scheme (thesis Fig. 4.10) the structure moves from t(n-1) to t(n) under the forces
// f(n-1), held as point loads, so the fluid's work on it is exactly
//   W_fs(n) = sum_i f_i(n-1) . (x_i(n) - x_i(n-1));
// the fluid takes its step with the wall at x(n) moving at v(n) and answers with f(n): the
// structure's work on the fluid, as the fluid saw it, is
//   W_sf(n) = -sum_i f_i(n) . v_i(n) dt.
// The books pair the two works of the same force f(n): what the fluid got for it over its step n
// and what the structure got for it over the next step, W_fs(n+1) + W_sf(n) = f(n) . (x(n+1) -
// x(n) - v(n) dt): zero for a wall that moves as the fluid assumed, otherwise the energy the
// coupling itself created (> 0) or destroyed (< 0). The signature of the added-mass instability
// of explicit partitioned coupling is a coupling energy that grows positive. The latest force's
// W_sf waits for the structure's answer (the totals hold the paired works only).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fsi/output/state_archive.hpp"

namespace fsi::coupling {

// The coupling injects energy when the accumulated coupling energy exceeds this fraction of the
// energy the fluid moved into or out of the structure so far, sum |W_fs(n)| (and round-off,
// kAuditRoundOff).
inline constexpr double kInjectionWarningFraction = 0.1;
// The audit judges from this exchange on: a wall driven from rest at a constant acceleration
// (a PrescribedMotion) makes a coupling energy of 1/n of the traffic after n exchanges, the
// staggered scheme's lag of one step rather than an instability (5 % at exchange 20).
inline constexpr std::uint64_t kAuditFirstJudgedExchange = 20;
// Below this [J; 2D J/m] a coupling energy is round-off.
inline constexpr double kAuditRoundOff = 1e-12;
// A coupling energy below this fraction of the fluid's energy scale (audit_noise_floor) is not
// judged: when a water front first touches a structure at rest (a dam break reaching an obstacle)
// the forces rise from nothing while the traffic is still ~1e-9 J, and the lag of one step made a
// few 1e-10 J that read as 10-40 % of the traffic (a healthy run stopped at its first contact).
// An instability that ends a run makes far more: a single particle thrown at half the speed of
// sound carries 25 / N of the scale (N particles).
inline constexpr double kAuditNoiseFraction = 1e-6;

// The fluid's energy scale of the audit: the kinetic energy of the whole fluid (total mass
// `fluid_mass`, kg; 2D kg/m) at the flow speed its speed of sound was chosen for, c / 10 (thesis
// §6.2, Mach 0.1): 1/2 M (c / 10)^2 [J; 2D J/m]. 0 when c is not known.
double audit_energy_scale(double fluid_mass, double speed_of_sound);
// The coupling energy the audit judges above: kAuditNoiseFraction of the energy scale, at least
// kAuditRoundOff.
double audit_noise_floor(double energy_scale);

struct EnergyTotals {
  double work_fluid_on_structure = 0.0;  // sum of W_fs [J; 2D J/m]
  double work_structure_on_fluid = 0.0;  // sum of W_sf
  double coupling_energy = 0.0;          // their sum: created by the coupling
  double max_coupling_energy = 0.0;      // the largest accumulated value (0 or more)
  double traffic = 0.0;                  // sum |W_fs(n)|: the energy moved through the interface
  std::uint64_t exchanges = 0;
  // The largest coupling_energy / traffic of the judged exchanges (from
  // kAuditFirstJudgedExchange on, where the coupling energy exceeds round-off); 0 before.
  double max_coupling_fraction = 0.0;
};

class EnergyAudit {
 public:
  static constexpr const char* kGeneralRemedy =
      "halve SolverOptions.Timeint.step_size (with substeps > 1: lower the substeps first), or "
      "make the structure heavier or stiffer, or damp a flexible body's own modes (docs/theory.md, "
      "\"The energy audit\")";
  EnergyAudit() = default;
  // stop_growth > 0: the audit stops the run (stop() returns its diagnosis) when, after its
  // warning, the coupling energy has grown to more than stop_growth times its value at the
  // warning: the instability feeds itself, where a one-off injection (a release, an impact)
  // stays put; 0: it never stops.
  // remedy: what to change, ending the warning's text and given with the stop (the session's
  // names the scene's own step and substeps); empty: kGeneralRemedy.
  // noise_floor [J; 2D J/m]: a coupling energy at or below it is not judged (audit_noise_floor);
  // never below kAuditRoundOff.
  explicit EnergyAudit(double stop_growth, std::string remedy = {},
                       double noise_floor = kAuditRoundOff);

  // The dynamic vertices at t = 0 and the fluid's forces on them (dimension values each).
  void start(std::span<const double> positions, std::span<const double> velocities,
             std::span<const double> forces);
  // The bodies the vertices belong to, audited each on its own books as well as together:
  // `part_of_value[k]` names the body (an index into `names`) of value k of the spans start()
  // and exchange() take. With one body (or none given) the whole is the only book. A drive that
  // pushes much water through its walls makes most of the traffic; the instability of a light
  // body in that water then stayed at 1-7 % of the whole's traffic while it grew 6-8 times
  // every 0.5 s (a user's elastic baffle in a rolling tank): judged on its own books, its share
  // is its own.
  void set_parts(std::vector<std::uint32_t> part_of_value, std::vector<std::string> names);
  // The books of each body (set_parts), in the order of `names`.
  struct Part {
    std::string name;
    EnergyTotals totals;
    std::optional<std::uint64_t> warned_at;
    double energy_at_warning = 0.0;
  };
  const std::vector<Part>& parts() const { return parts_; }
  // One exchange: the dynamic vertices at t(n) (positions, velocities), the step dt and the
  // fluid's answer f(n). `applied`, if not empty, is the force the structure will move under
  // instead of f(n) (a force predictor): the fluid's work on the structure W_fs(n+1) is then
  // that force's, the structure's on the fluid W_sf(n) stays f(n)'s. Throws fsi::Error when the
  // sizes differ from start()'s.
  void exchange(std::span<const double> positions, std::span<const double> velocities, double dt,
                std::span<const double> forces, std::uint64_t step,
                std::span<const double> applied = {});

  const EnergyTotals& totals() const { return totals_; }
  // The last exchange's W_fs(n) and W_sf(n-1) (the works of the force f(n-1)).
  double last_work_fluid_on_structure() const { return last_fs_; }
  double last_work_structure_on_fluid() const { return last_sf_; }
  // A warning, the first time the coupling has injected more than kInjectionWarningFraction of
  // the largest exchanged work (and more than round-off): what it means and what to change.
  // Empty otherwise, and after it was returned once.
  std::string take_warning();
  // The step at which the first warning fired (the whole's or a body's), if one did.
  std::optional<std::uint64_t> warned_at() const {
    std::optional<std::uint64_t> first = warned_at_;
    for (const Part& part : parts_) {
      if (part.warned_at && (!first || *part.warned_at < *first)) first = part.warned_at;
    }
    return first;
  }
  // The diagnosis that ends the run, once the coupling energy has outgrown the stop growth
  // (what happened and what it means; remedy() says what to change); empty while it has not.
  const std::string& stop() const { return stop_; }
  // What to change: the constructor's remedy, or kGeneralRemedy.
  const std::string& remedy() const { return remedy_; }
  // The step at which the stop growth was exceeded, if it was.
  std::optional<std::uint64_t> stopped_at() const { return stopped_at_; }
  // The coupling energy the audit judges above [J; 2D J/m].
  double noise_floor() const { return noise_floor_; }

  // Checkpoints: everything the audit carries from exchange to exchange, bit for bit.
  void save_state(output::StateWriter& out) const;
  void restore_state(output::StateReader& in);

 private:
  std::vector<double> positions_;
  std::vector<double> velocities_;
  std::vector<double> forces_;
  std::vector<double> applied_;  // the predicted force the structure moves under; empty: forces_
  EnergyTotals totals_;
  double last_fs_ = 0.0;
  double last_sf_ = 0.0;
  bool started_ = false;
  std::optional<std::uint64_t> warned_at_;
  std::string pending_;
  double stop_growth_ = 0.0;
  std::string remedy_ = kGeneralRemedy;
  double noise_floor_ = kAuditRoundOff;
  double energy_at_warning_ = 0.0;
  std::optional<std::uint64_t> stopped_at_;
  std::string stop_;
  std::vector<std::uint32_t> part_of_value_;
  std::vector<Part> parts_;
  std::vector<double> part_fs_, part_sf_;  // one exchange's works per part

  // Judges one set of books (the whole, or one body's: `where` names it, empty for the whole).
  void judge(EnergyTotals& books, std::optional<std::uint64_t>& warned_at,
             double& energy_at_warning, const std::string& where, std::uint64_t step);
};

}  // namespace fsi::coupling
