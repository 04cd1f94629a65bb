#include "fsi/coupling/session.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <thread>

#include "fsi/common/error.hpp"
#include "fsi/common/stopwatch.hpp"
#include "fsi/common/text.hpp"
#include "fsi/coupling/energy_audit.hpp"
#include "fsi/coupling/fluid_health.hpp"
#include "fsi/coupling/force_predictor.hpp"
#include "fsi/coupling/output.hpp"
#include "fsi/coupling/particle_pairs.hpp"
#include "fsi/coupling/progress.hpp"
#include "fsi/coupling/release_check.hpp"
#include "fsi/coupling/run_manifest.hpp"
#include "fsi/coupling/structure_side.hpp"
#include "fsi/coupling/tcp_fluid_side.hpp"
#include "fsi/coupling/vtk_output.hpp"
#include "fsi/output/checkpoint_store.hpp"
#include "fsi/output/state_archive.hpp"
#include "fsi/scene/physics_checks.hpp"

namespace fsi::coupling {
namespace {

namespace fs = std::filesystem;

std::atomic<int> g_stop_signal{0};
extern "C" void on_stop_signal(int signal) {
  g_stop_signal = signal;
}

struct Timings {
  Stopwatch total, setup, coupled, mbd, output, round_trip, checkpoint;
};

// The checkpoint files of the two sides.
constexpr const char* kServerStateFile = "server.state";
constexpr const char* kFluidStateFile = "fluid.state";

void put_optional(output::StateWriter& out, const std::optional<double>& value) {
  out.put(value.has_value());
  out.put(value.value_or(0.0));
}

std::optional<double> optional_f64(output::StateReader& in, std::string_view what) {
  const bool present = in.boolean(what);
  const double value = in.f64(what);
  return present ? std::optional<double>(value) : std::nullopt;
}

// What to change when the energy audit warns or stops the run, and by how much: the lag of the
// held force first (measured on the light floating box, examples/floating_box/stability_map.json:
// unstable at 20 substeps, stable at 5 and 1), then the structure.
std::string coupling_energy_remedy(const scene::Scene& scene) {
  const int k = scene.solver.substeps;
  std::string fix;
  if (k > 1) {
    fix = "lower SolverOptions.Timeint.substeps from " + std::to_string(k) + " to at most " +
          std::to_string(std::max(1, k / 4)) +
          " (the light box of examples/floating_box: unstable at 20, stable at 5)";
    if (scene.solver.linear_force_predictor)
      fix += " and set SolverOptions.Timeint.force_predictor = \"none\"";
  } else {
    char step[32];
    std::snprintf(step, sizeof step, "%.3g", scene.solver.step_size / 2.0);
    fix = "halve SolverOptions.Timeint.step_size (to " + std::string(step) + " s)";
  }
  return fix +
         "; or make the structure heavier or stiffer against the water it moves, or damp a "
         "flexible body's own modes (AncfBeam2D axial_damping, bending_damping: the strip of "
         "examples/pump/pump_fine.scene) "
         "(FluidHealth.max_coupling_energy_growth = 0 turns the check off; not advised: the "
         "energy keeps growing)";
}

// What the server learns of the fluid beyond its forces.
struct FluidWatch {
  FluidRecord record;
  double closest_approach_over_r0 = std::numeric_limits<double>::infinity();
  bool balance_warned = false;
  bool health_unreported_warned = false;
  double last_snapshot_time = 0.0;
  double last_density_deviation = 0.0;  // max |rho/rho0 - 1| in the latest snapshot
  double last_max_speed = 0.0;          // max |v| in the latest snapshot [m/s]
  std::uint64_t last_close_pairs = 0;   // particle pairs closer than d/2 in it
  double last_closest_pair = 0.0;       // the closest of them [m]; 0: none
  double closest_since_report = std::numeric_limits<double>::infinity();
};

class Session {
 public:
  Session(scene::Scene& scene, const ServerOptions& options, FluidSide& fluid)
      : scene_(scene),
        options_(options),
        fluid_(fluid),
        audit_(scene.health.max_coupling_energy_growth, coupling_energy_remedy(scene),
               audit_noise_floor(
                   audit_energy_scale(scene.fluid.mass * static_cast<double>(scene.fluid.count()),
                                      scene::speed_of_sound(scene).value_or(0.0)))),
        health_(scene.health, scene.liggghts.allowed_lost_particles, fluid_scales(scene)),
        progress_logger_(spdlog::get("progress") ? spdlog::get("progress")
                                                 : spdlog::default_logger()) {
    watch_.record.speed_of_sound = scene::speed_of_sound(scene);
    audit_by_body();
  }

  int run() {
    timings_.total.start();
    started_utc_ = utc_now();
    int status = 0;
    try {
      if (options_.resume) {
        resume();
      } else {
        prepare_output();
        // From now on the folder says which run it holds, also when this run is killed.
        write_run_manifest(options_.output_dir, scene_, record());
        set_up();
        // With the release's check and the set-up's time, for a script reading it mid-run.
        write_run_manifest(options_.output_dir, scene_, record());
      }
      couple();
      fluid_.finish();
      status_ = "completed";
    } catch (const std::exception& failure) {
      status = 1;
      status_ = "failed";
      reason_ = failure.what();
      spdlog::error("{}", failure.what());
      fluid_.report_fault(failure, coupling_);
    }
    timings_.total.stop();
    if (structure_) {
      const std::string drift = constraint_drift_warning(structure_->position_constraint_drift(),
                                                         scene_.solver.constraint_form);
      if (!drift.empty()) spdlog::warn("{}", drift);
    }
    try {
      if (sensors_) sensors_->flush();
      // A resume that failed before it took the checkpoint's state leaves the earlier run's
      // run.json as it was: the record of the run is still that one.
      if (!options_.resume || resumed_state_)
        write_run_manifest(options_.output_dir, scene_, record());
    } catch (const std::exception& failure) {
      spdlog::error("writing run.json failed: {}", failure.what());
      status = 1;
    }
    report_particle_pairs();
    if (status == 0) {
      spdlog::info("run completed: {} steps in {:.1f} s; results in {}", steps_done_,
                   timings_.total.seconds(), options_.output_dir);
      if (const std::vector<std::string> near = health_.near_limits(); !near.empty()) {
        std::string figures;
        for (const std::string& figure : near)
          figures += (figures.empty() ? "" : "; ") + figure;
        spdlog::warn(
            "the run came within 20 % of a health limit's stop, or past its warning level: {}. It "
            "completed, but a result this close to a stop is at the edge of what the resolution "
            "and the speed of sound hold: check it at a finer spacing or a larger c "
            "(docs/user-guide.md, \"When a run stops: the health checks\")",
            figures);
      }
    } else if (options_.resume && !resumed_state_) {
      spdlog::error("resume refused: the run in {} is as it was", options_.output_dir);
    } else {
      spdlog::error("run failed after {} coupled steps; partial results in {}", steps_done_,
                    options_.output_dir);
    }
    return status;
  }

