#pragma once
// run.json, the manifest of one run (docs/user-guide.md, "run.json"): one builder and one shape
// for coupled and --mbd-only runs. Entries a mode does not have (the fluid, the client, the
// protocol in an --mbd-only run; the fluid's timings and checks) are null, never missing.

#include <array>
#include <cstdint>
#include <filesystem>

#include <optional>
#include <string>
#include <vector>
#include "fsi/common/utc_time.hpp"

#include "fsi/common/utc_time.hpp"
#include "fsi/coupling/energy_audit.hpp"
#include "fsi/coupling/fluid_health.hpp"
#include "fsi/coupling/fluid_side.hpp"
#include "fsi/coupling/release_check.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::coupling {

// Version 2: one shape for every mode ("mode", gravity with `dimension` components, bodies as a
// list, null for what a mode does not have). Version 3: "release", the fluid at release.
// Version 4: "health", the fluid health checks (limits, the worst values, the failed check).
// Version 5: "energy_audit", the works exchanged by the coupling (energy_audit.hpp).
// Version 6: "started_utc"; run.json is written when the run starts too ("status": "started"
// until the end is recorded), always whole (a temporary name and a rename).
// Version 7: "checkpoints" (interval, how many written, the last step) and "resumes" (each resume
// of the run: when, from which checkpoint); "scene" names the run's --set overrides.
// Version 8: particle pairs in "checks". Version 9: "wavemakers", each wavemaker's waves with
// the components of its paddle's motion.
inline constexpr int kRunManifestFormatVersion = 9;

// run.json's times ("started_utc", resumes) come from fsi::utc_now (fsi/common/utc_time.hpp).

enum class RunMode { Coupled, MbdOnly };

// What the fluid side reported and what the server checked of it.
struct FluidRecord {
  std::optional<FluidPeer> peer;  // none: not connected, or an in-process fluid side
  std::uint64_t particle_count = 0;
  std::string liggghts_version;
  double seconds_client_setup = 0.0;
  double seconds_client_equilibration = 0.0;
  double seconds_liggghts = 0.0;
  double seconds_contact = 0.0;
  double seconds_client_communication = 0.0;
  double seconds_round_trip = 0.0;   // of the exchanges, as the server waited for them
  double max_action_reaction = 0.0;  // |F_fluid + F_structure| / sum |pair forces|
  std::optional<double> closest_approach_over_r0;
  std::uint64_t particles_initial = 0;
  std::uint64_t particles_final = 0;
  std::uint64_t snapshots_checked = 0;  // snapshots whose fluid health was measured
  double max_density_deviation = 0.0;   // max |rho/rho0 - 1| over those snapshots
  double max_particle_speed = 0.0;
  std::optional<double> speed_of_sound;
  // Particle pairs closer than d/2 over those snapshots (particle_pairs.hpp): the most at once,
  // and the closest pair (its distance over d) with its midpoint and time.
  std::uint64_t max_close_pairs = 0;
  std::optional<double> closest_pair_over_spacing;
  std::vector<double> closest_pair_where;
  double closest_pair_time = 0.0;
};

// The fluid health checks of a coupled run (fluid_health.hpp).
struct HealthSummary {
  HealthRecord record;
  scene::FluidHealthLimits limits;
  std::uint64_t allowed_lost_particles = 0;
};

// The energy audit of a coupled run's exchanges.
struct EnergyAuditSummary {
  EnergyTotals totals;
  std::optional<std::uint64_t> warned_at;   // the step of the injection warning, if any
  std::optional<std::uint64_t> stopped_at;  // the step whose coupling energy stopped the run
  std::vector<EnergyAudit::Part> bodies;    // each body's books (two bodies or more)
};

// A resume of the run (fsi-server --resume): when, and from which checkpoint.
struct ResumeRecord {
  std::string utc;
  std::uint64_t step = 0;          // the checkpoint's
  std::string checkpoint;          // its folder name
  std::uint32_t client_ranks = 0;  // the fluid side's ranks after the resume (0: unknown)
};

// The run's checkpoints (OUTPUT/checkpoints).
struct CheckpointRecord {
  long every_steps = 0;
  double every_seconds = 0.0;
  std::uint64_t written = 0;  // by this run, resumed processes included
  std::optional<std::uint64_t> last_step;
  double seconds_writing = 0.0;  // both sides' time for them
};

struct RunRecord {
  RunMode mode = RunMode::Coupled;
  std::string command_line;
  // The --set KEY=EXPR of the run, as given (scene.overrides; a resume without a scene reads
  // the scene's file and these back).
  std::vector<std::string> overrides;
  std::vector<std::string> warnings;
  std::string started_utc;         // utc_now() when the run began
  std::string status = "started";  // "completed" or "failed" at the end
  std::string reason;              // why it failed; empty otherwise
  std::uint64_t steps = 0;         // done
  std::uint64_t snapshots = 0;
  double seconds_total = 0.0;
  double seconds_setup_and_equilibration = 0.0;
  double seconds_stepping = 0.0;  // the coupled phase, or the --mbd-only steps
  double seconds_mbd = 0.0;
  double seconds_output = 0.0;
  mbd::IntegratorStatistics newton;
  std::optional<double> position_constraint_drift;
  std::optional<double> velocity_constraint_drift;
  std::optional<FluidRecord> fluid;  // coupled runs only
  // Coupled runs whose client reported the fluid at release (protocol 1.2).
  std::optional<ReleaseCheck> release;
  std::optional<HealthSummary> health;             // coupled runs only
  std::optional<EnergyAuditSummary> energy_audit;  // coupled runs that began their steps
  std::optional<CheckpointRecord> checkpoints;     // coupled runs
  std::vector<ResumeRecord> resumes;               // in order
};

// Writes DIR/run.json whole or not at all (a reader never sees a part of it). Throws fsi::Error
// naming the file and the fix if it cannot; the previous run.json stays then.
void write_run_manifest(const std::filesystem::path& output_dir, const scene::Scene& scene,
                        const RunRecord& record);

}  // namespace fsi::coupling
