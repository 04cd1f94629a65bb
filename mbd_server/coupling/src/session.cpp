#include "fsi/coupling/session.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "fsi/common/error.hpp"
#include "fsi/common/stopwatch.hpp"
#include "fsi/common/version.hpp"
#include "fsi/coupling/output.hpp"
#include "fsi/coupling/progress.hpp"
#include "fsi/coupling/vtk_output.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/protocol/channel.hpp"
#include "fsi/scene/physics_checks.hpp"

namespace fsi::coupling {
namespace {

namespace fs = std::filesystem;
namespace protocol = fsi::protocol;
using json = nlohmann::json;

std::atomic<int> g_stop_signal{0};
extern "C" void on_stop_signal(int signal) {
  g_stop_signal = signal;
}

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

std::string hex(std::uint64_t value) {
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

void write_port_file(const std::string& path, std::uint16_t port) {
  // Written to a temporary name and renamed, so a reader never sees a partial number.
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary);
    out << port << "\n";
    if (!out)
      throw Error("cannot write port file " + temporary, "--port-file", "choose a writable path");
  }
  fs::rename(temporary, path);
}

struct Timings {
  Stopwatch total, setup, coupled, mbd, output, round_trip;
  double client_liggghts = 0.0;
  double client_contact = 0.0;
  double client_communication = 0.0;
};

struct Checks {
  double max_action_reaction = 0.0;  // |F_fluid + F_structure| / sum |pair forces|
  double closest_approach_over_r0 = std::numeric_limits<double>::infinity();
  std::uint64_t particles_initial = 0;
  std::uint64_t particles_final = 0;
  bool lost_warned = false;
  bool balance_warned = false;
  // Fluid health from the particle snapshots (the only time the server sees every particle).
  std::uint64_t health_samples = 0;
  double last_snapshot_time = 0.0;
  double last_density_deviation = 0.0;  // max |rho/rho0 - 1| in the latest snapshot
  double last_max_speed = 0.0;          // max |v| in the latest snapshot [m/s]
  double max_density_deviation = 0.0;   // over all snapshots
  double max_speed = 0.0;
  double closest_since_report = std::numeric_limits<double>::infinity();
};

class Session {
 public:
  Session(scene::Scene& scene, const ServerOptions& options)
      : scene_(scene),
        options_(options),
        speed_of_sound_(scene::speed_of_sound(scene)),
        progress_logger_(spdlog::get("progress") ? spdlog::get("progress")
                                                 : spdlog::default_logger()) {}

  int run() {
    timings_.total.start();
    int status = 0;
    try {
      prepare_output();
      connect();
      set_up();
      couple();
      finish();
      status_ = "completed";
    } catch (const std::exception& failure) {
      status = 1;
      status_ = "failed";
      reason_ = failure.what();
      spdlog::error("{}", failure.what());
      // Tell the client unless it reported the fault itself (docs/protocol.md §7): before the
      // coupled steps a failure of ours is a set-up failure, during them (solver, signal) an
      // abort.
      const auto code = protocol::error_code_for(
          failure, coupling_ ? protocol::ErrorCode::PeerAborted : protocol::ErrorCode::SetupFailed);
      if (channel_ && code) {
        try {
          channel_->send(protocol::ErrorMessage{*code, failure.what()});
          channel_->close();
        } catch (...) {
        }
      }
    }
    timings_.total.stop();
    try {
      if (sensors_) sensors_->flush();
      write_manifest();
    } catch (const std::exception& failure) {
      spdlog::error("writing run.json failed: {}", failure.what());
      status = 1;
    }
    if (status == 0) {
      spdlog::info("run completed: {} steps in {:.1f} s; results in {}", steps_done_,
                   timings_.total.seconds(), options_.output_dir);
    } else {
      spdlog::error("run failed after {} coupled steps; partial results in {}", steps_done_,
                    options_.output_dir);
    }
    return status;
  }