 private:
  // The output files: new ones, or (resumed) the earlier run's cut back to the checkpoint.
  void prepare_output(std::optional<std::uint64_t> sensors_length = std::nullopt,
                      std::optional<std::uint64_t> energy_length = std::nullopt) {
    create_run_folder(options_.output_dir);
    sensors_ = std::make_unique<SensorFile>(fs::path(options_.output_dir) / "sensors.csv",
                                            "fsi-server sensors of " + scene_.file, scene_.sensors,
                                            scene_.probes, scene_.dimension, sensors_length);
    probe_columns_ = 0;
    for (const auto& probe : scene_.probes)
      probe_columns_ += probes::columns(probe, scene_.dimension).size();
    const std::string work_unit = scene_.dimension == 3 ? "J" : "J/m";
    std::vector<std::string> energy_columns{"work_fluid_on_structure", "work_structure_on_fluid",
                                            "coupling_energy"};
    // With several bodies, each body's own books too (the audit's parts, in their order).
    const AuditParts parts = audit_parts();
    if (parts.bodies.size() > 1) {
      for (const std::string& body : parts.bodies) {
        energy_columns.push_back("work_fluid_on_" + column_safe(body));
        energy_columns.push_back("coupling_energy_" + column_safe(body));
      }
    }
    energy_ = std::make_unique<SensorFile>(
        (fs::path(options_.output_dir) / "energy.csv").string(),
        "fsi-server energy audit of the coupling of " + scene_.file +
            " (docs/theory.md, \"The energy audit\")",
        energy_columns, std::vector<std::string>(energy_columns.size(), work_unit), energy_length);
    if (scene_.output.snapshot_every_steps > 0) {
      fs::create_directories(fs::path(options_.output_dir) / "snapshots");
      vtk_ = std::make_unique<VtkOutput>(fs::path(options_.output_dir) / "vtk");
    }
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
  }

  void set_up() {
    timings_.setup.start();
    // The fluid advances by the coupled step, so the structure does too, whatever
    // Timeint.method says (fsi-server warns about that before the run).
    structure_ = std::make_unique<StructureSide>(scene_, scene::IntegrationMethod::FixedStep);
    std::vector<double> positions, velocities;
    structure_->boundary_state(positions, velocities);
    fluid_.set_up(scene_, positions, velocities);
    const bool spatial = scene_.dimension == 3;
    spdlog::info(
        "sent set-up ({}D): {} particles (m = {:.6g} {}), {} boundary vertices ({} dynamic), {} "
        "{}; client runs script 1, {} equilibration steps, script 2",
        scene_.dimension, scene_.fluid.count(), scene_.fluid.mass, spatial ? "kg" : "kg/m",
        scene_.boundary.vertex_count, scene_.boundary.dynamic_vertex_count,
        scene_.boundary.element_count(), spatial ? "triangles" : "segments",
        scene_.liggghts.equilibration_steps);
    FluidReady ready = fluid_.equilibrate();
    take_ready(ready);
    take_forces(ready.initial_forces, 0);
    {
      const BoundaryMotion start = structure_->boundary_motion(0, scene_.solver.step_size);
      audit_.start(start.positions, start.velocities, ready.initial_forces.forces);
    }
    if (ready.release) judge_release(*ready.release, ready.initial_forces.diagnostics);
    timings_.setup.stop();
    write_initial_output(ready.initial_forces.probe_values);
  }

  // Row and frame at t = 0: the structure as given and the fluid as equilibrated around it, with
  // the forces they exchange before the first step.
  void write_initial_output(const std::vector<double>& probe_values) {
    {
      ScopedTimer timer(timings_.output);
      sensors_->write(0.0, with_probes(structure_->initial_sensor_readout(total_fluid_force_),
                                       probe_values, 0));
      energy_->write(0.0, std::vector<double>(energy_->columns(), 0.0));
    }
    if (scene_.output.snapshot_every_steps > 0) take_snapshot(0);
  }

  void take_ready(const FluidReady& ready) {
    FluidRecord& record = watch_.record;
    record.particle_count = ready.particle_count;
    record.particles_initial = ready.particle_count;
    health_.set_initial_particles(ready.particle_count);
    const scene::FluidHealthLimits& limits = health_.limits();
    spdlog::info(
        "fluid health checks at every exchange: stop at NaN, a particle closer than {:.3g} r0 "
        "to a wall, |rho/rho0 - 1| > {:.3g}, |v| > {:.3g} c, more than {} particle(s) lost, "
        "a coupling energy grown {:.3g} times after the energy audit's warning (0: not checked; "
        "judged above {:.3g} {}, {:.3g} of the fluid's 1/2 M (c/10)^2; scene block FluidHealth, "
        "LIGGGHTS.allowed_lost_particles)",
        limits.min_wall_distance, limits.max_density_deviation, limits.max_mach,
        health_.allowed_lost_particles(), limits.max_coupling_energy_growth, audit_.noise_floor(),
        scene_.dimension == 3 ? "J" : "J/m", kAuditNoiseFraction);
    record.liggghts_version = ready.liggghts_version;
    record.seconds_client_setup = ready.seconds_setup;
    record.seconds_client_equilibration = ready.seconds_equilibration;
    spdlog::info("client ready: {} particles in LIGGGHTS; set-up {:.2f} s, equilibration {:.2f} s",
                 ready.particle_count, ready.seconds_setup, ready.seconds_equilibration);
    if (ready.particle_count == 0) {
      // A run without fluid would "complete" and weigh nothing: never silent garbage.
      throw Error("LIGGGHTS holds no particle after the set-up and the " +
                      std::to_string(scene_.liggghts.equilibration_steps) +
                      " equilibration steps (the scene generated " +
                      std::to_string(scene_.fluid.count()) + ")",
                  "the client's Ready message",
                  "the particles left the LIGGGHTS box or were deleted by a script: check the "
                  "box in script 1 against the fluid region, the particle mass (rho0 d^2 in 2D, "
                  "rho0 d^3 in 3D), the time step and the equilibration viscosity");
    }
    if (ready.particle_count != scene_.fluid.count()) {
      spdlog::warn(
          "LIGGGHTS holds {} particles, the scene generated {} (the scripts create or delete "
          "particles)",
          ready.particle_count, scene_.fluid.count());
    }
  }

  // The water must be at rest when the bodies are released: weighed against the fluid's force on
  // every mesh at t = 0.
  void judge_release(const protocol::ReleaseState& release,
                     const protocol::ForceDiagnostics& initial) {
    const ReleaseCheck check =
        check_release(release, initial.force_on_structure, scene_.gravity,
                      scene_.liggghts.equilibration_steps, scene_.liggghts.settling_drag);
    spdlog::info(
        "fluid at release: settling drag {:.4g} 1/s (H = {:.4g} m); the structure carries {} of "
        "the fluid's weight {:.6g} {}; kinetic / potential energy {}",
        check.settling_drag, check.column_height,
        check.weight_fraction ? fmt::format("{:.2f} %", 100.0 * *check.weight_fraction)
                              : std::string("-"),
        check.weight, scene_.dimension == 3 ? "N" : "N/m",
        check.kinetic_over_potential ? fmt::format("{:.3e}", *check.kinetic_over_potential)
                                     : std::string("-"));
    if (!check.at_rest) {
      spdlog::warn("{}", check.warning);
      health_.set_unsettled_release(
          check.weight_fraction
              ? fmt::format("the structure carried {:.1f} % of the fluid's weight",
                            100.0 * *check.weight_fraction)
              : std::string("its kinetic energy was not small against its potential energy"));
    }
    release_ = check;
  }

