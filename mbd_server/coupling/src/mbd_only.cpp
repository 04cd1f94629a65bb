#include "fsi/coupling/mbd_only.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "fsi/common/error.hpp"
#include "fsi/common/stopwatch.hpp"
#include "fsi/common/version.hpp"
#include "fsi/coupling/output.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/readouts.hpp"

namespace fsi::coupling {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The scene's sensors without a fluid: fluid forces are zero (no point loads are set).
std::vector<double> sensor_values(const scene::Scene& scene, const mbd::State& state) {
  std::vector<double> values;
  for (const auto& sensor : scene.sensors) {
    values.push_back(sensor.type == scene::SensorType::TotalFluidForce
                         ? 0.0
                         : scene::structure_sensor_value(scene.model, sensor, state));
  }
  return values;
}

// The first non-finite entry of the state, named by body where possible.
std::string non_finite_entry(const mbd::Model& model, const mbd::State& state) {
  for (int b = 0; b < model.body_count(); ++b) {
    try {
      for (const mbd::Coordinate c :
           {mbd::Coordinate::X, mbd::Coordinate::Y, mbd::Coordinate::Angle}) {
        const int i = model.coordinate_index(b, c);
        if (!std::isfinite(state.q(i)) || !std::isfinite(state.v(i))) {
          return "body '" + model.body(b).name + "' coordinate " + std::string(mbd::name(c));
        }
      }
    } catch (const Error&) {
      // not a planar rigid body: named by index below
    }
  }
  for (int i = 0; i < state.q.size(); ++i) {
    if (!std::isfinite(state.q(i)) || !std::isfinite(state.v(i))) {
      return model.coordinate_description(i);
    }
  }
  for (int k = 0; k < model.constraint_count(); ++k) {
    if (!std::isfinite(state.lambda(k))) return "multiplier of " + model.constraint_description(k);
  }
  return "the state";
}

}  // namespace

int run_mbd_only(scene::Scene& scene, const MbdOnlyOptions& options) {
  Stopwatch total;
  total.start();
  std::string status = "started", reason;
  std::uint64_t steps_done = 0;
  mbd::IntegratorStatistics stats;
  mbd::State state;
  const double dt = scene.solver.step_size;
  const auto steps = static_cast<std::uint64_t>(std::llround(scene.solver.end_time / dt));
  std::unique_ptr<SensorFile> sensors;
  try {
    std::error_code error;
    fs::create_directories(options.output_dir, error);
    if (error) {
      throw Error("cannot create output folder " + options.output_dir + ": " + error.message(),
                  "--output", "choose a writable folder");
    }
    std::vector<std::string> names, units;
    for (const auto& sensor : scene.sensors) {
      names.push_back(sensor.name);
      units.push_back(sensor.unit);
    }
    sensors = std::make_unique<SensorFile>((fs::path(options.output_dir) / "sensors.csv").string(),
                                           "fsi-server --mbd-only sensors of " + scene.file, names,
                                           units);
    state = scene.model.initial_state();
    mbd::RadauIIA integrator(scene.solver.integrator_options());
    spdlog::info("multibody alone: {} steps of {:.3g} s to t = {:.6g} s ({})", steps, dt,
                 static_cast<double>(steps) * dt, scene.solver.integrator_description());
    for (std::uint64_t n = 1; n <= steps; ++n) {
      try {
        integrator.step(scene.model, state, dt);
      } catch (const Error& failure) {
        char where[96];
        std::snprintf(where, sizeof where, "step %llu (t = %.9g s)",
                      static_cast<unsigned long long>(n), static_cast<double>(n - 1) * dt);
        throw Error(failure.fault(), std::string(where) + ", " + failure.location(),
                    failure.remedy());
      }
      state.time = static_cast<double>(n) * dt;
      if (!state.q.allFinite() || !state.v.allFinite() || !state.lambda.allFinite()) {
        char where[96];
        std::snprintf(where, sizeof where, "step %llu (t = %.9g s)",
                      static_cast<unsigned long long>(n), state.time);
        throw Error("the multibody state is not finite: " + non_finite_entry(scene.model, state),
                    where, "check the scene's forces and constraints for that element");
      }
      if (n % static_cast<std::uint64_t>(scene.output.sensor_every_steps) == 0)
        sensors->write(state.time, sensor_values(scene, state));
      steps_done = n;
    }
    stats = integrator.statistics();
    status = "completed";
  } catch (const std::exception& failure) {
    status = "failed";
    reason = failure.what();
    spdlog::error("{}", failure.what());
  }
  total.stop();
  int exit_status = status == "completed" ? 0 : 1;
  try {
    if (sensors) sensors->flush();
    json manifest;
    manifest["format"] = "fsi-run-manifest";
    manifest["format_version"] = 1;
    manifest["mode"] = "mbd-only";
    manifest["program"] = {{"name", "fsi-server"},
                           {"version", std::string(fsi::software_version())},
                           {"git_revision", std::string(fsi::git_revision())},
                           {"command_line", options.command_line}};
    manifest["scene"] = {{"file", fs::absolute(scene.file).string()}};
    manifest["parameters"] = scene::to_json(scene.parameters);
    manifest["model"] = {{"gravity", {scene.model.gravity().x(), scene.model.gravity().y()}},
                         {"bodies", scene.model.body_count()},
                         {"constraints", scene.model.constraint_count()},
                         {"integrator", scene.solver.integrator_description()}};
    manifest["time_step"] = dt;
    manifest["end_time"] = scene.solver.end_time;
    manifest["steps"] = steps_done;
    manifest["timings_seconds"] = {{"total", total.seconds()}};
    manifest["newton"] = {{"steps", stats.steps},
                          {"iterations", stats.newton_iterations},
                          {"jacobian_evaluations", stats.jacobian_evaluations},
                          {"factorisations", stats.factorisations}};
    const bool have_state = state.q.size() == scene.model.coordinate_count() &&
                            state.q.allFinite() && state.v.allFinite();
    manifest["checks"] = {
        {"position_constraint_drift",
         have_state ? json(position_constraint_drift(scene.model, state)) : json(nullptr)},
        {"velocity_constraint_drift",
         have_state ? json(velocity_constraint_drift(scene.model, state)) : json(nullptr)}};
    manifest["warnings"] = options.warnings;
    manifest["status"] = status;
    if (!reason.empty()) manifest["reason"] = reason;
    const fs::path path = fs::path(options.output_dir) / "run.json";
    std::ofstream out(path);
    out << manifest.dump(2) << "\n";
    if (!out) throw Error("cannot write " + path.string(), "output folder", "free disk space");
  } catch (const std::exception& failure) {
    spdlog::error("writing run.json failed: {}", failure.what());
    exit_status = 1;
  }
  if (exit_status == 0) {
    spdlog::info("multibody run completed: {} steps in {:.2f} s; results in {}", steps_done,
                 total.seconds(), options.output_dir);
  }
  return exit_status;
}

}  // namespace fsi::coupling
