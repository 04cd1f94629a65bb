#include "fsi/coupling/tcp_fluid_side.hpp"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <typeinfo>

#include "fsi/common/error.hpp"
#include "fsi/common/version.hpp"
#include "fsi/protocol/channel.hpp"

namespace fsi::coupling {
namespace {

namespace fs = std::filesystem;

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

class HeartbeatScope final : public FluidSide::WaitScope {
 public:
  explicit HeartbeatScope(protocol::HeartbeatSender& sender) : busy_(sender.busy()) {}

 private:
  protocol::HeartbeatSender::Busy busy_;
};

}  // namespace

TcpFluidSide::TcpFluidSide(const ServerOptions& options) : options_(options) {}

TcpFluidSide::~TcpFluidSide() = default;

void TcpFluidSide::connect() {
  // A second connection (a client started again after the first died) comes on the same port,
  // within the reconnect timeout.
  const bool again = bound_port_ != 0;
  heartbeat_.reset();
  channel_.reset();
  protocol::Listener listener(options_.listen_address, again ? bound_port_ : options_.port);
  bound_port_ = listener.port();
  spdlog::info("listening on {}:{} for fsi-client (mpirun -np N fsi-client --server {}:{})",
               options_.listen_address, listener.port(), options_.listen_address, listener.port());
  if (!options_.port_file.empty()) write_port_file(options_.port_file, listener.port());
  channel_ = std::make_unique<protocol::Channel>(
      listener.accept(again ? options_.reconnect_timeout : options_.accept_timeout));
  protocol::ServerHandshake handshake;
  handshake.token = options_.token;
  handshake.software_version = std::string(fsi::software_version());
  handshake.run_name = fs::path(options_.output_dir).filename().string();
  handshake.timeout = options_.handshake_timeout;
  handshake.session_capabilities = protocol::kCapabilitySettling |
                                   protocol::kCapabilityFluidHealth | protocol::kCapabilityProbes |
                                   protocol::kCapabilityMovingProbes |
                                   protocol::kCapabilityMultiRate | protocol::kCapabilityCheckpoint;
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

void TcpFluidSide::set_up(const scene::Scene& scene, const std::vector<double>& boundary_positions,
                          const std::vector<double>& boundary_velocities) {
  send_setup_and_mesh(scene, boundary_positions, boundary_velocities);
  send_particles(scene);
  if (settling_agreed()) {
    protocol::Settling settling;
    settling.gravity = scene.gravity;
    settling.column_height = scene.fluid.column_height;
    settling.drag_rate = scene.liggghts.settling_drag.value_or(protocol::kAutomaticDragRate);
    settling.initial_densities = scene.fluid.densities;
    channel_->send(settling);
  } else {
    spdlog::warn(
        "fsi-client speaks protocol {}: the fluid settles without the drag, starts at rho0 "
        "everywhere (no hydrostatic start) and is not checked at release (use an fsi-client of "
        "protocol 1.2 or later)",
        protocol::version_text(channel_->peer_major(), channel_->peer_minor()));
  }
  send_probes(scene);
}

FluidReady TcpFluidSide::resume(const scene::Scene& scene,
                                const std::vector<double>& boundary_positions,
                                const std::vector<double>& boundary_velocities, std::uint64_t step,
                                double time, std::string_view fluid_state) {
  connect();  // a new connection, also after a lost one
  if (!can_checkpoint()) {
    throw Error("fsi-client " + client_->software_version + " (protocol " +
                    protocol::version_text(channel_->peer_major(), channel_->peer_minor()) +
                    ") cannot resume a run (capability 'checkpoint' of protocol 1.6)",
                "resume of " + scene.file + " with fsi-client at " + channel_->peer_description(),
                "use an fsi-client of protocol 1.6 or later (the release of this fsi-server)");
  }
  send_setup_and_mesh(scene, boundary_positions, boundary_velocities);
  // The scene's particles as in a new run (its scripts may need them), then their state.
  send_particles(scene);
  channel_->send(protocol::Resume{step, time, std::string(fluid_state)});
  send_probes(scene);
  const protocol::Ready ready = expect_ready();
  FluidReady result;
  result.particle_count = ready.particle_count;
  result.liggghts_version = ready.liggghts_version;
  result.seconds_setup = ready.seconds_setup;
  return result;
}

bool TcpFluidSide::peer_lost(const std::exception& failure) const {
  // The client's own report that its job was ended from outside (a rank killed), a connection
  // that closed, or a client that fell silent; not a fault of the session (a version, an
  // unexpected or malformed message) nor one the client would meet again.
  if (const auto* reported = dynamic_cast<const protocol::PeerReportedError*>(&failure))
    return reported->code() == protocol::ErrorCode::PeerAborted;
  if (dynamic_cast<const protocol::PeerTimeoutError*>(&failure)) return true;
  return typeid(failure) == typeid(protocol::ProtocolError);
}

std::string TcpFluidSide::checkpoint(std::uint64_t step) {
  channel_->send(protocol::CheckpointRequest{step});
  auto reply = channel_->expect<protocol::FluidState>(options_.peer_timeout);
  if (reply.step != step) {
    throw Error("the FluidState of step " + std::to_string(reply.step) + " arrived, step " +
                    std::to_string(step) + " was asked for",
                "checkpoint", "use matching fsi-server and fsi-client releases");
  }
  return std::move(reply.state);
}

void TcpFluidSide::send_particles(const scene::Scene& scene) {
  protocol::Particles particles;
  particles.dimension = static_cast<std::uint32_t>(scene.fluid.dimension);
  particles.atom_type = static_cast<std::uint32_t>(scene.fluid.atom_type);
  particles.mass = scene.fluid.mass;
  particles.density = scene.fluid.density;
  particles.positions = scene.fluid.positions;
  particles.velocities = scene.fluid.velocities;
  channel_->send(particles);
}

protocol::Ready TcpFluidSide::expect_ready() {
  // Set-up and equilibration may take long: a client that sends heartbeats (1.1) is waited for
  // as long as it computes; one of protocol 1.0 (no heartbeats) as long as it takes.
  const bool client_heartbeats = (capabilities_ & protocol::kCapabilityHeartbeat) != 0;
  return channel_->expect<protocol::Ready>(client_heartbeats ? std::optional(options_.peer_timeout)
                                                             : std::nullopt);
}

void TcpFluidSide::send_setup_and_mesh(const scene::Scene& scene,
                                       const std::vector<double>& boundary_positions,
                                       const std::vector<double>& boundary_velocities) {
  if (!channel_) connect();
  // Before any set-up data: an older client would otherwise run its whole set-up first.
  refuse_client_lacking(scene);
  protocol::Setup setup;
  setup.dimension = static_cast<std::uint32_t>(scene.dimension);
  setup.time_step = scene.solver.step_size;
  setup.equilibration_steps = scene.liggghts.equilibration_steps;
  for (const auto& [name, value] : scene.liggghts.variables)
    setup.liggghts_variables.push_back({name, value});
  setup.script1_name = scene.liggghts.script1_name;
  setup.script1_text = scene.liggghts.script1_text;
  setup.script2_name = scene.liggghts.script2_name;
  setup.script2_text = scene::script2_sent(scene);
  for (const scene::DampingZone& zone : scene.damping_zones) {
    spdlog::info(
        "damping zone {}: a drag of up to {:g} 1/s from the coupled run's first step "
        "(appended to script 2, fix fsi_damping_*)",
        zone.location.text(), zone.rate);
  }
  channel_->send(setup);

  const auto& boundary = scene.boundary;
  protocol::Mesh mesh;
  mesh.dimension = static_cast<std::uint32_t>(boundary.dimension);
  mesh.dynamic_vertex_count = static_cast<std::uint32_t>(boundary.dynamic_vertex_count);
  mesh.refinement_option = static_cast<std::uint32_t>(boundary.refinement_option);
  mesh.refinement_resolution = boundary.refinement_resolution;
  // Every vertex; the static ones travel only here, the dynamic ones with every Step.
  mesh.positions = boundary_positions;
  mesh.velocities = boundary_velocities;
  mesh.element_vertices = boundary.elements();
  channel_->send(mesh);
}

void TcpFluidSide::refuse_client_lacking(const scene::Scene& scene) const {
  if (scene.solver.substeps > 1 && (capabilities_ & protocol::kCapabilityMultiRate) == 0) {
    throw Error("the scene couples with SolverOptions.Timeint.substeps = " +
                    std::to_string(scene.solver.substeps) + ", and fsi-client " +
                    client_->software_version + " (protocol " +
                    protocol::version_text(channel_->peer_major(), channel_->peer_minor()) +
                    ") lacks multi-rate coupling (capability 'multi-rate' of protocol 1.5)",
                "set-up of " + scene.file + " with fsi-client at " + channel_->peer_description(),
                "use an fsi-client of protocol 1.5 or later, or couple with substeps = 1");
  }
  if (probes_agreed() && !scene.attached_probes.empty() &&
      (capabilities_ & protocol::kCapabilityMovingProbes) == 0) {
    throw Error("the scene's probe '" + scene.probes[scene.attached_probes.front().probe].name +
                    "' moves with a body, and fsi-client " + client_->software_version +
                    " (protocol " +
                    protocol::version_text(channel_->peer_major(), channel_->peer_minor()) +
                    ") lacks probes that move (capability 'moving probes' of protocol 1.4)",
                "set-up of " + scene.file + " with fsi-client at " + channel_->peer_description(),
                "use an fsi-client of protocol 1.4 or later, or fix the probe in space (leave "
                "out its `body`)");
  }
  if (probes_agreed() || scene.probes.empty()) return;
  throw Error("the scene declares " + std::to_string(scene.probes.size()) +
                  " probe(s) (the first: '" + scene.probes.front().name + "'), and fsi-client " +
                  client_->software_version + " (protocol " +
                  protocol::version_text(channel_->peer_major(), channel_->peer_minor()) +
                  ") lacks probes (capability 'probes' of protocol 1.3)",
              "set-up of " + scene.file + " with fsi-client at " + channel_->peer_description(),
              "use an fsi-client of protocol 1.3 or later, or remove the *Probe blocks from "
              "the scene");
}

void TcpFluidSide::send_probes(const scene::Scene& scene) {
  if (!probes_agreed()) return;
  protocol::ProbeSetup setup;
  setup.every_steps = static_cast<std::uint64_t>(scene.output.sensor_every_steps);
  setup.gravity = scene.gravity;
  setup.particle_spacing = scene.fluid.spacing;
  for (const probes::ProbeDefinition& probe : scene.probes) {
    setup.probes.push_back({static_cast<std::uint32_t>(probe.kind), probe.name, probe.parameters});
  }
  channel_->send(setup);
  probes_expected_ = !scene.probes.empty();
  probe_every_steps_ = setup.every_steps;
}

FluidReady TcpFluidSide::equilibrate() {
  const auto ready = expect_ready();
  FluidReady result;
  result.particle_count = ready.particle_count;
  result.liggghts_version = ready.liggghts_version;
  result.seconds_setup = ready.seconds_setup;
  result.seconds_equilibration = ready.seconds_equilibration;
  if (settling_agreed())
    result.release = channel_->expect<protocol::ReleaseState>(options_.peer_timeout);
  result.initial_forces = expect_forces(0);
  return result;
}

FluidForces TcpFluidSide::expect_forces(std::uint64_t step) {
  auto forces = channel_->expect<protocol::Forces>(options_.peer_timeout);
  if (forces.step != step) {
    throw Error("Forces of step " + std::to_string(forces.step) + " arrived, step " +
                    std::to_string(step) + " was expected",
                "coupled step", "use matching fsi-server and fsi-client releases");
  }
  FluidForces result{std::move(forces.forces), forces.diagnostics, {}, std::nullopt};
  // The client sends FluidHealth, then ProbeValues, after the Forces (docs/protocol.md).
  if ((capabilities_ & protocol::kCapabilityFluidHealth) != 0) {
    result.health = channel_->expect<protocol::FluidHealth>(options_.peer_timeout);
    if (result.health->step != step) {
      throw Error("FluidHealth of step " + std::to_string(result.health->step) +
                      " arrived after the Forces of step " + std::to_string(step),
                  "coupled step", "use matching fsi-server and fsi-client releases");
    }
  }
  if (probes_expected_ && step % probe_every_steps_ == 0) {
    auto probes = channel_->expect<protocol::ProbeValues>(options_.peer_timeout);
    if (probes.step != step) {
      throw Error("ProbeValues of step " + std::to_string(probes.step) + " arrived, step " +
                      std::to_string(step) + " was expected",
                  "coupled step", "use matching fsi-server and fsi-client releases");
    }
    result.probe_values = std::move(probes.values);
  }
  return result;
}

FluidForces TcpFluidSide::exchange(const BoundaryMotion& motion) {
  protocol::Step step;
  step.step = motion.step;
  step.time = motion.time;
  step.time_step = motion.time_step;
  step.positions = motion.positions;
  step.velocities = motion.velocities;
  // The probes that move with a body, placed at the end of the step, ahead of it (1.4).
  if (!motion.probe_placements.empty())
    channel_->send(protocol::ProbePlacement{motion.step, motion.probe_placements});
  if (motion.substeps > 1) {
    // Multi-rate (1.5): the stage values instead of the end, the fluid interpolates.
    channel_->send(protocol::StepMotion{motion.step, motion.time, motion.time_step, motion.substeps,
                                        motion.nodes, motion.node_positions,
                                        motion.node_velocities});
  } else {
    channel_->send(step);
  }
  return expect_forces(motion.step);
}

ParticleSnapshot TcpFluidSide::snapshot(std::uint64_t step) {
  channel_->send(protocol::SnapshotRequest{step});
  auto reply = channel_->expect<protocol::Snapshot>(options_.peer_timeout);
  ParticleSnapshot snapshot;
  snapshot.step = reply.step;
  snapshot.time = reply.time;
  snapshot.dimension = static_cast<int>(reply.dimension);
  snapshot.ids = std::move(reply.ids);
  snapshot.positions = std::move(reply.positions);
  snapshot.velocities = std::move(reply.velocities);
  snapshot.density = std::move(reply.density);
  snapshot.pressure = std::move(reply.pressure);
  return snapshot;
}

void TcpFluidSide::finish() {
  channel_->send(protocol::Shutdown{"end time reached"});
  const auto goodbye = channel_->expect<protocol::Goodbye>(std::chrono::seconds(60));
  spdlog::info("client finished: {} steps, {:.1f} s", goodbye.steps_done, goodbye.seconds_total);
  channel_->close();
}

void TcpFluidSide::report_fault(const std::exception& failure, bool during_coupled_steps) noexcept {
  // Told to the client unless it reported the fault itself (docs/protocol.md §7): before the
  // coupled steps a failure of ours is a set-up failure, during them (solver, signal) an abort.
  try {
    const auto code =
        protocol::error_code_for(failure, during_coupled_steps ? protocol::ErrorCode::PeerAborted
                                                               : protocol::ErrorCode::SetupFailed);
    if (channel_ && code) {
      channel_->send(protocol::ErrorMessage{*code, failure.what()});
      channel_->close();
    }
  } catch (...) {
    // The connection may be the fault itself; the run records the failure either way.
  }
}

std::unique_ptr<FluidSide::WaitScope> TcpFluidSide::waiting() {
  if (!heartbeat_) return nullptr;
  return std::make_unique<HeartbeatScope>(*heartbeat_);
}

std::optional<FluidPeer> TcpFluidSide::peer() const {
  if (!client_) return std::nullopt;
  return FluidPeer{capabilities_, (capabilities_ & protocol::kCapabilityAuthentication) != 0,
                   client_->software_version, client_->host, client_->mpi_ranks};
}

}  // namespace fsi::coupling