  // The fluid forces on the dynamic vertices become point loads held over the next step; the
  // fluid's diagnostics are checked and kept for run.json and the progress report.
  void take_forces(const FluidForces& forces, std::uint64_t step) {
    const auto& d = forces.diagnostics;
    // Recorded before the judgement, so that run.json of a stopped run shows what stopped it.
    watch_.closest_approach_over_r0 =
        std::min(watch_.closest_approach_over_r0, d.closest_approach_over_r0);
    watch_.closest_since_report = std::min(watch_.closest_since_report, d.closest_approach_over_r0);
    watch_.record.particles_final = d.particle_count;
    judge_health(forces, step);
    structure_->apply_vertex_forces(predicted(forces.forces, step), step);
    // Held for the sensors of the step these forces act in (like the point loads).
    total_fluid_force_ = d.force_on_structure;
    FluidRecord& record = watch_.record;
    record.seconds_liggghts += d.seconds_liggghts;
    record.seconds_contact += d.seconds_contact;
    record.seconds_client_communication += d.seconds_client_communication;
    if (d.pair_force_magnitude_sum > 0.0) {
      double imbalance = 0.0;
      for (int k = 0; k < 3; ++k)
        imbalance = std::max(imbalance, std::abs(d.force_on_fluid[k] + d.force_on_structure[k]));
      const double ratio = imbalance / d.pair_force_magnitude_sum;
      record.max_action_reaction = std::max(record.max_action_reaction, ratio);
      if (ratio > 1e-12 && !watch_.balance_warned) {
        spdlog::warn(
            "step {}: forces on fluid and structure differ by {:.3e} of the pair force sum (> "
            "1e-12)",
            step, ratio);
        watch_.balance_warned = true;
      }
    }
    if (d.particle_count == 0) {
      throw Error("every particle has left LIGGGHTS (" + std::to_string(record.particles_initial) +
                      " at the start)",
                  "step " + std::to_string(step),
                  "the fluid left the LIGGGHTS box: check the box in script 1, the time step "
                  "(fsi-server --check lists the physics warnings) and the wall forces");
    }
  }

  // The force the structure moves under: the fluid's (average) force, or with
  // SolverOptions.Timeint.force_predictor = "linear" and substeps > 1 that force extrapolated
  // over the fluid steps it lags (force_predictor.hpp), from the first averaged exchange on (the
  // forces at release are no average). predicted_ is empty when the force is not predicted.
  std::span<const double> predicted(const std::vector<double>& average, std::uint64_t step) {
    predicted_ = {};
    if (!scene_.solver.linear_force_predictor || scene_.solver.substeps == 1 || step == 0)
      return average;
    predicted_ = predictor_.apply(average);  // valid until the next exchange's call
    return predicted_;
  }

  // The run judges its fluid (fluid_health.hpp): a failing check ends the run with its diagnosis
  // before this step's forces act or its output is written.
  void judge_health(const FluidForces& forces, std::uint64_t step) {
    if (!forces.health && !watch_.health_unreported_warned) {
      spdlog::warn(
          "the fluid side reports no FluidHealth (an fsi-client of protocol 1.2): density and "
          "particle speed are not checked, only recorded at the snapshots; use an fsi-client of "
          "protocol 1.3 or later");
      watch_.health_unreported_warned = true;
    }
    const HealthVerdict verdict = health_.judge(step, forces);
    for (const HealthFinding& warning : verdict.warnings)
      spdlog::warn("fluid health ({}): {}; {}", warning.check, warning.message, warning.fix);
    if (verdict.stop) {
      std::string fix = verdict.stop->fix;
      const std::string at_stop = snapshot_at_stop(step, fix);
      throw Error("fluid health check '" + verdict.stop->check +
                      "' failed: " + verdict.stop->message + at_stop,
                  "step " + std::to_string(step), fix);
    }
  }

  // A run stopped by a health check keeps the fluid of its stopping step (when the scene writes
  // snapshots at all) and names the particle of the extreme density in it: a user had to rerun
  // with snapshots every 100 steps to find it, and still saw it 98 steps early. The fluid has
  // answered this step's exchange, so it can still be asked. When that particle is one of a pair
  // closer than d/2, `fix` is told first that the speed of sound is not the cure there.
  std::string snapshot_at_stop(std::uint64_t step, std::string& fix) {
    if (scene_.output.snapshot_every_steps == 0 || !vtk_) return {};
    ParticleSnapshot snapshot;
    try {
      snapshot = fluid_.snapshot(step);
      char name[64];
      std::snprintf(name, sizeof name, "particles_%09llu.csv",
                    static_cast<unsigned long long>(step));
      write_snapshot_csv((fs::path(options_.output_dir) / "snapshots" / name).string(), snapshot);
      vtk_->write(snapshot, scene_.model, structure_->state(), scene_.boundary,
                  structure_->vertex_loads());
      ++snapshots_;
      record_health(snapshot);  // its pairs and extremes belong to the run's record
    } catch (const std::exception& failure) {
      spdlog::warn("no snapshot of the stopping step: {}", failure.what());
      return {};
    }
    const double rho0 = scene_.fluid.density;
    const auto dimension = static_cast<std::size_t>(snapshot.dimension);
    std::size_t worst = snapshot.density.size();
    double deviation = -1.0;
    for (std::size_t i = 0; i < snapshot.density.size(); ++i) {
      const double d = std::abs(snapshot.density[i] / rho0 - 1.0);
      if (!std::isfinite(d) || d > deviation) {
        worst = i;
        deviation = std::isfinite(d) ? d : std::numeric_limits<double>::infinity();
      }
      if (!std::isfinite(d)) break;
    }
    if (worst >= snapshot.density.size() || dimension * (worst + 1) > snapshot.positions.size())
      return {};
    const std::string where =
        point_text(std::span(snapshot.positions).subspan(dimension * worst, dimension), 6);
    // A pair closer than d/2 is what the Shepard filter lets form along the walls: c is not
    // the cure there.
    std::string pair;
    const double spacing = scene_.fluid.spacing;
    if (const auto nearest =
            nearest_particle_distance(snapshot.positions, snapshot.dimension, worst);
        nearest && spacing > 0.0 && *nearest < 0.5 * spacing) {
      pair = fmt::format("; it is one of a particle pair {:.2f} d apart (closer than d/2)",
                         *nearest / spacing);
      fix =
          "the particle is one of a pair that LIGGGHTS' Shepard density filter does not push "
          "apart, which a wall moving through it compresses (docs/theory.md, \"Particle pairs "
          "along the walls\"): a larger speed of sound only delays such a stop (18 s at c = 28 "
          "m/s, 26 s at 40 m/s in examples/wave_flume) and no setting removes it; end the run "
          "before, or delay it as follows: " +
          fix;
    }
    return fmt::format(
        "; the particle of the extreme density at this step: id {} at {} m, rho = {:.6g} kg/m^3 "
        "(snapshots/particles_{:09d}.csv holds the fluid of this step){}",
        worst < snapshot.ids.size() ? snapshot.ids[worst] : 0, where, snapshot.density[worst], step,
        pair);
  }