 private:
  void prepare_output() {
    std::error_code error;
    fs::create_directories(options_.output_dir, error);
    if (error) {
      throw Error("cannot create output folder " + options_.output_dir + ": " + error.message(),
                  "--output", "choose a writable folder");
    }
    std::vector<std::string> names, units;
    for (const auto& sensor : scene_.sensors) {
      names.push_back(sensor.name);
      units.push_back(sensor.unit);
    }
    sensors_ =
        std::make_unique<SensorFile>((fs::path(options_.output_dir) / "sensors.csv").string(),
                                     "fsi-server sensors of " + scene_.file, names, units);
    if (scene_.output.snapshot_every_steps > 0) {
      fs::create_directories(fs::path(options_.output_dir) / "snapshots");
      vtk_ = std::make_unique<VtkOutput>(fs::path(options_.output_dir) / "vtk");
    }
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
  }

  void connect() {
    protocol::Listener listener(options_.listen_address, options_.port);
    spdlog::info("listening on {}:{} for fsi-client (mpirun -np N fsi-client --server {}:{})",
                 options_.listen_address, listener.port(), options_.listen_address,
                 listener.port());
    if (!options_.port_file.empty()) write_port_file(options_.port_file, listener.port());
    channel_ = std::make_unique<protocol::Channel>(listener.accept(options_.accept_timeout));
    protocol::ServerHandshake handshake;
    handshake.token = options_.token;
    handshake.software_version = std::string(fsi::software_version());
    handshake.run_name = fs::path(options_.output_dir).filename().string();
    handshake.timeout = options_.handshake_timeout;
    const protocol::ServerHandshakeResult opened = protocol::accept_client(*channel_, handshake);
    const protocol::Hello& hello = opened.hello;
    client_ = hello;
    capabilities_ = opened.capabilities;
    heartbeat_ = std::make_unique<protocol::HeartbeatSender>(
        *channel_, (capabilities_ & protocol::kCapabilityHeartbeat) != 0);
    spdlog::info("fsi-client {} connected from {} ({}, {} MPI rank(s)){}", hello.software_version,
                 channel_->peer_description(), hello.host, hello.mpi_ranks,
                 (capabilities_ & protocol::kCapabilityAuthentication) != 0
                     ? "; authenticated with the token of " + options_.token->file()
                     : std::string());
  }

  void send_boundary_setup() {
    const auto& boundary = scene_.boundary;
    protocol::Mesh mesh;
    mesh.dimension = static_cast<std::uint32_t>(boundary.dimension);
    mesh.dynamic_vertex_count = static_cast<std::uint32_t>(boundary.dynamic_vertex_count);
    mesh.refinement_option = static_cast<std::uint32_t>(boundary.refinement_option);
    mesh.refinement_resolution = boundary.refinement_resolution;
    // Every vertex; the static ones are sent only here, the dynamic ones with every Step.
    scene::boundary_state(boundary, scene_.model, state_, mesh.positions, mesh.velocities);
    mesh.element_vertices = boundary.elements();
    channel_->send(mesh);
  }

