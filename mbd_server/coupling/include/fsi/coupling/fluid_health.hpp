#pragma once
// The run judges its fluid at every exchange (ARCHITECTURE.md §13, "A run judges itself";
// docs/user-guide.md, "When a run stops: the health checks"): from the Forces and FluidHealth of
// each step, a failing fluid stops the run before it writes NaN, with a diagnosis naming the
// parameter to change and by how much. Pure: the session feeds it what the client reported.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fsi/coupling/fluid_side.hpp"
#include "fsi/output/state_archive.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::coupling {

// The names of the checks, as the log, the error and run.json ("health.failed_check") give them.
inline constexpr const char* kCheckNonFinite = "non_finite";
inline constexpr const char* kCheckWallDistance = "wall_distance";
inline constexpr const char* kCheckDensityDeviation = "density_deviation";
inline constexpr const char* kCheckMach = "mach";
inline constexpr const char* kCheckLostParticles = "lost_particles";
// Judged by the energy audit (energy_audit.hpp), recorded here with the others.
inline constexpr const char* kCheckCouplingEnergy = "coupling_energy";

// What the checks compare the fluid against, and the names in the fix texts.
struct FluidScales {
  double rest_density = 0.0;             // rho0 [kg/m^3]; 0: unknown (the density check is skipped)
  std::optional<double> speed_of_sound;  // c [m/s] (cAB); absent: the Mach check is skipped
  std::optional<double> smoothing_length;     // h [m]; absent: no dt c / h in the advice
  double time_step = 0.0;                     // the coupled step [s]
  std::optional<double> wall_repulsion;       // k (SPH_wall_rep) for the advice, if known
  std::optional<double> wall_cutoff;          // r_c of the thesis' wall law, if known
  std::optional<double> true_shape_pressure;  // the true-shape wall's reference pressure, if used
  std::string box_description;                // where script 1 makes the LIGGGHTS box
  // The speed of sound's name in the fix texts: the LIGGGHTS variable cAB, or the Fluid block's
  // key when the block derives it.
  std::string speed_of_sound_name = "cAB";
  // The coupled step is the Fluid block's time-step rule's (Timeint.step_size not given): it
  // follows a new speed of sound by itself.
  bool step_follows_speed_of_sound = false;
  // 2 sqrt(H / |g|) [s] of the water column H: an unsettled release explains a density or Mach
  // finding within this time after it, not a later one (a dam break's impact); 0: at any time.
  double settling_time = 0.0;
};

// One finding: `check` is one of the names above; message says what and by how much, fix what to
// change.
struct HealthFinding {
  std::string check;
  std::string message;
  std::string fix;
};

struct HealthVerdict {
  std::optional<HealthFinding> stop;    // the run must end
  std::vector<HealthFinding> warnings;  // each kind of warning once per run
};

// The worst the fluid did, for run.json's "health".
struct HealthRecord {
  std::uint64_t steps_checked = 0;  // exchanges with a FluidHealth report
  double max_density_deviation = 0.0;
  std::uint64_t max_density_deviation_step = 0;
  double max_particle_speed = 0.0;
  std::uint64_t max_particle_speed_step = 0;
  std::uint64_t particles_lost = 0;  // the most seen at once, against the count at Ready
  std::optional<std::string> failed_check;
  std::vector<std::string> warnings;
};

class FluidHealthMonitor {
 public:
  FluidHealthMonitor(const scene::FluidHealthLimits& limits, std::uint64_t allowed_lost_particles,
                     FluidScales scales);

  // The particle count the losses are counted from (the client's Ready).
  void set_initial_particles(std::uint64_t count) { initial_particles_ = count; }
  // The release check found the water not at rest (`why`: "the structure carried 405.8 % of
  // the fluid's weight"): a density or Mach finding then says to let it settle first, before
  // raising c (a column released from its lattice compresses and splashes whatever c is).
  void set_unsettled_release(std::string why) { unsettled_release_ = std::move(why); }

  // Judges the exchange of `step`: checks in the order non-finite values, wall distance, density
  // deviation, Mach number, lost particles; the first that fails is the verdict's stop.
  HealthVerdict judge(std::uint64_t step, const FluidForces& forces);

  const HealthRecord& record() const { return record_; }
  // At the end of a run that passed: each judged figure that came within 20 % of its stop limit
  // (the worst density deviation, particle speed over c, closest wall approach), e.g. "max
  // |rho/rho0 - 1| = 0.0498 at step 41526 (the stop: above 0.05)"; empty when none did. A run
  // this close to a stop completed, but its result is at the edge of what its resolution and c
  // hold.
  std::vector<std::string> near_limits() const;
  // A check judged elsewhere (kCheckCouplingEnergy) that ends the run.
  void record_failed_check(std::string check) { record_.failed_check = std::move(check); }
  const scene::FluidHealthLimits& limits() const { return limits_; }
  std::uint64_t allowed_lost_particles() const { return allowed_lost_; }

  // Checkpoints: the record, the warnings given and the particle count losses are counted from.
  void save_state(output::StateWriter& out) const;
  void restore_state(output::StateReader& in);

 private:
  std::optional<HealthFinding> non_finite(std::uint64_t step, const FluidForces& forces) const;
  std::optional<HealthFinding> wall_distance(std::uint64_t step, double closest_over_r0) const;
  std::optional<HealthFinding> density(std::uint64_t step, const protocol::FluidHealth& health,
                                       std::vector<HealthFinding>& warnings);
  std::optional<HealthFinding> mach(std::uint64_t step, const protocol::FluidHealth& health,
                                    std::vector<HealthFinding>& warnings);
  std::optional<HealthFinding> lost(std::uint64_t step, std::uint64_t count,
                                    std::vector<HealthFinding>& warnings);
  // "dt c / h = 0.19" and the step that brings it to the measured stable 0.125, if h and c are
  // known; empty otherwise.
  std::string time_step_advice() const;
  // dt c / h, if c and h are known.
  std::optional<double> courant_number() const;
  // What happens to the step when c is raised: " and reduce SolverOptions.Timeint.step_size by
  // the same factor to keep dt c / h", or that the Fluid block's rule follows.
  std::string step_with_new_speed_of_sound() const;
  // `fix`, after the advice to settle the water first when the release found it moving and the
  // finding of `step` came within the settling time after it.
  std::string settle_first(const std::string& fix, std::uint64_t step) const;

  scene::FluidHealthLimits limits_;
  std::uint64_t allowed_lost_;
  FluidScales scales_;
  std::uint64_t initial_particles_ = 0;
  double closest_over_r0_ = 0.0;  // smallest so far, for the lost-particle diagnosis
  bool density_warned_ = false, mach_warned_ = false, lost_warned_ = false;
  std::string unsettled_release_;  // kept in checkpoints: a resumed run advises as the first
  HealthRecord record_;
};

// Where script 1 makes the LIGGGHTS box: "region domain at static_tank.in1:22 (block ${xmin}
// ${xmax} ...)", from its create_box command; a plain hint when the script has none.
std::string describe_liggghts_box(const std::string& script_name, const std::string& script_text);

// The scales of `scene` (rho0, c, h, dt, k, the box of script 1).
FluidScales fluid_scales(const scene::Scene& scene);

}  // namespace fsi::coupling