  void couple() {
    coupling_ = true;
    timings_.coupled.start();
    const double dt = scene_.solver.step_size;
    const std::uint64_t steps = scene_.solver.step_count();
    // Multi-rate coupling: one structure step per `substeps` fluid steps (the scene checked
    // that the run, its rows and snapshots fall on structure steps).
    const auto k = static_cast<std::uint64_t>(scene_.solver.substeps);
    if (k > 1) {
      spdlog::info(
          "coupled phase: {} steps of {:.3g} s to t = {:.6g} s; the structure steps {:.3g} s, "
          "once per {} fluid steps ({} structure steps and exchanges)",
          steps, dt, static_cast<double>(steps) * dt, static_cast<double>(k) * dt, k, steps / k);
    } else {
      spdlog::info("coupled phase: {} steps of {:.3g} s to t = {:.6g} s", steps, dt,
                   static_cast<double>(steps) * dt);
    }
    coupled_begin_ = std::chrono::steady_clock::now();
    last_log_ = last_live_ = last_checkpoint_ = coupled_begin_;
    first_step_ = step_at_last_log_ = steps_done_;
    checkpoints_ =
        scene_.output.checkpoint_every_steps > 0 || scene_.output.checkpoint_every_seconds > 0.0;
    if (checkpoints_ && !fluid_.can_checkpoint()) {
      if (scene_.output.checkpoint_every_steps > 0) {
        throw Error("Output.checkpoint_every_steps = " +
                        std::to_string(scene_.output.checkpoint_every_steps) +
                        ", but the fluid side cannot write checkpoints (an fsi-client older "
                        "than protocol 1.6)",
                    "checkpoints",
                    "use matching fsi-server and fsi-client releases, or set "
                    "Output.checkpoint_every_steps = 0");
      }
      spdlog::warn(
          "no checkpoints in this run: the fluid side cannot write them (an fsi-client "
          "older than protocol 1.6)");
      checkpoints_ = false;
    }
    if (steps_done_ >= steps) {
      throw Error("the checkpoint is at step " + std::to_string(steps_done_) +
                      ", the scene's run ends at step " + std::to_string(steps),
                  "--resume", "raise SolverOptions.end_time to continue the run beyond it");
    }
    while (true) {
      try {
        steps_to_end(steps, dt, k);
        break;
      } catch (const std::exception& failure) {
        if (!may_reconnect(failure)) throw;
        roll_back(failure);
      }
    }
    if (options_.live_status) options_.live_status("");
    timings_.coupled.stop();
  }

  void steps_to_end(std::uint64_t steps, double dt, std::uint64_t k) {
    for (std::uint64_t n = steps_done_ + k; n <= steps; n += k) {
      if (g_stop_signal != 0) {
        throw Error("stopped by signal " + std::to_string(g_stop_signal.load()) + " at step " +
                        std::to_string(n),
                    "fsi-server", "results up to this step are in the output folder");
      }
      coupled_step(n, dt, k);
      if (scene_.output.snapshot_every_steps > 0 &&
          n % static_cast<std::uint64_t>(scene_.output.snapshot_every_steps) == 0) {
        take_snapshot(n);
      }
      if (checkpoint_due(n, steps)) write_checkpoint(n);
      report_progress(n, steps);
    }
  }

  // A lost fluid side is waited for again (--reconnect-timeout) when there is a checkpoint to go
  // back to, and not more than kMaxRollbacksPerCheckpoint times to the same one (a client that
  // dies at the same step every time would otherwise be restarted forever).
  static constexpr int kMaxRollbacksPerCheckpoint = 3;
  bool may_reconnect(const std::exception& failure) {
    if (options_.reconnect_timeout.count() <= 0 || !fluid_.peer_lost(failure)) return false;
    if (!last_checkpoint_step_) {
      spdlog::error("the fluid side is gone and there is no checkpoint to go back to");
      return false;
    }
    if (rollback_step_ == last_checkpoint_step_) {
      if (++rollbacks_to_step_ > kMaxRollbacksPerCheckpoint) {
        spdlog::error("the fluid side was lost {} times after the checkpoint of step {}; giving up",
                      kMaxRollbacksPerCheckpoint, *last_checkpoint_step_);
        return false;
      }
    } else {
      rollback_step_ = last_checkpoint_step_;
      rollbacks_to_step_ = 1;
    }
    return true;
  }

  // Thesis Fig. 4.10: the structure moves from t(n-k) to t(n) under f(t(n-k)), the fluid follows
  // the boundary to t(n) and returns f(t(n)). k = 1: the thesis' scheme; k > 1 (multi-rate): the
  // fluid takes k steps of dt against the interpolated wall and returns their average force.
  void coupled_step(std::uint64_t n, double dt, std::uint64_t k) {
    BoundaryMotion motion;
    std::optional<std::vector<double>> row;  // this step's sensor row, when it is written
    {
      // The fluid waits for the boundary meanwhile.
      const auto waiting = fluid_.waiting();
      {
        ScopedTimer timer(timings_.mbd);
        structure_->advance(n / k, static_cast<double>(k) * dt);
      }
      {
        ScopedTimer timer(timings_.output);
        // Sensors at t_n: multipliers of the step and the fluid forces that acted during it.
        // The probes of t_n come with the fluid's answer to this step: the row waits for them.
        if (n % static_cast<std::uint64_t>(scene_.output.sensor_every_steps) == 0) {
          row = structure_->sensor_readout(total_fluid_force_);
          if (probe_columns_ == 0) {
            sensors_->write(structure_->time(), *row);
            row.reset();
          }
        }
      }
      motion = structure_->boundary_motion(n, dt);
    }
    timings_.round_trip.start();
    const FluidForces forces = fluid_.exchange(motion);
    timings_.round_trip.stop();
    if (row) {
      ScopedTimer timer(timings_.output);
      sensors_->write(structure_->time(), with_probes(std::move(*row), forces.probe_values, n));
    }
    take_forces(forces, n);
    audit(motion, forces, n, dt,
          n % static_cast<std::uint64_t>(scene_.output.sensor_every_steps) == 0);
    steps_done_ = n;
  }

  // The energy audit's books by body (EnergyAudit::set_parts): the body of every dynamic vertex's
  // values, the bodies in the order their first vertex comes.
  struct AuditParts {
    std::vector<std::uint32_t> part_of_value;
    std::vector<std::string> bodies;  // the bodies' names
  };
  AuditParts audit_parts() const {
    const scene::BoundaryMesh& boundary = scene_.boundary;
    const auto dimension = static_cast<std::size_t>(scene_.dimension);
    std::map<mbd::BodyId, std::uint32_t> part_of_body;
    AuditParts parts;
    parts.part_of_value.reserve(dimension * boundary.dynamic_vertex_count);
    for (std::size_t v = 0; v < boundary.dynamic_vertex_count; ++v) {
      const mbd::BodyId body =
          scene::vertex_body(boundary, scene_.model, static_cast<std::uint32_t>(v));
      auto [found, added] =
          part_of_body.emplace(body, static_cast<std::uint32_t>(part_of_body.size()));
      if (added) parts.bodies.push_back(scene_.model.body_name(body));
      parts.part_of_value.insert(parts.part_of_value.end(), dimension, found->second);
    }
    return parts;
  }

  // A body's name as part of a CSV column name: letters, digits and '_' kept, the rest '_'.
  static std::string column_safe(std::string name) {
    for (char& c : name) {
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
    }
    return name;
  }

