#include "fsi/coupling/mbd_only.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>

#include "fsi/common/stopwatch.hpp"
#include "fsi/coupling/output.hpp"
#include "fsi/coupling/run_manifest.hpp"
#include "fsi/coupling/structure_side.hpp"
#include "fsi/coupling/vtk_output.hpp"

namespace fsi::coupling {
namespace {

namespace fs = std::filesystem;

// Without a fluid, no boundary feels a force.
constexpr std::array<double, 3> kNoFluidForce{};

}  // namespace

int run_mbd_only(scene::Scene& scene, const MbdOnlyOptions& options) {
  Stopwatch total, stepping, mbd, output;
  total.start();
  RunRecord run;
  run.mode = RunMode::MbdOnly;
  run.command_line = options.command_line;
  run.started_utc = utc_now();
  run.warnings = options.warnings;
  run.overrides = options.overrides;
  const double dt = scene.solver.step_size;
  const std::uint64_t steps = scene.solver.step_count();
  std::unique_ptr<SensorFile> sensors;
  std::unique_ptr<StructureSide> structure;
  try {
    create_run_folder(options.output_dir);
    write_run_manifest(options.output_dir, scene, run);  // "started": the folder names its run
    sensors = std::make_unique<SensorFile>(fs::path(options.output_dir) / "sensors.csv",
                                           "fsi-server --mbd-only sensors of " + scene.file,
                                           scene.sensors);
    structure = std::make_unique<StructureSide>(scene, scene.solver.method, false);
    sensors->write(0.0, structure->initial_sensor_readout(kNoFluidForce));
    // Output.snapshot_every_steps: the structure's shape in ParaView (vtk/: boundary, bodies,
    // beams; planar scenes), as a coupled run writes it with its particle snapshots.
    const auto every = static_cast<std::uint64_t>(std::max(0L, scene.output.snapshot_every_steps));
    std::unique_ptr<VtkOutput> vtk;
    if (every > 0 && scene.dimension == 2) {
      vtk = std::make_unique<VtkOutput>(fs::path(options.output_dir) / "vtk");
      vtk->write_structure(0, scene.model, structure->state(), scene.boundary);
    } else if (every > 0) {
      spdlog::warn(
          "Output.snapshot_every_steps = {}: an --mbd-only run of a 3D scene writes no VTK files "
          "(sensors.csv only); a coupled run writes the structure with its particle snapshots",
          every);
    }
    spdlog::info("multibody alone: {} steps of {:.3g} s to t = {:.6g} s ({})", steps, dt,
                 static_cast<double>(steps) * dt, scene.solver.integrator_description());
    ScopedTimer stepping_timer(stepping);
    for (std::uint64_t n = 1; n <= steps; ++n) {
      {
        ScopedTimer timer(mbd);
        structure->advance(n, dt);
      }
      ScopedTimer timer(output);
      if (n % static_cast<std::uint64_t>(scene.output.sensor_every_steps) == 0)
        sensors->write(structure->time(), structure->sensor_readout(kNoFluidForce));
      if (vtk && n % every == 0)
        vtk->write_structure(n, scene.model, structure->state(), scene.boundary);
      run.steps = n;
    }
    run.status = "completed";
  } catch (const std::exception& failure) {
    run.status = "failed";
    run.reason = failure.what();
    spdlog::error("{}", failure.what());
  }
  total.stop();
  int exit_status = run.status == "completed" ? 0 : 1;
  try {
    if (sensors) sensors->flush();
    run.seconds_total = total.seconds();
    run.seconds_stepping = stepping.seconds();
    run.seconds_mbd = mbd.seconds();
    run.seconds_output = output.seconds();
    if (structure) {
      // A failed run records the Newton work it did, up to the failing step.
      run.newton = structure->statistics();
      run.position_constraint_drift = structure->position_constraint_drift();
      run.velocity_constraint_drift = structure->velocity_constraint_drift();
      const std::string drift =
          constraint_drift_warning(run.position_constraint_drift, scene.solver.constraint_form);
      if (!drift.empty()) spdlog::warn("{}", drift);
    }
    write_run_manifest(options.output_dir, scene, run);
  } catch (const std::exception& failure) {
    spdlog::error("writing run.json failed: {}", failure.what());
    exit_status = 1;
  }
  if (exit_status == 0) {
    // The output steps, and what the integrator took to land on them (an error-controlled
    // method's own steps can be many more: a user compares the methods by these).
    const std::uint64_t split = run.newton.substepped_steps;
    spdlog::info(
        "multibody run completed: {} steps of {:g} s in {:.2f} s ({} integrator steps, {} "
        "factorisations{}); results in {}",
        run.steps, dt, total.seconds(), run.newton.steps, run.newton.factorisations,
        split == 0 ? std::string()
                   : fmt::format("; {} of the steps in substeps, their Newton iteration having "
                                 "failed on the whole step: a smaller step_size may cost no more",
                                 split),
        options.output_dir);
  }
  return exit_status;
}

}  // namespace fsi::coupling