  void set_up() {
    timings_.setup.start();
    state_ = scene_.model.initial_state();
    integrator_ = std::make_unique<mbd::RadauIIA>(scene_.solver.integrator_options());

    protocol::Setup setup;
    setup.dimension = static_cast<std::uint32_t>(scene_.dimension);
    setup.time_step = scene_.solver.step_size;
    setup.equilibration_steps = scene_.liggghts.equilibration_steps;
    for (const auto& [name, value] : scene_.liggghts.variables)
      setup.liggghts_variables.push_back({name, value});
    setup.script1_name = scene_.liggghts.script1_name;
    setup.script1_text = scene_.liggghts.script1_text;
    setup.script2_name = scene_.liggghts.script2_name;
    setup.script2_text = scene_.liggghts.script2_text;
    channel_->send(setup);
    send_boundary_setup();
    protocol::Particles particles;
    particles.dimension = static_cast<std::uint32_t>(scene_.fluid.dimension);
    particles.atom_type = static_cast<std::uint32_t>(scene_.fluid.atom_type);
    particles.mass = scene_.fluid.mass;
    particles.density = scene_.fluid.density;
    particles.positions = scene_.fluid.positions;
    particles.velocities = scene_.fluid.velocities;
    channel_->send(particles);
    const bool spatial = scene_.dimension == 3;
    spdlog::info(
        "sent set-up ({}D): {} particles (m = {:.6g} {}), {} boundary vertices ({} dynamic), {} "
        "{}; client runs script 1, {} equilibration steps, script 2",
        scene_.dimension, scene_.fluid.count(), scene_.fluid.mass, spatial ? "kg" : "kg/m",
        scene_.boundary.vertex_count, scene_.boundary.dynamic_vertex_count,
        scene_.boundary.element_count(), spatial ? "triangles" : "segments",
        scene_.liggghts.equilibration_steps);
    // Set-up and equilibration may take long: a client that sends heartbeats (1.1) is waited for
    // as long as it computes; one of protocol 1.0 (no heartbeats) as long as it takes.
    const bool client_heartbeats = (capabilities_ & protocol::kCapabilityHeartbeat) != 0;
    ready_ = channel_->expect<protocol::Ready>(
        client_heartbeats ? std::optional(options_.peer_timeout) : std::nullopt);
    checks_.particles_initial = ready_.particle_count;
    spdlog::info("client ready: {} particles in LIGGGHTS; set-up {:.2f} s, equilibration {:.2f} s",
                 ready_.particle_count, ready_.seconds_setup, ready_.seconds_equilibration);
    if (ready_.particle_count == 0) {
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
    if (ready_.particle_count != scene_.fluid.count()) {
      spdlog::warn(
          "LIGGGHTS holds {} particles, the scene generated {} (the scripts create or delete "
          "particles)",
          ready_.particle_count, scene_.fluid.count());
    }
    apply_forces(channel_->expect<protocol::Forces>(options_.peer_timeout), 0);
    timings_.setup.stop();
  }

  // The fluid forces on the dynamic vertices become point loads held over the next step.
  void apply_forces(const protocol::Forces& forces, std::uint64_t expected_step) {
    if (forces.step != expected_step) {
      throw Error("Forces of step " + std::to_string(forces.step) + " arrived, step " +
                      std::to_string(expected_step) + " was expected",
                  "coupled step", "use matching fsi-server and fsi-client releases");
    }
    const auto dimension = static_cast<std::size_t>(scene_.dimension);
    const std::size_t dynamic_values = dimension * scene_.boundary.dynamic_vertex_count;
    if (forces.forces.size() != dynamic_values) {
      throw Error("Forces carry " + std::to_string(forces.forces.size() / dimension) +
                      " vertices, the mesh has " +
                      std::to_string(scene_.boundary.dynamic_vertex_count) + " dynamic ones",
                  "step " + std::to_string(expected_step),
                  "use matching fsi-server and fsi-client releases");
    }
    for (double f : forces.forces) {
      if (!std::isfinite(f)) {
        throw Error("the fluid forces of step " + std::to_string(expected_step) + " are not finite",
                    "fluid side",
                    "reduce the time step or the contact stiffness k (see the thesis' §6.2 rules)");
      }
    }
    // Held for the sensors of the step these forces act in (like the point loads).
    applied_total_force_ = {forces.diagnostics.force_on_structure[0],
                            forces.diagnostics.force_on_structure[1],
                            forces.diagnostics.force_on_structure[2]};
    // One load per marker: in 2D every vertex is a marker (the ground ones carry none), in 3D
    // only the dynamic vertices are.
    loads_.assign(dimension * static_cast<std::size_t>(scene_.model.marker_count()), 0.0);
    std::copy(forces.forces.begin(), forces.forces.end(), loads_.begin());
    scene_.model.set_point_loads(loads_);

    const auto& d = forces.diagnostics;
    timings_.client_liggghts += d.seconds_liggghts;
    timings_.client_contact += d.seconds_contact;
    timings_.client_communication += d.seconds_client_communication;
    if (d.pair_force_magnitude_sum > 0.0) {
      double imbalance = 0.0;
      for (int k = 0; k < 3; ++k)
        imbalance = std::max(imbalance, std::abs(d.force_on_fluid[k] + d.force_on_structure[k]));
      const double ratio = imbalance / d.pair_force_magnitude_sum;
      checks_.max_action_reaction = std::max(checks_.max_action_reaction, ratio);
      if (ratio > 1e-12 && !checks_.balance_warned) {
        spdlog::warn(
            "step {}: forces on fluid and structure differ by {:.3e} of the pair force sum (> "
            "1e-12)",
            expected_step, ratio);
        checks_.balance_warned = true;
      }
    }
    checks_.closest_approach_over_r0 =
        std::min(checks_.closest_approach_over_r0, d.closest_approach_over_r0);
    checks_.closest_since_report =
        std::min(checks_.closest_since_report, d.closest_approach_over_r0);
    checks_.particles_final = d.particle_count;
    if (d.particle_count == 0) {
      throw Error("every particle has left LIGGGHTS (" + std::to_string(checks_.particles_initial) +
                      " at the start)",
                  "step " + std::to_string(expected_step),
                  "the fluid left the LIGGGHTS box: check the box in script 1, the time step "
                  "(fsi-server --check lists the physics warnings) and the wall forces");
    }
    if (d.particle_count < checks_.particles_initial && !checks_.lost_warned) {
      spdlog::warn("step {}: {} particle(s) lost (left the LIGGGHTS box)", expected_step,
                   checks_.particles_initial - d.particle_count);
      checks_.lost_warned = true;
    }
  }

  std::vector<double> sensor_values() const {
    std::vector<double> values;
    const mbd::Model& model = scene_.model;
    for (const auto& sensor : scene_.sensors) {
      values.push_back(sensor.type == scene::SensorType::TotalFluidForce
                           ? applied_total_force_[static_cast<std::size_t>(sensor.axis)]
                           : scene::structure_sensor_value(model, sensor, state_));
    }
    return values;
  }

  void couple() {
    coupling_ = true;
    timings_.coupled.start();
    const double dt = scene_.solver.step_size;
    const auto steps = static_cast<std::uint64_t>(std::llround(scene_.solver.end_time / dt));
    const std::size_t dynamic_values =
        static_cast<std::size_t>(scene_.dimension) * scene_.boundary.dynamic_vertex_count;
    // A model without bodies (a static 3D container) has nothing to integrate.
    const bool structure = scene_.model.coordinate_count() > 0;
    std::vector<double> positions, velocities;
    spdlog::info("coupled phase: {} steps of {:.3g} s to t = {:.6g} s", steps, dt, steps * dt);
    coupled_begin_ = std::chrono::steady_clock::now();
    last_log_ = last_live_ = coupled_begin_;
    for (std::uint64_t n = 1; n <= steps; ++n) {
      if (g_stop_signal != 0) {
        throw Error("stopped by signal " + std::to_string(g_stop_signal.load()) + " at step " +
                        std::to_string(n),
                    "fsi-server", "results up to this step are in the output folder");
      }
      // The client waits for the Step meanwhile: heartbeats tell it we are computing.
      auto computing = heartbeat_->busy();
      {
        ScopedTimer timer(timings_.mbd);
        if (structure) integrator_->step(scene_.model, state_, dt);
        state_.time = static_cast<double>(n) * dt;  // no drift of the clock over many steps
      }
      {
        ScopedTimer timer(timings_.output);
        // Sensors at t_n: multipliers of the step and the fluid forces that acted during it.
        if (n % static_cast<std::uint64_t>(scene_.output.sensor_every_steps) == 0)
          sensors_->write(state_.time, sensor_values());
      }
      scene::boundary_state(scene_.boundary, scene_.model, state_, positions, velocities);
      protocol::Step step;
      step.step = n;
      step.time = state_.time;
      step.time_step = dt;
      step.positions.assign(positions.begin(),
                            positions.begin() + static_cast<long>(dynamic_values));
      step.velocities.assign(velocities.begin(),
                             velocities.begin() + static_cast<long>(dynamic_values));
      computing = {};
      timings_.round_trip.start();
      channel_->send(step);
      const auto forces = channel_->expect<protocol::Forces>(options_.peer_timeout);
      timings_.round_trip.stop();
      apply_forces(forces, n);
      steps_done_ = n;

      if (scene_.output.snapshot_every_steps > 0 &&
          n % static_cast<std::uint64_t>(scene_.output.snapshot_every_steps) == 0) {
        take_snapshot(n);
      }
      report_progress(n, steps);
    }
    if (options_.live_status) options_.live_status("");
    timings_.coupled.stop();
  }

  void report_progress(std::uint64_t n, std::uint64_t steps) {
    const auto now = std::chrono::steady_clock::now();
    const bool log_due = now - last_log_ >= options_.progress_interval || n == steps;
    const bool live_due =
        options_.live_status && (now - last_live_ >= std::chrono::milliseconds(250) || n == steps);
    if (!log_due && !live_due) return;
    ProgressSample sample;
    sample.time = state_.time;
    sample.end_time = static_cast<double>(steps) * scene_.solver.step_size;
    sample.step = n;
    sample.steps = steps;
    sample.steps_per_second =
        static_cast<double>(n) /
        std::max(1e-9, std::chrono::duration<double>(now - coupled_begin_).count());
    sample.closest_approach_over_r0 = checks_.closest_since_report;
    if (checks_.health_samples > 0) {
      sample.snapshot_time = checks_.last_snapshot_time;
      sample.density_deviation = checks_.last_density_deviation;
      sample.max_speed = checks_.last_max_speed;
    }
    sample.speed_of_sound = speed_of_sound_;
    const std::string line = format_progress(sample);
    if (live_due) {
      options_.live_status(line);
      last_live_ = now;
    }
    if (log_due) {
      progress_logger_->info("{}", line);
      last_log_ = now;
      // The closest approach of a log line covers the whole interval since the previous one.
      checks_.closest_since_report = std::numeric_limits<double>::infinity();
    }
  }

  void take_snapshot(std::uint64_t n) {
    ScopedTimer timer(timings_.output);
    channel_->send(protocol::SnapshotRequest{n});
    auto reply = channel_->expect<protocol::Snapshot>(options_.peer_timeout);
    auto writing = heartbeat_->busy();
    ParticleSnapshot snapshot;
    snapshot.step = reply.step;
    snapshot.time = reply.time;
    snapshot.dimension = static_cast<int>(reply.dimension);
    snapshot.ids = std::move(reply.ids);
    snapshot.positions = std::move(reply.positions);
    snapshot.velocities = std::move(reply.velocities);
    snapshot.density = std::move(reply.density);
    snapshot.pressure = std::move(reply.pressure);
    char name[64];
    std::snprintf(name, sizeof name, "particles_%09llu.csv", static_cast<unsigned long long>(n));
    record_health(snapshot);
    write_snapshot_csv((fs::path(options_.output_dir) / "snapshots" / name).string(), snapshot);
    vtk_->write(snapshot, scene_.model, state_, scene_.boundary, loads_);
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
    ++checks_.health_samples;
    checks_.last_snapshot_time = snapshot.time;
    checks_.last_density_deviation = deviation;
    checks_.last_max_speed = std::sqrt(speed2);
    checks_.max_density_deviation = std::max(checks_.max_density_deviation, deviation);
    checks_.max_speed = std::max(checks_.max_speed, checks_.last_max_speed);
  }

  void finish() {
    channel_->send(protocol::Shutdown{"end time reached"});
    const auto goodbye = channel_->expect<protocol::Goodbye>(std::chrono::seconds(60));
    spdlog::info("client finished: {} steps, {:.1f} s", goodbye.steps_done, goodbye.seconds_total);
    channel_->close();
  }

  void write_manifest() {
    json manifest;
    manifest["format"] = "fsi-run-manifest";
    manifest["format_version"] = 1;
    manifest["program"] = {{"name", "fsi-server"},
                           {"version", std::string(fsi::software_version())},
                           {"git_revision", std::string(fsi::git_revision())},
                           {"command_line", options_.command_line}};
    manifest["protocol"] = {
        {"major", protocol::kMajorVersion},
        {"minor", protocol::kMinorVersion},
        {"capabilities", capabilities_},
        {"authenticated", (capabilities_ & protocol::kCapabilityAuthentication) != 0}};
    if (client_) {
      manifest["client"] = {{"software_version", client_->software_version},
                            {"host", client_->host},
                            {"mpi_ranks", client_->mpi_ranks},
                            {"liggghts_version", ready_.liggghts_version}};
    }
    std::ifstream scene_file(scene_.file);
    std::stringstream scene_text;
    scene_text << scene_file.rdbuf();
    manifest["scene"] = {{"file", fs::absolute(scene_.file).string()},
                         {"fnv1a64", hex(fnv1a(scene_text.str()))}};
    manifest["parameters"] = scene::to_json(scene_.parameters);
    manifest["parameters_flat"] = scene::flatten_numbers(scene_.parameters);
    json bodies = json::array();
    const mbd::Model& model = scene_.model;
    for (int b = 0; b < model.body_count(); ++b) {
      json body = {
          {"name", model.body_name(b)}, {"type", model.body_kind(b)}, {"mass", model.body_mass(b)}};
      if (model.body_kind(b) == "rigid_body_2d") body["inertia"] = model.body(b).inertia;
      if (model.is_beam(b)) body["elements"] = model.beam(b).element_count;
      if (model.body_kind(b) == "ancf_cable") body["elements"] = model.cable(b).element_count;
      bodies.push_back(body);
    }
    const bool spatial = scene_.dimension == 3;
    const json gravity = spatial ? json{scene_.gravity[0], scene_.gravity[1], scene_.gravity[2]}
                                 : json{scene_.model.gravity().x(), scene_.model.gravity().y()};
    manifest["dimension"] = scene_.dimension;
    manifest["model"] = {{"gravity", gravity},
                         {"bodies", bodies},
                         {"constraints", scene_.model.constraint_count()},
                         {"integrator", scene_.solver.integrator_description()}};
    manifest["fluid"] = {
        {"particle_count", ready_.particle_count ? ready_.particle_count : scene_.fluid.count()},
        {"generated_particles", scene_.fluid.count()},
        {"particle_mass", scene_.fluid.mass},
        {"density", scene_.fluid.density},
        {"spacing", scene_.fluid.spacing}};
    manifest["mesh"] = {{"vertices", scene_.boundary.vertex_count},
                        {"dynamic_vertices", scene_.boundary.dynamic_vertex_count},
                        {spatial ? "triangles" : "segments", scene_.boundary.element_count()},
                        {"refinement_resolution", scene_.boundary.refinement_resolution}};
    manifest["time_step"] = scene_.solver.step_size;
    manifest["end_time"] = scene_.solver.end_time;
    manifest["steps"] = steps_done_;
    manifest["snapshots"] = snapshots_;
    const double round_trip = timings_.round_trip.seconds();
    const double communication =
        std::max(0.0, round_trip - timings_.client_liggghts - timings_.client_contact);
    manifest["timings_seconds"] = {{"total", timings_.total.seconds()},
                                   {"setup_and_equilibration", timings_.setup.seconds()},
                                   {"client_setup", ready_.seconds_setup},
                                   {"client_equilibration", ready_.seconds_equilibration},
                                   {"coupled_phase", timings_.coupled.seconds()},
                                   {"mbd", timings_.mbd.seconds()},
                                   {"liggghts", timings_.client_liggghts},
                                   {"contact_fix", timings_.client_contact},
                                   {"communication", communication},
                                   {"client_mpi_communication", timings_.client_communication},
                                   {"output", timings_.output.seconds()}};
    const mbd::IntegratorStatistics stats =
        integrator_ ? integrator_->statistics() : mbd::IntegratorStatistics{};
    // A run that failed before the set-up has no state yet.
    const bool have_state = state_.q.size() == scene_.model.coordinate_count();
    auto drift = [&](double (*measure)(const mbd::ConstrainedSystem&, const mbd::State&)) {
      return have_state ? json(measure(scene_.model, state_)) : json(nullptr);
    };
    manifest["newton"] = {{"steps", stats.steps},
                          {"iterations", stats.newton_iterations},
                          {"jacobian_evaluations", stats.jacobian_evaluations},
                          {"factorisations", stats.factorisations}};
    manifest["checks"] = {
        {"max_action_reaction_relative", checks_.max_action_reaction},
        {"closest_approach_over_r0", std::isfinite(checks_.closest_approach_over_r0)
                                         ? json(checks_.closest_approach_over_r0)
                                         : json(nullptr)},
        {"particles_initial", checks_.particles_initial},
        {"particles_final", checks_.particles_final},
        {"snapshots_checked", checks_.health_samples},
        {"max_density_deviation_at_snapshots",
         checks_.health_samples > 0 ? json(checks_.max_density_deviation) : json(nullptr)},
        {"max_particle_speed_at_snapshots",
         checks_.health_samples > 0 ? json(checks_.max_speed) : json(nullptr)},
        {"speed_of_sound", speed_of_sound_ ? json(*speed_of_sound_) : json(nullptr)},
        {"max_particle_speed_over_speed_of_sound_at_snapshots",
         checks_.health_samples > 0 && speed_of_sound_ ? json(checks_.max_speed / *speed_of_sound_)
                                                       : json(nullptr)},
        {"position_constraint_drift", drift(&mbd::position_constraint_drift)},
        {"velocity_constraint_drift", drift(&mbd::velocity_constraint_drift)}};
    manifest["warnings"] = options_.warnings;
    manifest["status"] = status_;
    if (!reason_.empty()) manifest["reason"] = reason_;
    const fs::path path = fs::path(options_.output_dir) / "run.json";
    std::ofstream out(path);
    out << manifest.dump(2) << "\n";
    if (!out) throw Error("cannot write " + path.string(), "output folder", "free disk space");
  }

  scene::Scene& scene_;
  ServerOptions options_;
  std::unique_ptr<SensorFile> sensors_;
  std::unique_ptr<VtkOutput> vtk_;
  std::unique_ptr<protocol::Channel> channel_;
  std::optional<protocol::Hello> client_;
  std::uint32_t capabilities_ = 0;  // agreed in the handshake
  std::unique_ptr<protocol::HeartbeatSender> heartbeat_;
  protocol::Ready ready_;
  std::unique_ptr<mbd::RadauIIA> integrator_;
  mbd::State state_;
  std::vector<double> loads_;
  std::array<double, 3> applied_total_force_{};
  Timings timings_;
  Checks checks_;
  bool coupling_ = false;  // the set-up is done, the coupled steps have begun
  std::uint64_t steps_done_ = 0;
  std::uint64_t snapshots_ = 0;
  std::string status_ = "started";
  std::string reason_;
  std::optional<double> speed_of_sound_;
  std::shared_ptr<spdlog::logger> progress_logger_;
  std::chrono::steady_clock::time_point coupled_begin_, last_log_, last_live_;
};

}  // namespace

int run_coupled_session(scene::Scene& scene, const ServerOptions& options) {
  Session session(scene, options);
  return session.run();
}

}  // namespace fsi::coupling