  void audit_by_body() {
    AuditParts parts = audit_parts();
    std::vector<std::string> names;
    for (const std::string& body : parts.bodies)
      names.push_back("body '" + body + "'");
    audit_.set_parts(std::move(parts.part_of_value), std::move(names));
  }

  // The energy audit of this exchange (energy_audit.hpp); its totals go to energy.csv at the
  // sensor rows, its warning to the log once.
  void audit(const BoundaryMotion& motion, const FluidForces& forces, std::uint64_t n, double dt,
             bool sensor_row) {
    if (motion.substeps > 1) {
      // Multi-rate: the fluid's forces are averages over the structure step of k dt; its work
      // on the fluid is taken as the average force over the step's displacement (the wall's
      // mean velocity over the step), the pairing of docs/theory.md, "The energy audit".
      const double step = static_cast<double>(motion.substeps) * dt;
      const std::size_t values = motion.positions.size();
      std::vector<double> mean_velocity(values);
      for (std::size_t i = 0; i < values; ++i)
        mean_velocity[i] = (motion.positions[i] - motion.node_positions[i]) / step;
      audit_.exchange(motion.positions, mean_velocity, step, forces.forces, n, predicted_);
    } else {
      audit_.exchange(motion.positions, motion.velocities, dt, forces.forces, n);
    }
    if (const std::string warning = audit_.take_warning(); !warning.empty())
      spdlog::warn("energy audit: {}", warning);
    if (sensor_row || !audit_.stop().empty()) {
      ScopedTimer timer(timings_.output);
      const EnergyTotals& totals = audit_.totals();
      std::vector<double> row{totals.work_fluid_on_structure, totals.work_structure_on_fluid,
                              totals.coupling_energy};
      if (audit_.parts().size() > 1) {
        for (const EnergyAudit::Part& part : audit_.parts()) {
          row.push_back(part.totals.work_fluid_on_structure);
          row.push_back(part.totals.coupling_energy);
        }
      }
      energy_->write(structure_->time(), row);
    }
    if (!audit_.stop().empty()) {
      health_.record_failed_check(kCheckCouplingEnergy);
      throw Error(std::string("health check '") + kCheckCouplingEnergy +
                      "' failed (energy audit): " + audit_.stop(),
                  "step " + std::to_string(n), audit_.remedy());
    }
  }

  // A sensor row followed by the probes' values of the same step (none without probes).
  std::vector<double> with_probes(std::vector<double> row, const std::vector<double>& probe_values,
                                  std::uint64_t step) const {
    if (probe_values.size() != probe_columns_) {
      throw Error("the fluid side returned " + std::to_string(probe_values.size()) +
                      " probe values at step " + std::to_string(step) +
                      ", the scene's probes have " + std::to_string(probe_columns_) + " columns",
                  "sensor row of step " + std::to_string(step),
                  "use matching fsi-server and fsi-client releases");
    }
    row.insert(row.end(), probe_values.begin(), probe_values.end());
    return row;
  }

  void report_progress(std::uint64_t n, std::uint64_t steps) {
    const auto now = std::chrono::steady_clock::now();
    const bool log_due = now - last_log_ >= options_.progress_interval || n == steps;
    const bool live_due =
        options_.live_status && (now - last_live_ >= std::chrono::milliseconds(250) || n == steps);
    if (!log_due && !live_due) return;
    ProgressSample sample;
    sample.time = structure_->time();
    sample.end_time = static_cast<double>(steps) * scene_.solver.step_size;
    sample.step = n;
    sample.steps = steps;
    // The recent pace: since the previous log line when that is at least a second ago (a run
    // that slows down, a machine that got busy, shows at once), else since the coupled phase
    // began.
    const double recent = std::chrono::duration<double>(now - last_log_).count();
    sample.steps_per_second =
        recent >= 1.0
            ? static_cast<double>(n - step_at_last_log_) / recent
            : static_cast<double>(n - first_step_) /
                  std::max(1e-9, std::chrono::duration<double>(now - coupled_begin_).count());
    sample.closest_approach_over_r0 = watch_.closest_since_report;
    if (watch_.record.snapshots_checked > 0) {
      sample.snapshot_time = watch_.last_snapshot_time;
      sample.density_deviation = watch_.last_density_deviation;
      sample.max_speed = watch_.last_max_speed;
      if (scene_.fluid.spacing > 0.0) {
        sample.close_pairs = watch_.last_close_pairs;
        if (watch_.last_close_pairs > 0)
          sample.closest_pair_over_spacing = watch_.last_closest_pair / scene_.fluid.spacing;
      }
    }
    sample.speed_of_sound = watch_.record.speed_of_sound;
    const std::string line = format_progress(sample);
    if (live_due) {
      options_.live_status(line);
      last_live_ = now;
    }
    if (log_due) {
      progress_logger_->info("{}", line);
      last_log_ = now;
      step_at_last_log_ = n;
      // run.json follows the run at the log's pace: steps, timings, health so far ("status"
      // stays "started" until the run ends).
      write_run_manifest(options_.output_dir, scene_, record());
      // The closest approach of a log line covers the whole interval since the previous one.
      watch_.closest_since_report = std::numeric_limits<double>::infinity();
    }
  }

  void take_snapshot(std::uint64_t n) {
    ScopedTimer timer(timings_.output);
    const ParticleSnapshot snapshot = fluid_.snapshot(n);
    const auto writing = fluid_.waiting();
    char name[64];
    std::snprintf(name, sizeof name, "particles_%09llu.csv", static_cast<unsigned long long>(n));
    record_health(snapshot);
    write_snapshot_csv((fs::path(options_.output_dir) / "snapshots" / name).string(), snapshot);
    vtk_->write(snapshot, scene_.model, structure_->state(), scene_.boundary,
                structure_->vertex_loads());
    ++snapshots_;
  }

  void record_health(const ParticleSnapshot& snapshot) {
    const double rho0 = scene_.fluid.density;
    double deviation = 0.0;
    if (rho0 > 0.0) {
      for (double rho : snapshot.density)
        deviation = std::max(deviation, std::abs(rho / rho0 - 1.0));
    }
    const std::size_t dimension = static_cast<std::size_t>(scene_.fluid.dimension);
    double speed2 = 0.0;
    for (std::size_t i = 0; i + dimension <= snapshot.velocities.size(); i += dimension) {
      double v2 = 0.0;
      for (std::size_t k = 0; k < dimension; ++k)
        v2 += snapshot.velocities[i + k] * snapshot.velocities[i + k];
      speed2 = std::max(speed2, v2);
    }
    FluidRecord& record = watch_.record;
    ++record.snapshots_checked;
    watch_.last_snapshot_time = snapshot.time;
    watch_.last_density_deviation = deviation;
    watch_.last_max_speed = std::sqrt(speed2);
    record.max_density_deviation = std::max(record.max_density_deviation, deviation);
    record.max_particle_speed = std::max(record.max_particle_speed, watch_.last_max_speed);
    if (scene_.fluid.spacing <= 0.0) return;
    const ParticlePairs pairs = particle_pairs_closer_than(snapshot.positions, snapshot.dimension,
                                                           0.5 * scene_.fluid.spacing);
    watch_.last_close_pairs = pairs.count;
    watch_.last_closest_pair = pairs.closest.value_or(0.0);
    record.max_close_pairs = std::max<std::uint64_t>(record.max_close_pairs, pairs.count);
    const double spacing = scene_.fluid.spacing;
    if (pairs.closest && (!record.closest_pair_over_spacing ||
                          *pairs.closest / spacing < *record.closest_pair_over_spacing)) {
      record.closest_pair_over_spacing = *pairs.closest / spacing;
      record.closest_pair_where = pairs.where;
      record.closest_pair_time = snapshot.time;
    }
  }

  // The pairs the snapshots saw, for the end of the log (docs/theory.md, "Particle pairs along
  // the walls"): where a wall moves through such a pair, long runs stop on its density.
  void report_particle_pairs() const {
    const FluidRecord& record = watch_.record;
    if (record.snapshots_checked == 0 || scene_.fluid.spacing <= 0.0) return;
    if (!record.closest_pair_over_spacing) {
      spdlog::info("particle pairs: none closer than d/2 = {:.3g} m in {} snapshot(s)",
                   0.5 * scene_.fluid.spacing, record.snapshots_checked);
      return;
    }
    spdlog::info(
        "particle pairs: up to {} closer than d/2 = {:.3g} m at once in {} snapshot(s); the "
        "closest {:.2f} d apart at {} m, t = {:.4g} s (pairs along the walls, first in concave "
        "corners, are what LIGGGHTS' Shepard density filter does not push apart; a wall moving "
        "through one can end a long run on the density check: docs/theory.md, \"Particle pairs "
        "along the walls\")",
        record.max_close_pairs, 0.5 * scene_.fluid.spacing, record.snapshots_checked,
        *record.closest_pair_over_spacing, point_text(record.closest_pair_where, 4),
        record.closest_pair_time);
  }

  // --- Checkpoints and resume (issue 16; docs/user-guide.md, "Checkpoints and resume") ---

  bool checkpoint_due(std::uint64_t n, std::uint64_t steps) const {
    if (!checkpoints_ || n >= steps) return false;  // the end is the results, not a checkpoint
    const long every_steps = scene_.output.checkpoint_every_steps;
    const double every_seconds = scene_.output.checkpoint_every_seconds;
    if (every_steps > 0 && n % static_cast<std::uint64_t>(every_steps) == 0) return true;
    return every_seconds > 0.0 && std::chrono::steady_clock::now() - last_checkpoint_ >=
                                      std::chrono::duration<double>(every_seconds);
  }

  output::CheckpointStore& checkpoint_store() {
    if (!store_) store_.emplace(fs::path(options_.output_dir) / "checkpoints");
    return *store_;
  }

  // Both sides' state at the end of step n, complete or not at all: the fluid's first (the
  // client may fail), then the server's, then both files synced, hashed and renamed
  // (checkpoint_store.hpp). A failure (a full disk) ends the run; the checkpoints before stay.
  void write_checkpoint(std::uint64_t n) {
    ScopedTimer timer(timings_.checkpoint);
    const std::string fluid_state = fluid_.checkpoint(n);
    const auto writing = fluid_.waiting();
    output::StateWriter state;
    save_state(state, n);
    output::CheckpointStore& store = checkpoint_store();
    try {
      store.begin(n);
      store.add(kServerStateFile, state.bytes());
      pause_for_tests(n);
      store.add(kFluidStateFile, fluid_state);
      const output::Checkpoint written = store.commit(structure_->time());
      ++checkpoints_written_;
      last_checkpoint_step_ = n;
      last_checkpoint_ = std::chrono::steady_clock::now();
      spdlog::info("checkpoint at step {} (t = {:.9g} s): {} ({:.3g} MB)", n, structure_->time(),
                   written.folder.string(),
                   static_cast<double>(state.bytes().size() + fluid_state.size()) / 1e6);
    } catch (const Error& failure) {
      store.abandon();
      const auto kept = store.list();
      throw Error(
          std::string(failure.fault()), "checkpoint of step " + std::to_string(n),
          std::string(failure.remedy()) +
              (kept.empty() ? std::string("; no earlier checkpoint exists")
                            : "; the checkpoint of step " + std::to_string(kept.back().step) +
                                  " is intact: fsi-server --resume " + options_.output_dir +
                                  " continues from it"));
    }
  }

  // FSI_TEST_SLOW_CHECKPOINT=STEP:SECONDS (integration tests only): the checkpoint of STEP waits
  // that long between its two files, so that a test can kill the server in the middle of it.
  static void pause_for_tests(std::uint64_t step) {
    const char* hook = std::getenv("FSI_TEST_SLOW_CHECKPOINT");
    if (hook == nullptr) return;
    unsigned long long slow_step = 0;
    double seconds = 0.0;
    if (std::sscanf(hook, "%llu:%lf", &slow_step, &seconds) == 2 && slow_step == step) {
      spdlog::warn("test hook: the checkpoint of step {} waits {} s between its files", step,
                   seconds);
      std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    }
  }

  // The server's half: the session's own state, then each part's, in a fixed order that
  // restore_state reads back.
  void save_state(output::StateWriter& out, std::uint64_t n) {
    out.section("session");
    out.put(scene_.file);
    out.put(scene_.solver.step_size);
    out.put(static_cast<std::uint64_t>(scene_.solver.substeps));
    out.put(static_cast<std::uint64_t>(scene_.dimension));
    out.put(static_cast<std::uint64_t>(scene_.boundary.dynamic_vertex_count));
    out.put(n);
    out.put(structure_->time());
    out.put(sensors_->length());
    out.put(energy_->length());
    out.put(snapshots_);
    for (double f : total_fluid_force_)
      out.put(f);
    out.put(started_utc_);
    out.put(checkpoints_written_ + 1);
    out.put(static_cast<std::uint64_t>(resumes_.size()));
    for (const ResumeRecord& resume : resumes_) {
      out.put(resume.utc);
      out.put(resume.step);
      out.put(resume.checkpoint);
      out.put(static_cast<std::uint64_t>(resume.client_ranks));
    }
    for (const Stopwatch* watch :
         {&timings_.total, &timings_.setup, &timings_.coupled, &timings_.mbd, &timings_.output,
          &timings_.round_trip, &timings_.checkpoint}) {
      out.put(watch->seconds());
    }
    const FluidRecord& fluid = watch_.record;
    out.put(fluid.particle_count);
    out.put(fluid.liggghts_version);
    for (double value :
         {fluid.seconds_client_setup, fluid.seconds_client_equilibration, fluid.seconds_liggghts,
          fluid.seconds_contact, fluid.seconds_client_communication, fluid.max_action_reaction,
          fluid.max_density_deviation, fluid.max_particle_speed, watch_.closest_approach_over_r0,
          watch_.last_snapshot_time, watch_.last_density_deviation, watch_.last_max_speed}) {
      out.put(value);
    }
    out.put(fluid.particles_initial);
    out.put(fluid.particles_final);
    out.put(fluid.snapshots_checked);
    out.put(fluid.max_close_pairs);
    put_optional(out, fluid.closest_pair_over_spacing);
    out.put(static_cast<std::uint64_t>(fluid.closest_pair_where.size()));
    for (double x : fluid.closest_pair_where)
      out.put(x);
    for (double value : {fluid.closest_pair_time, watch_.last_closest_pair})
      out.put(value);
    out.put(watch_.last_close_pairs);
    out.put(watch_.balance_warned);
    out.put(release_.has_value());
    if (release_) {
      const ReleaseCheck& r = *release_;
      for (double value : {r.settling_drag, r.column_height, r.fluid_mass, r.weight, r.carried,
                           r.kinetic_energy, r.potential_energy})
        out.put(value);
      put_optional(out, r.weight_fraction);
      put_optional(out, r.kinetic_over_potential);
      out.put(r.at_rest);
      out.put(r.warning);
    }
    structure_->save_state(out);
    audit_.save_state(out);
    predictor_.save_state(out);
    health_.save_state(out);
    out.put(vtk_ != nullptr);
    if (vtk_) vtk_->save_state(out);
  }

  // fsi-server --resume: the newest complete checkpoint of the output folder, both sides set up
  // from it, the output files cut back to it; couple() then goes on from its step.
  void resume() {
    timings_.setup.start();
    if (!fs::is_directory(options_.output_dir)) {
      throw Error("no run folder " + options_.output_dir, "--resume",
                  "give --resume (or --output with --resume) the folder of the run to continue");
    }
    restore_newest_checkpoint(true);
    timings_.setup.stop();
  }

  // The fluid side is gone during the coupled steps (--reconnect-timeout): back to the newest
  // checkpoint, its output files cut back to it, and a new fluid side set up from it (TCP: the
  // next client that connects within the timeout, on the same port).
  void roll_back(const std::exception& failure) {
    spdlog::warn(
        "the fluid side is gone ({}); back to the newest checkpoint, waiting up to {:.0f} "
        "s for fsi-client to connect again (the same command line)",
        failure.what(), std::chrono::duration<double>(options_.reconnect_timeout).count());
    // The open files go first: their last rows must not land after the cut.
    sensors_.reset();
    energy_.reset();
    vtk_.reset();
    restore_newest_checkpoint(false);
  }

  // Both sides from the newest complete checkpoint: the server's state, the output files cut
  // back to it, the fluid side resumed from its bytes. A fresh process (fsi-server --resume)
  // also continues the timings of the run; a rollback keeps its own (the lost steps took time).
  void restore_newest_checkpoint(bool fresh_process) {
    output::CheckpointStore& store = checkpoint_store();
    std::vector<std::string> skipped;
    const std::optional<output::Checkpoint> checkpoint = store.newest_valid(&skipped);
    for (const std::string& reason : skipped)
      spdlog::warn("checkpoint passed over: {}", reason);
    if (!checkpoint) {
      throw Error("no complete checkpoint in " + store.root().string(), "--resume",
                  "a run writes checkpoints every Output.checkpoint_every_steps steps or "
                  "checkpoint_every_seconds of wall time; without one, start the run afresh "
                  "(--overwrite)");
    }
    const std::string source = std::string(kServerStateFile) + " of " + checkpoint->folder.string();
    const std::string server_bytes = output::read_checkpoint_file(*checkpoint, kServerStateFile);
    const std::string fluid_bytes = output::read_checkpoint_file(*checkpoint, kFluidStateFile);
    output::StateReader in(server_bytes, source);
    in.section("session");
    const std::string scene_file = in.text("scene file");
    const double step_size = in.f64("step size");
    const std::uint64_t substeps = in.u64("substeps");
    const std::uint64_t dimension = in.u64("dimension");
    const std::uint64_t dynamic_vertices = in.u64("dynamic vertices");
    auto differs = [&](const std::string& what, const std::string& then, const std::string& now) {
      throw Error("the checkpoint was written with " + what + " " + then + ", the scene has " + now,
                  source,
                  "resume with the scene (and its parameters) that wrote the checkpoint; "
                  "only SolverOptions.end_time and the Output block may change");
    };
    if (step_size != scene_.solver.step_size) {
      differs("SolverOptions.Timeint.step_size", fmt::format("{:.17g}", step_size),
              fmt::format("{:.17g}", scene_.solver.step_size));
    }
    if (substeps != static_cast<std::uint64_t>(scene_.solver.substeps))
      differs("substeps", std::to_string(substeps), std::to_string(scene_.solver.substeps));
    if (dimension != static_cast<std::uint64_t>(scene_.dimension))
      differs("dimension", std::to_string(dimension), std::to_string(scene_.dimension));
    if (dynamic_vertices != scene_.boundary.dynamic_vertex_count) {
      differs("dynamic boundary vertices", std::to_string(dynamic_vertices),
              std::to_string(scene_.boundary.dynamic_vertex_count));
    }
    if (scene_file != scene_.file) {
      spdlog::warn("resuming the checkpoint of scene {} with scene {}", scene_file, scene_.file);
    }
    const std::uint64_t step = in.u64("step");
    const double time = in.f64("time");
    const std::uint64_t sensors_length = in.u64("sensors.csv length");
    const std::uint64_t energy_length = in.u64("energy.csv length");
    snapshots_ = in.u64("snapshots");
    for (double& f : total_fluid_force_)
      f = in.f64("total fluid force");
    started_utc_ = in.text("start");
    checkpoints_written_ = in.u64("checkpoints written");
    resumes_.resize(in.count("resumes"));
    for (ResumeRecord& resume : resumes_) {
      resume.utc = in.text("resume time");
      resume.step = in.u64("resume step");
      resume.checkpoint = in.text("resume checkpoint");
      resume.client_ranks = static_cast<std::uint32_t>(in.u64("resume ranks"));
    }
    for (Stopwatch* watch : {&timings_.total, &timings_.setup, &timings_.coupled, &timings_.mbd,
                             &timings_.output, &timings_.round_trip, &timings_.checkpoint}) {
      const double seconds = in.f64("timing");
      if (fresh_process) watch->add(seconds);
    }
    FluidRecord& fluid = watch_.record;
    fluid.particle_count = in.u64("particles");
    fluid.liggghts_version = in.text("LIGGGHTS version");
    for (double* value :
         {&fluid.seconds_client_setup, &fluid.seconds_client_equilibration, &fluid.seconds_liggghts,
          &fluid.seconds_contact, &fluid.seconds_client_communication, &fluid.max_action_reaction,
          &fluid.max_density_deviation, &fluid.max_particle_speed, &watch_.closest_approach_over_r0,
          &watch_.last_snapshot_time, &watch_.last_density_deviation, &watch_.last_max_speed}) {
      *value = in.f64("fluid record");
    }
    fluid.particles_initial = in.u64("particles at the start");
    fluid.particles_final = in.u64("particles at the checkpoint");
    fluid.snapshots_checked = in.u64("snapshots checked");
    fluid.max_close_pairs = in.u64("most particle pairs");
    fluid.closest_pair_over_spacing = optional_f64(in, "closest particle pair");
    fluid.closest_pair_where.resize(in.count("closest pair's place"));
    for (double& x : fluid.closest_pair_where)
      x = in.f64("closest pair's place");
    fluid.closest_pair_time = in.f64("closest pair's time");
    watch_.last_closest_pair = in.f64("last closest pair");
    watch_.last_close_pairs = in.u64("last particle pairs");
    watch_.balance_warned = in.boolean("balance warned");
    if (in.boolean("release")) {
      ReleaseCheck r;
      for (double* value : {&r.settling_drag, &r.column_height, &r.fluid_mass, &r.weight,
                            &r.carried, &r.kinetic_energy, &r.potential_energy})
        *value = in.f64("release");
      r.weight_fraction = optional_f64(in, "weight fraction");
      r.kinetic_over_potential = optional_f64(in, "kinetic over potential");
      r.at_rest = in.boolean("at rest");
      r.warning = in.text("release warning");
      release_ = r;
    }
    structure_ = std::make_unique<StructureSide>(scene_, scene::IntegrationMethod::FixedStep);
    structure_->restore_state(in);
    audit_.restore_state(in);
    predictor_.restore_state(in);
    health_.restore_state(in);
    const bool had_vtk = in.boolean("VTK series");

    resumed_state_ = true;
    prepare_output(sensors_length, energy_length);
    if (had_vtk != (vtk_ != nullptr)) {
      throw Error(std::string("the checkpoint was written ") + (had_vtk ? "with" : "without") +
                      " particle snapshots, the scene asks " + (had_vtk ? "for none" : "for them"),
                  source, "keep Output.snapshot_every_steps 0 or non-zero as the run had it");
    }
    if (vtk_) vtk_->restore_state(in);
    in.finish();
    remove_snapshots_after(step);
    steps_done_ = step;
    resumes_.push_back({utc_now(), step, checkpoint->folder.filename().string(), 0});
    last_checkpoint_step_ = step;  // the checkpoint to go back to if the fluid side is lost
    spdlog::info(
        "resuming from {} (step {}, t = {:.9g} s); sensors.csv and energy.csv cut back "
        "to it",
        checkpoint->folder.string(), step, time);
    write_run_manifest(options_.output_dir, scene_, record());

    std::vector<double> positions, velocities;
    structure_->boundary_state(positions, velocities);
    const FluidReady ready =
        fluid_.resume(scene_, positions, velocities, step, structure_->time(), fluid_bytes);
    if (const auto peer = fluid_.peer()) resumes_.back().client_ranks = peer->mpi_ranks;
    spdlog::info("client resumed: {} particles in LIGGGHTS, set-up {:.2f} s", ready.particle_count,
                 ready.seconds_setup);
    if (ready.particle_count != fluid.particles_final) {
      throw Error("the fluid holds " + std::to_string(ready.particle_count) +
                      " particles after the resume, " + std::to_string(fluid.particles_final) +
                      " at the checkpoint",
                  "resume from " + checkpoint->folder.string(),
                  "check that the scripts are those of the run that wrote the checkpoint");
    }
  }

  // Snapshots of steps after `step` belong to the run resumed from there and go.
  void remove_snapshots_after(std::uint64_t step) {
    const fs::path folder = fs::path(options_.output_dir) / "snapshots";
    std::error_code error;
    if (!fs::is_directory(folder, error)) return;
    for (const auto& file : fs::directory_iterator(folder, error)) {
      const std::string name = file.path().filename().string();
      unsigned long long file_step = 0;
      if (std::sscanf(name.c_str(), "particles_%llu.csv", &file_step) == 1 && file_step > step)
        fs::remove(file.path(), error);
    }
  }

  RunRecord record() const {
    RunRecord run;
    run.mode = RunMode::Coupled;
    run.command_line = options_.command_line;
    run.overrides = options_.overrides;
    run.started_utc = started_utc_;
    run.warnings = options_.warnings;
    // The release warning stays in run.json's "release" entry: "warnings" lists the scene's
    // physics checks, which tools compare from run to run.
    run.release = release_;
    run.status = status_;
    run.reason = reason_;
    run.steps = steps_done_;
    run.snapshots = snapshots_;
    run.seconds_total = timings_.total.seconds();
    run.seconds_setup_and_equilibration = timings_.setup.seconds();
    run.seconds_stepping = timings_.coupled.seconds();
    run.seconds_mbd = timings_.mbd.seconds();
    run.seconds_output = timings_.output.seconds();
    run.fluid = watch_.record;
    run.health =
        HealthSummary{health_.record(), health_.limits(), health_.allowed_lost_particles()};
    if (coupling_) {
      run.energy_audit = EnergyAuditSummary{audit_.totals(), audit_.warned_at(),
                                            audit_.stopped_at(), audit_.parts()};
    }
    run.fluid->peer = fluid_.peer();
    run.checkpoints = CheckpointRecord{scene_.output.checkpoint_every_steps,
                                       scene_.output.checkpoint_every_seconds, checkpoints_written_,
                                       last_checkpoint_step_, timings_.checkpoint.seconds()};
    run.resumes = resumes_;
    run.fluid->seconds_round_trip = timings_.round_trip.seconds();
    if (std::isfinite(watch_.closest_approach_over_r0))
      run.fluid->closest_approach_over_r0 = watch_.closest_approach_over_r0;
    // A run that failed before the set-up has no structure yet.
    if (structure_) {
      run.newton = structure_->statistics();
      run.position_constraint_drift = structure_->position_constraint_drift();
      run.velocity_constraint_drift = structure_->velocity_constraint_drift();
    }
    return run;
  }

  scene::Scene& scene_;
  ServerOptions options_;
  FluidSide& fluid_;
  std::unique_ptr<SensorFile> sensors_;
  std::unique_ptr<SensorFile> energy_;  // energy.csv: the energy audit at the sensor rows
  EnergyAudit audit_;
  ForcePredictor predictor_{scene_.solver.substeps};
  // The predictor's force (its buffer); empty when the force is not predicted.
  std::span<const double> predicted_;
  std::unique_ptr<VtkOutput> vtk_;
  std::unique_ptr<StructureSide> structure_;
  std::array<double, 3> total_fluid_force_{};
  std::size_t probe_columns_ = 0;  // columns of the scene's probes after the sensors'
  Timings timings_;
  std::optional<ReleaseCheck> release_;  // absent: the fluid side did not report it
  FluidWatch watch_;
  FluidHealthMonitor health_;
  bool coupling_ = false;  // the set-up is done, the coupled steps have begun
  std::uint64_t steps_done_ = 0;
  std::uint64_t snapshots_ = 0;
  std::string started_utc_;
  std::string status_ = "started";
  std::string reason_;
  std::shared_ptr<spdlog::logger> progress_logger_;
  std::chrono::steady_clock::time_point coupled_begin_, last_log_, last_live_, last_checkpoint_;
  std::uint64_t first_step_ = 0;  // the step the coupled phase began at (a resume's checkpoint)
  std::uint64_t step_at_last_log_ = 0;  // the step of the last progress log line
  std::optional<output::CheckpointStore> store_;
  bool checkpoints_ = false;    // the scene asks for them and the fluid side can write them
  bool resumed_state_ = false;  // a resume has taken the checkpoint's state
  std::optional<std::uint64_t> rollback_step_;  // the checkpoint the last rollback went to
  int rollbacks_to_step_ = 0;
  std::uint64_t checkpoints_written_ = 0;
  std::optional<std::uint64_t> last_checkpoint_step_;
  std::vector<ResumeRecord> resumes_;
};

}  // namespace

int run_session(scene::Scene& scene, const ServerOptions& options, FluidSide& fluid) {
  Session session(scene, options, fluid);
  return session.run();
}

int run_coupled_session(scene::Scene& scene, const ServerOptions& options) {
  TcpFluidSide fluid(options);
  return run_session(scene, options, fluid);
}

}  // namespace fsi::coupling
