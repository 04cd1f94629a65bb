#include "client_session.hpp"

#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <thread>
#include <utility>
#include <variant>
#include <vector>

#include "boundary_distribution.hpp"
#include "decomposition.hpp"
#include "fault_relay.hpp"
#include "fluid_decomposition.hpp"
#include "fluid_probes.hpp"
#include "fluid_state.hpp"
#include "fsi/common/error.hpp"
#include "fsi/common/stopwatch.hpp"
#include "fsi/common/version.hpp"
#include "fsi/contact/liggghts_fix.hpp"
#include "fsi/protocol/auth.hpp"
#include "fsi/protocol/channel.hpp"
#include "fsi/protocol/messages.hpp"
#include "fsi/protocol/step_motion.hpp"
#include "liggghts_driver.hpp"
#include "liggghts_errors.hpp"
#include "settling.hpp"

namespace fsi::client {
namespace {

namespace protocol = fsi::protocol;

// The set-up data every rank needs, broadcast from rank 0.
struct SetupData {
  protocol::Setup setup;
  protocol::Mesh mesh;
  protocol::Particles particles;
  std::optional<protocol::Resume> resume;      // protocol 1.6: a resumed run, in place of Settling
  std::optional<protocol::Settling> settling;  // protocol 1.2, when both sides agreed
  std::optional<protocol::ProbeSetup> probes;  // protocol 1.3, when both sides agreed
};

// The client's half of a checkpoint (FluidState.state, Resume.state): the fluid's state and the
// last step's rates (fluid_state.hpp), one after the other, each behind its length.
std::string pack_checkpoint(const std::string& state, const std::string& rates) {
  std::string bytes;
  for (const std::string* part : {&state, &rates}) {
    const std::uint64_t size = part->size();
    bytes.append(reinterpret_cast<const char*>(&size), sizeof size);
    bytes += *part;
  }
  return bytes;
}

std::pair<std::string_view, std::string_view> unpack_checkpoint(std::string_view bytes) {
  std::string_view parts[2];
  for (std::string_view& part : parts) {
    std::uint64_t size = 0;
    if (bytes.size() < sizeof size) break;
    std::memcpy(&size, bytes.data(), sizeof size);
    bytes.remove_prefix(sizeof size);
    if (size > bytes.size()) {
      throw Error("the checkpoint's fluid state is cut short", "Resume",
                  "resume from another checkpoint; this one is damaged");
    }
    part = bytes.substr(0, size);
    bytes.remove_prefix(size);
  }
  if (!bytes.empty() || parts[1].empty()) {
    throw Error("the checkpoint's fluid state has another layout", "Resume",
                "resume with the release that wrote the checkpoint");
  }
  return {parts[0], parts[1]};
}

// State the exit handler needs when LIGGGHTS ends the process with exit(1) (Error::all).
struct ExitReport {
  protocol::Channel* channel = nullptr;
  const LiggghtsDriver* driver = nullptr;
  protocol::HeartbeatSender* heartbeat = nullptr;
  bool active = false;
};
ExitReport g_exit_report;

void report_liggghts_exit() {
  if (!g_exit_report.active || !g_exit_report.channel) return;
  // LIGGGHTS may exit in the middle of a step, while heartbeats go out: stop them first.
  if (g_exit_report.heartbeat) g_exit_report.heartbeat->stop();
  std::string text = "LIGGGHTS stopped the client";
  if (g_exit_report.driver) {
    const auto& position = g_exit_report.driver->position();
    const std::string error = g_exit_report.driver->output().last_error_line();
    if (!error.empty()) text += ": " + error;
    if (!position.script.empty()) {
      text += " (while executing " + position.script +
              (position.line > 0 ? ":" + std::to_string(position.line) : std::string()) + ": '" +
              position.command + "')";
    }
  }
  try {
    g_exit_report.channel->send(protocol::ErrorMessage{protocol::ErrorCode::LiggghtsError, text});
    g_exit_report.channel->close();
  } catch (...) {
    // The server may be gone already; the exit status tells the rest.
  }
}

class MpiContext {
 public:
  explicit MpiContext(MPI_Comm communicator) : communicator_(communicator) {
    MPI_Comm_rank(communicator_, &rank_);
    MPI_Comm_size(communicator_, &size_);
  }
  MPI_Comm communicator() const { return communicator_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  // Wall time spent in MPI distribution and reduction of coupling data.
  Stopwatch& mpi_time() { return mpi_time_; }

  // Broadcasts a message type and its payload from rank 0.
  void broadcast(std::uint16_t& type, std::vector<std::byte>& payload) {
    ScopedTimer timer(mpi_time_);
    std::uint64_t header[2] = {type, payload.size()};
    MPI_Bcast(header, 2, MPI_UINT64_T, 0, communicator_);
    type = static_cast<std::uint16_t>(header[0]);
    payload.resize(header[1]);
    // MPI counts are int: send large payloads in pieces.
    constexpr std::size_t kPiece = std::size_t{1} << 30;
    for (std::size_t offset = 0; offset < payload.size(); offset += kPiece) {
      const int count = static_cast<int>(std::min(kPiece, payload.size() - offset));
      MPI_Bcast(payload.data() + offset, count, MPI_BYTE, 0, communicator_);
    }
  }

 private:
  MPI_Comm communicator_;
  int rank_ = 0;
  int size_ = 1;
  Stopwatch mpi_time_;
};

std::string host_name() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

class ClientSession {
 public:
  ClientSession(MPI_Comm communicator, const ClientOptions& options, FaultRelay& relay)
      : mpi_(communicator), options_(options), relay_(relay) {}
  ClientSession(const ClientSession&) = delete;
  ClientSession& operator=(const ClientSession&) = delete;
  // The exit handler and the relay must not reach into a finished session (--persistent runs
  // several).
  ~ClientSession() {
    relay_.set_handler({});
    g_exit_report.active = false;
    g_exit_report.channel = nullptr;
    g_exit_report.driver = nullptr;
    g_exit_report.heartbeat = nullptr;
  }

  int run() {
    if (mpi_.root()) {
      connect();
      // Another rank's fault, relayed while this rank may wait for it inside LIGGGHTS.
      relay_.set_handler([this](int rank, std::uint32_t code, const std::string& text) {
        spdlog::error("fsi-client: {}{}", rank >= 0 ? "rank " + std::to_string(rank) + ": " : "",
                      text);
        spdlog::default_logger()->flush();
        report_failure(text, static_cast<protocol::ErrorCode>(code));
      });
    }
    // Every rank must know which optional messages of the set-up follow.
    MPI_Bcast(&capabilities_, 1, MPI_UINT32_T, 0, mpi_.communicator());
    SetupData data = receive_setup();
    // From here until Ready, rank 0 tells the server it is busy (set-up and equilibration).
    setup_busy_ = busy();
    dimension_ = static_cast<int>(data.setup.dimension);
    configure_boundary(std::move(data.mesh));
    DriverOptions driver_options;
    driver_options.log_file = mpi_.root() ? options_.liggghts_log : std::string();
    driver_options.echo_output = options_.echo_liggghts;
    driver_options.allow_unsafe_commands = options_.allow_unsafe_commands;
    driver_ = std::make_unique<LiggghtsDriver>(mpi_.communicator(), driver_options, boundary_);
    g_exit_report.driver = driver_.get();
    prepare_fluid(data);
    exchange_loop();
    g_exit_report.active = false;
    return 0;
  }

  // Tells the server why the client ends: once, from whichever thread of rank 0 learns it first
  // (the main thread's own fault, or the relay's watcher with another rank's).
  void report_failure(const std::string& text, protocol::ErrorCode code) {
    if (!channel_ || told_server_.exchange(true)) return;
    g_exit_report.active = false;
    if (heartbeat_) heartbeat_->stop();
    // The main thread holds the channel only while it talks to the server, which no fault of
    // another rank interrupts (that rank would wait in a collective call, not fail); a channel
    // still held after two seconds is left alone, and the server sees the connection close.
    std::unique_lock lock(channel_mutex_, std::defer_lock);
    if (!lock.try_lock_for(std::chrono::seconds(2))) return;
    try {
      channel_->send(protocol::ErrorMessage{code, text});
      channel_->close();  // lingers until the server has read it (MPI_Abort follows)
    } catch (...) {
    }
  }

  // Rank 0, after a fault of the connection: how many heartbeats went out and when the last one
  // did, to tell a silent client from a network or a server that stopped reading. Empty on other
  // ranks and without heartbeats.
  std::string heartbeat_summary() const {
    if (!heartbeat_) return {};
    const auto last = heartbeat_->last_sent();
    const std::uint64_t sent = heartbeat_->sent();
    if (!last) return fmt::format("no heartbeat had gone out to fsi-server ({} sent)", sent);
    const double ago =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - *last).count();
    // Heartbeats fill only the silences of a long computation (a busy spell longer than the
    // interval); steps that answer sooner need none, so the last one can be long ago.
    return fmt::format(
        "{} heartbeat(s) had gone out to fsi-server, the last {:.2f} s before this (they go out "
        "only while the client computes for longer than {} ms without a message to the server, "
        "so a long time since the last one means its steps answered within that)",
        sent, ago, protocol::kHeartbeatInterval.count());
  }

  // What the server and the log are told of a fault on this rank: LIGGGHTS' own line with the
  // script line being executed, and which rank saw it when there are several.
  std::string describe(const std::exception& failure) const {
    const std::string rank = mpi_.size() > 1 ? " on rank " + std::to_string(mpi_.rank()) + " of " +
                                                   std::to_string(mpi_.size())
                                             : std::string();
    const auto* liggghts = dynamic_cast<const LiggghtsError*>(&failure);
    if (liggghts == nullptr) {
      return mpi_.root() ? std::string(failure.what())
                         : "fsi-client" + rank + ": " + failure.what();
    }
    // An error every rank raises is the job's, not a rank's.
    std::string text = "LIGGGHTS stopped the client" + (liggghts->every_rank() ? "" : rank) + ": " +
                       failure.what();
    if (driver_) {
      const auto& position = driver_->position();
      if (!position.script.empty()) {
        text += " (while executing " + position.script +
                (position.line > 0 ? ":" + std::to_string(position.line) : std::string()) + ": '" +
                position.command + "')";
      }
    }
    return text;
  }

 private:
  void connect() {
    channel_ = std::make_unique<protocol::Channel>(connect_to_server());
    g_exit_report.channel = channel_.get();
    g_exit_report.active = true;
    static const bool registered = std::atexit(report_liggghts_exit) == 0;
    (void)registered;
    protocol::ClientHandshake handshake;
    handshake.token = options_.token;
    handshake.hello.software_version = std::string(fsi::software_version());
    handshake.hello.host = host_name();
    handshake.hello.mpi_ranks = static_cast<std::uint32_t>(mpi_.size());
    handshake.timeout = options_.connect_timeout;
    handshake.session_capabilities =
        protocol::kCapabilitySettling | protocol::kCapabilityFluidHealth |
        protocol::kCapabilityProbes | protocol::kCapabilityMovingProbes |
        protocol::kCapabilityMultiRate | protocol::kCapabilityCheckpoint;
    const protocol::ClientHandshakeResult opened = protocol::open_session(*channel_, handshake);
    capabilities_ = opened.capabilities;
    heartbeat_ = std::make_unique<protocol::HeartbeatSender>(
        *channel_, (capabilities_ & protocol::kCapabilityHeartbeat) != 0);
    g_exit_report.heartbeat = heartbeat_.get();
    const protocol::Welcome& welcome = opened.welcome;
    spdlog::info(
        "connected to {} (fsi-server {}, run '{}'), {} rank(s){}", channel_->peer_description(),
        welcome.software_version, welcome.run_name, mpi_.size(),
        (capabilities_ & protocol::kCapabilityAuthentication) != 0 ? ", server authenticated" : "");
  }

  // --persistent waits for the next server as long as it takes; otherwise --connect-timeout.
  protocol::Channel connect_to_server() const {
    if (!options_.persistent) {
      return protocol::Channel::connect(options_.host, options_.port, options_.connect_timeout);
    }
    while (true) {
      try {
        return protocol::Channel::connect(options_.host, options_.port, options_.connect_timeout);
      } catch (const protocol::ProtocolError&) {
        // Nobody listens yet: keep waiting.
      }
    }
  }

  // Rank 0 sends heartbeats while this lives (other ranks have no connection).
  protocol::HeartbeatSender::Busy busy() {
    return heartbeat_ ? heartbeat_->busy() : protocol::HeartbeatSender::Busy{};
  }

  // Test hook: FSI_TEST_SLOW_STEP="STEP:SECONDS" makes every rank sleep that long in coupled step
  // STEP, standing in for a long LIGGGHTS step (tests/integration/test_heartbeat.py).
  void slow_step_for_tests(std::uint64_t step) const {
    const char* hook = std::getenv("FSI_TEST_SLOW_STEP");
    if (hook == nullptr) return;
    unsigned long long slow_step = 0;
    double seconds = 0.0;
    if (std::sscanf(hook, "%llu:%lf", &slow_step, &seconds) == 2 && slow_step == step) {
      if (mpi_.root()) {
        std::fprintf(stderr, "fsi-client: test hook: step %llu takes %g s\n", slow_step, seconds);
        std::fflush(stderr);
      }
      std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    }
  }

  // How rank 0 hands a message to the other ranks.
  enum class Handout : std::uint64_t {
    kWhole = 0,         // every rank gets the whole message
    kMeshSettings = 1,  // the Mesh stays on rank 0; the others get its settings (no arrays)
    kShares = 2,        // a Step or StepMotion: each rank gets its share's vertices
    kSharesChosen = 3,  // as kShares, after choosing the shares again
  };

  // Receives one frame on rank 0 and hands the message to every rank: whole, or only what a
  // rank's share of the boundary needs (boundary_distribution.hpp).
  protocol::Message next_message() {
    std::uint16_t type = 0;
    std::vector<std::byte> payload;
    std::optional<protocol::Message> whole;
    Handout handout = Handout::kWhole;
    if (mpi_.root()) {
      std::lock_guard lock(channel_mutex_);
      protocol::Frame frame =
          channel_->receive(options_.peer_timeout, "the next message from fsi-server");
      type = static_cast<std::uint16_t>(frame.header.type);
      payload = std::move(frame.payload);
      const auto kind = static_cast<protocol::MessageType>(type);
      if (kind == protocol::MessageType::Mesh) {
        whole = protocol::decode(kind, payload);
        handout = Handout::kMeshSettings;
      } else if (distribution_ && (kind == protocol::MessageType::Step ||
                                   kind == protocol::MessageType::StepMotion)) {
        whole = protocol::decode(kind, payload);
        handout = distribution_->take_whole(*whole) ? Handout::kSharesChosen : Handout::kShares;
      }
    }
    std::uint64_t header[2] = {type, static_cast<std::uint64_t>(handout)};
    {
      ScopedTimer timer(mpi_.mpi_time());
      MPI_Bcast(header, 2, MPI_UINT64_T, 0, mpi_.communicator());
    }
    type = static_cast<std::uint16_t>(header[0]);
    handout = static_cast<Handout>(header[1]);
    switch (handout) {
      case Handout::kMeshSettings:
        return mesh_settings(whole);
      case Handout::kSharesChosen:
        distribution_->select(driver_->lammps());
        [[fallthrough]];
      case Handout::kShares: {
        ScopedTimer timer(mpi_.mpi_time());
        return distribution_->scatter(whole ? &*whole : nullptr, type);
      }
      case Handout::kWhole:
        break;
    }
    mpi_.broadcast(type, payload);
    return protocol::decode(static_cast<protocol::MessageType>(type), payload);
  }

  // Rank 0 keeps the whole Mesh; the other ranks get its counts and settings only.
  protocol::Message mesh_settings(std::optional<protocol::Message>& whole) {
    std::array<double, 4> settings{};
    if (mpi_.root()) {
      const auto& mesh = std::get<protocol::Mesh>(*whole);
      settings = {static_cast<double>(mesh.dimension),
                  static_cast<double>(mesh.dynamic_vertex_count),
                  static_cast<double>(mesh.refinement_option), mesh.refinement_resolution};
    }
    MPI_Bcast(settings.data(), 4, MPI_DOUBLE, 0, mpi_.communicator());
    if (mpi_.root()) return std::move(*whole);
    protocol::Mesh mesh;
    mesh.dimension = static_cast<std::uint32_t>(settings[0]);
    mesh.dynamic_vertex_count = static_cast<std::uint32_t>(settings[1]);
    mesh.refinement_option = static_cast<std::uint32_t>(settings[2]);
    mesh.refinement_resolution = settings[3];
    return mesh;
  }

  template <class T>
  T expect_message(const char* phase) {
    protocol::Message message = next_message();
    if (auto* wanted = std::get_if<T>(&message)) return std::move(*wanted);
    if (auto* error = std::get_if<protocol::ErrorMessage>(&message)) {
      throw protocol::PeerReportedError(error->code, error->text,
                                        "fsi-server, during " + std::string(phase));
    }
    throw protocol::UnexpectedMessageError("expected a " + protocol::name(T::kType) +
                                               " message but received " +
                                               protocol::name(protocol::type_of(message)),
                                           "fsi-client, during " + std::string(phase),
                                           "use matching fsi-server and fsi-client releases");
  }

  SetupData receive_setup() {
    SetupData data;
    data.setup = expect_message<protocol::Setup>("set-up");
    data.mesh = expect_message<protocol::Mesh>("set-up (mesh)");
    data.particles = expect_message<protocol::Particles>("set-up (particles)");
    // Settling for a new run (1.2); a Resume (1.6) for a run resumed from a checkpoint.
    const bool settling = (capabilities_ & protocol::kCapabilitySettling) != 0;
    const bool resumable = (capabilities_ & protocol::kCapabilityCheckpoint) != 0;
    if (settling || resumable) {
      protocol::Message next = next_message();
      if (auto* resume = std::get_if<protocol::Resume>(&next); resume && resumable) {
        data.resume = std::move(*resume);
      } else if (auto* settled = std::get_if<protocol::Settling>(&next); settled && settling) {
        data.settling = std::move(*settled);
      } else if (auto* error = std::get_if<protocol::ErrorMessage>(&next)) {
        throw protocol::PeerReportedError(error->code, error->text,
                                          "fsi-server, during set-up (settling)");
      } else {
        throw protocol::UnexpectedMessageError(
            std::string("expected a ") + (settling ? "Settling" : "Resume") +
                " message but received " + protocol::name(protocol::type_of(next)),
            "fsi-client, during set-up (settling)",
            "use matching fsi-server and fsi-client releases");
      }
    }
    if ((capabilities_ & protocol::kCapabilityProbes) != 0) {
      data.probes = expect_message<protocol::ProbeSetup>("set-up (probes)");
    }
    if ((data.setup.dimension != 2 && data.setup.dimension != 3) ||
        data.mesh.dimension != data.setup.dimension ||
        data.particles.dimension != data.setup.dimension) {
      throw Error("inconsistent dimensions from fsi-server: scene " +
                      std::to_string(data.setup.dimension) + ", mesh " +
                      std::to_string(data.mesh.dimension) + ", particles " +
                      std::to_string(data.particles.dimension) + " (2 or 3, all equal)",
                  "set-up", "use matching fsi-server and fsi-client releases");
    }
    return data;
  }

  // Rank 0 keeps the whole mesh; every rank holds its share once select_shares() has run.
  void configure_boundary(protocol::Mesh mesh) {
    boundary_ = std::make_shared<contact::CouplingBoundary>();
    distribution_ = std::make_unique<DistributedBoundary>(mpi_.communicator(), boundary_);
    distribution_->configure(std::move(mesh));
  }

  // Collective: every rank's share of the boundary for the decomposition and particles as they
  // are now (after script 1, a balance, a restored fluid, and every equilibration chunk).
  void select_shares() {
    ScopedTimer timer(mpi_.mpi_time());
    distribution_->select(driver_->lammps());
  }

  // The scene's variables, then script 1 with the scene's particles created right after its
  // create_box; checks that the particles and the fsi/sph fix exist.
  void run_script1(const SetupData& data) {
    std::vector<std::pair<std::string, std::string>> variables;
    for (const auto& variable : data.setup.liggghts_variables)
      variables.emplace_back(variable.name, variable.value);
    driver_->define_variables(variables);
    ParticleBlock particles;
    particles.dimension = static_cast<int>(data.particles.dimension);
    particles.atom_type = static_cast<int>(data.particles.atom_type);
    particles.mass = data.particles.mass;
    particles.density = data.particles.density;
    particles.positions = data.particles.positions;
    particles.velocities = data.particles.velocities;
    if (data.settling) particles.densities = data.settling->initial_densities;
    const bool have_particles = !particles.positions.empty();
    driver_->set_automatic_grid(automatic_grid(particles));
    bool inserted = false;
    driver_->run_script(data.setup.script1_name, data.setup.script1_text, [&] {
      if (have_particles && !inserted) {
        driver_->insert_particles(particles);
        inserted = true;
      }
    });
    if (have_particles && !inserted) {
      throw Error(
          "script 1 has no create_box command, so the fluid particles of the scene "
          "could not be created",
          data.setup.script1_name, "create the simulation box in script 1");
    }
    if (!driver_->has_fsi_fix()) {
      throw Error(
          "script 1 defines no 'fix ID group fsi/sph ...': the fluid would not see the "
          "structure",
          data.setup.script1_name, "add the fix (docs/fix_fsi_sph.md)");
    }
    // No forces yet to carry: the set-up run that follows builds everything.
    if (options_.balance) balance_particles();
    log_decomposition(have_particles);
  }

  // The processor grid for script 1 from the extent of the server's particles (docs/user-guide.md,
  // "Ranks and balance"); none (LIGGGHTS' default from the box) when the scripts create the fluid.
  std::optional<ProcessorGrid> automatic_grid(const ParticleBlock& particles) const {
    if (!options_.automatic_grid || mpi_.size() < 2 || particles.positions.empty())
      return std::nullopt;
    return choose_processor_grid(mpi_.size(), particles.dimension,
                                 positions_extent(particles.positions, particles.dimension));
  }

  // Moves the cuts between the ranks' sub-domains so that each owns an equal share of the
  // particles, and the particles to their owners; the next run must set up (collective). Returns
  // the imbalance reached (whole lattice planes cannot always be shared evenly).
  double balance_particles() {
    if (mpi_.size() < 2) return 1.0;
    LAMMPS_NS::LAMMPS& lammps = driver_->lammps();
    apply_cuts(lammps, balanced_cuts_of_particles(lammps, mpi_.communicator()));
    migrate_particles(lammps);
    reached_imbalance_ = imbalance(particles_per_rank(lammps, mpi_.communicator()));
    return reached_imbalance_;
  }

  void log_decomposition(bool server_particles) const {
    const std::vector<std::uint64_t> counts =
        particles_per_rank(driver_->lammps(), mpi_.communicator());
    if (!mpi_.root() || mpi_.size() < 2) return;
    const char* grid_source = driver_->script_chose_grid() ? "script 1's processors command"
                              : !options_.automatic_grid   ? "LIGGGHTS' default (--grid liggghts)"
                              : server_particles
                                  ? "automatic, from the fluid's extent"
                                  : "LIGGGHTS' default: the scripts create the fluid";
    std::string shares;
    for (const std::uint64_t count : counts)
      shares += (shares.empty() ? "" : " / ") + std::to_string(count);
    spdlog::info(
        "decomposition: {} ranks ({}), {} cuts {}; particles per rank {} (imbalance {:.3f})",
        grid_text(processor_grid(driver_->lammps())), grid_source,
        options_.balance ? "balanced" : "even", cuts_text(driver_->lammps()), shares,
        imbalance(counts));
  }

  // Between steps (collective): when LIGGGHTS' step counter has passed a multiple of
  // rebalance_every since the last call, compares the ranks' particle counts and re-balances
  // when the largest exceeds rebalance_threshold times the mean, or times the imbalance the last
  // balance reached if that was higher (three ranks on ten lattice planes: 1.2 at best; no
  // futile moves at every check). The last step's forces and
  // density rates are carried through the set-up the move needs (fluid_state.hpp), so the run
  // goes on as without it, to the summation order. Depends only on the step counter and the
  // particles: a resumed run re-balances where the original did.
  // `mark_busy`: rank 0 marks itself busy for the heartbeat while it moves particles (in the
  // coupled phase; the set-up is busy as a whole).
  void maybe_rebalance(bool mark_busy) {
    const std::int64_t now = driver_->current_step();
    const std::int64_t before = last_balance_check_;
    last_balance_check_ = now;
    if (!options_.balance || mpi_.size() < 2 || options_.rebalance_every == 0) return;
    const auto every = static_cast<std::int64_t>(options_.rebalance_every);
    if (now / every == before / every) return;
    LAMMPS_NS::LAMMPS& lammps = driver_->lammps();
    const double measured = imbalance(particles_per_rank(lammps, mpi_.communicator()));
    largest_imbalance_ = std::max(largest_imbalance_, measured);
    if (measured <= options_.rebalance_threshold * std::max(1.0, reached_imbalance_)) return;
    auto balancing = mark_busy ? busy() : protocol::HeartbeatSender::Busy{};
    Stopwatch watch;
    watch.start();
    const std::string rates = capture_step_rates(lammps, mpi_.communicator());
    const double after = balance_particles();
    select_shares();
    driver_->run_with_setup(0);
    apply_step_rates(lammps, mpi_.communicator(), rates);
    seconds_rebalancing_ += watch.stop();
    ++rebalances_;
    if (mpi_.root()) {
      spdlog::debug("re-balanced at LIGGGHTS step {}: imbalance {:.3f} -> {:.3f}; {}", now,
                    measured, after, cuts_text(lammps));
    }
  }

  // A checkpoint's fluid in place of this one (collective). Balanced: the fluid is placed, the
  // cuts are set from it, and it is placed again, so that the process that writes a checkpoint
  // and one that resumes from it hold the same particles in the same order on every rank.
  void restore_balanced(std::string_view state) {
    LAMMPS_NS::LAMMPS& lammps = driver_->lammps();
    restore_fluid_state(lammps, mpi_.communicator(), state);
    if (!options_.balance || mpi_.size() < 2) return;
    apply_cuts(lammps, balanced_cuts_of_particles(lammps, mpi_.communicator()));
    restore_fluid_state(lammps, mpi_.communicator(), state);
    reached_imbalance_ = imbalance(particles_per_rank(lammps, mpi_.communicator()));
  }

  // Every rank's peak resident memory (getrusage), logged by rank 0 at the end (collective).
  void log_peak_memory() const {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const double megabytes = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: in KiB
    std::vector<double> all(static_cast<std::size_t>(mpi_.size()), 0.0);
    MPI_Gather(&megabytes, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, mpi_.communicator());
    if (!mpi_.root()) return;
    spdlog::info("memory: peak resident {:.1f} MiB per rank ({} particles)", fmt::join(all, " / "),
                 driver_->particle_count());
  }

  // Every rank's ghost particles at the end, and LIGGGHTS' ghost cut-off (collective): the
  // halo the decomposition costs (bench/cost_model.py reads this line).
  void log_ghosts() const {
    const LAMMPS_NS::LAMMPS& lammps = driver_->lammps();
    const std::vector<std::uint64_t> ghosts = ghosts_per_rank(lammps, mpi_.communicator());
    if (!mpi_.root()) return;
    spdlog::info("ghosts: {} per rank (ghost cut-off {:.6g} m)", fmt::join(ghosts, " / "),
                 ghost_cutoff(lammps));
  }

  // Every rank's sampling points per evaluation, averaged over its evaluations: those it
  // generated (within reach of its own particles) and all of its share of the mesh (collective;
  // thesis §7.1).
  void log_boundary_share() const {
    if (!boundary_) return;  // the same on every rank
    const double evaluations =
        static_cast<double>(std::max<std::uint64_t>(1, boundary_->evaluations));
    const std::array<double, 2> mine{
        static_cast<double>(boundary_->sampling_points_generated) / evaluations,
        static_cast<double>(boundary_->sampling_points) / evaluations};
    std::vector<double> all(2 * static_cast<std::size_t>(mpi_.size()), 0.0);
    MPI_Gather(mine.data(), 2, MPI_DOUBLE, all.data(), 2, MPI_DOUBLE, 0, mpi_.communicator());
    if (!mpi_.root()) return;
    std::vector<std::string> generated, held;
    for (std::size_t r = 0; r < all.size(); r += 2) {
      generated.push_back(fmt::format("{:.0f}", all[r]));
      held.push_back(fmt::format("{:.0f}", all[r + 1]));
    }
    spdlog::info(
        "boundary: {} sampling points generated per evaluation per rank, of {} in its share of "
        "the mesh",
        fmt::join(generated, " / "), fmt::join(held, " / "));
  }

  void log_balance_summary() const {
    if (!mpi_.root() || mpi_.size() < 2 || !options_.balance) return;
    spdlog::info(
        "balance: {} re-balance(s) in {:.3f} s; largest imbalance found at a check {:.3f} "
        "(threshold {:.3f}, checked every {} LIGGGHTS steps)",
        rebalances_, seconds_rebalancing_, largest_imbalance_, options_.rebalance_threshold,
        options_.rebalance_every);
  }

  void prepare_fluid(const SetupData& data) {
    if (data.resume) {
      resume_fluid(data);
      return;
    }
    Stopwatch setup_watch;
    setup_watch.start();
    run_script1(data);
    // Equilibration (thesis §5.4.2): the structure rests in its initial configuration.
    // Wall-pressure probes read every sampling point of their patches on rank 0.
    distribution_->root_holds_whole_mesh(reads_wall_samples(data));
    distribution_->hold_still(true);
    select_shares();
    driver_->set_time_step(data.setup.time_step);
    driver_->run_with_setup(0);
    const double seconds_setup = setup_watch.stop();

    Stopwatch equilibration_watch;
    equilibration_watch.start();
    const AppliedDrag drag =
        data.settling ? settling_drag(*data.settling, data.setup) : AppliedDrag{};
    if (drag.rate > 0.0) driver_->add_velocity_drag(drag.rate);
    if (data.setup.equilibration_steps > 0) equilibrate(data.setup.equilibration_steps);
    // The drag belongs to the equilibration only: the coupled run starts without it.
    if (drag.rate > 0.0) driver_->remove_velocity_drag();
    driver_->run_script(data.setup.script2_name, data.setup.script2_text);
    // The coupled phase starts from the structure's initial velocities; a run with set-up makes
    // script 2's changes effective and evaluates the wall forces f(0).
    distribution_->hold_still(false);
    select_shares();
    // The wall-pressure probes of step 0 read the wall forces of this evaluation.
    boundary_->samples.enabled = reads_wall_samples(data);
    driver_->set_time_step(data.setup.time_step);
    driver_->run_with_setup(0);
    const double seconds_equilibration = equilibration_watch.stop();
    time_step_ = data.setup.time_step;
    dimension_ = static_cast<int>(data.setup.dimension);

    const std::uint64_t count = driver_->particle_count();
    std::optional<FluidEnergies> energies;
    if (data.settling) energies = driver_->fluid_energies(data.settling->gravity);
    setup_busy_ = {};
    // Every rank: how the fluid is spread (rank 0 only by default; --log-all-ranks for all).
    spdlog::info("ready: {} of {} particles on this rank; set-up {:.2f} s, equilibration {:.2f} s",
                 driver_->local_particle_count(), count, seconds_setup, seconds_equilibration);
    if (mpi_.root()) {
      protocol::Ready ready;
      ready.particle_count = count;
      ready.liggghts_version = "LIGGGHTS 3.8 (Debian libliggghts)";
      ready.seconds_setup = seconds_setup;
      ready.seconds_equilibration = seconds_equilibration;
      send(ready);
      if (energies) {
        protocol::ReleaseState release;
        release.drag_rate = drag.rate;
        release.column_height = drag.column_height;
        release.fluid_mass = energies->mass;
        release.kinetic_energy = energies->kinetic;
        release.potential_energy = energies->potential;
        send(release);
      }
    }
    if (data.probes && !data.probes->probes.empty()) prepare_probes(*data.probes, data.particles);
    last_balance_check_ = driver_->current_step();
    send_forces(0, 0.0, 0.0);
  }

  static bool reads_wall_samples(const SetupData& data) {
    return data.probes && std::any_of(data.probes->probes.begin(), data.probes->probes.end(),
                                      [](const protocol::ProbeRecord& record) {
                                        return probes::reads_wall_samples(
                                            {static_cast<probes::ProbeKind>(record.kind), {}, {}});
                                      });
  }

  // A resumed run (1.6; docs/user-guide.md, "Checkpoints and resume"): the scripts on the scene's
  // particles as in a new run but no equilibration, then the fluid of the checkpoint in their
  // place (fluid_state.hpp); the boundary is the Mesh's, at the checkpoint. The next run sets up.
  void resume_fluid(const SetupData& data) {
    Stopwatch setup_watch;
    setup_watch.start();
    run_script1(data);
    distribution_->root_holds_whole_mesh(reads_wall_samples(data));
    select_shares();
    driver_->set_time_step(data.setup.time_step);
    driver_->run_script(data.setup.script2_name, data.setup.script2_text);
    driver_->set_time_step(data.setup.time_step);
    driver_->run_with_setup(0);
    const auto [state, rates] = unpack_checkpoint(data.resume->state);
    restore_balanced(state);
    select_shares();
    driver_->run_with_setup(0);  // as after a checkpoint (write_checkpoint)
    apply_step_rates(driver_->lammps(), mpi_.communicator(), rates);
    last_balance_check_ = driver_->current_step();
    time_step_ = data.setup.time_step;
    dimension_ = static_cast<int>(data.setup.dimension);
    last_time_ = data.resume->time;
    const double seconds_setup = setup_watch.stop();
    const std::uint64_t count = driver_->particle_count();
    setup_busy_ = {};
    spdlog::info(
        "resumed at step {} (t = {:.9g} s): {} of {} particles on this rank; set-up "
        "{:.2f} s",
        data.resume->step, data.resume->time, driver_->local_particle_count(), count,
        seconds_setup);
    if (mpi_.root()) {
      protocol::Ready ready;
      ready.particle_count = count;
      ready.liggghts_version = "LIGGGHTS 3.8 (Debian libliggghts)";
      ready.seconds_setup = seconds_setup;
      send(ready);
    }
    if (data.probes && !data.probes->probes.empty()) prepare_probes(*data.probes, data.particles);
  }

  // A checkpoint (1.6): the fluid's state to the server, and this process continues from the
  // very state a resume from it starts in (restored from its own bytes), so that a resumed run
  // goes on bit for bit like this one (docs/user-guide.md, "Checkpoints and resume").
  void write_checkpoint(const protocol::CheckpointRequest& request) {
    if ((capabilities_ & protocol::kCapabilityCheckpoint) == 0) {
      throw protocol::UnexpectedMessageError(
          "fsi-server asked for a checkpoint, but checkpoints were not agreed",
          "fsi-client, checkpoint of step " + std::to_string(request.step),
          "use matching fsi-server and fsi-client releases");
    }
    LAMMPS_NS::LAMMPS& lammps = driver_->lammps();
    const std::string state = capture_fluid_state(lammps, mpi_.communicator());
    const std::string rates = capture_step_rates(lammps, mpi_.communicator());
    restore_balanced(state);
    select_shares();
    // The set-up right here, with the walls where they were at the checkpoint (a resume does
    // the same with the Mesh's), then the last step's forces and density rates in place of the
    // set-up's: the next step goes on as without a checkpoint (to the summation order).
    driver_->run_with_setup(0);
    apply_step_rates(lammps, mpi_.communicator(), rates);
    const std::uint64_t count = driver_->particle_count();
    if (mpi_.root()) send(protocol::FluidState{request.step, count, pack_checkpoint(state, rates)});
  }

  // The scene's probes over LIGGGHTS' particles, with the kernel and h of the scripts (collective).
  void prepare_probes(const protocol::ProbeSetup& setup, const protocol::Particles& particles) {
    probes::ProbeContext context;
    context.dimension = dimension_;
    context.gravity = setup.gravity;
    context.particle_spacing = setup.particle_spacing;
    if (!(context.particle_spacing > 0.0)) {
      const FluidExtent extent = driver_->fluid_extent(setup.gravity);
      if (extent.mean_density > 0.0)
        context.particle_spacing =
            std::pow(extent.mean_mass / extent.mean_density, 1.0 / dimension_);
    }
    std::vector<probes::ProbeDefinition> definitions;
    for (const protocol::ProbeRecord& record : setup.probes) {
      definitions.push_back(
          {static_cast<probes::ProbeKind>(record.kind), record.name, record.parameters});
    }
    probe_every_steps_ = setup.every_steps;
    probes_ = std::make_unique<FluidProbes>(driver_->lammps(), mpi_.communicator(),
                                            probes::ProbeSet(std::move(definitions), context),
                                            static_cast<int>(particles.atom_type));
    // Rank 0 holds every sampling point of the probes' patches (root_holds_whole_mesh) and
    // tells every rank what it finds.
    share_verdict(mpi_.root() ? probes_->probes().wall_problems(wall_samples()) : std::string(),
                  mpi_.communicator(), "probe set-up (the wall law's sampling points at t = 0)",
                  "enlarge the probe's radius to the spacing of the sampling points (about "
                  "Coupling.refinement_resolution / the fix's gauss points) or move its centre "
                  "onto the mesh");
    if (mpi_.root()) {
      spdlog::info(
          "{} probe(s) every {} step(s), {} column(s); LIGGGHTS kernel {}, support {:.6g} m (h = "
          "{:.6g} m)",
          setup.probes.size(), probe_every_steps_, probes_->probes().column_count(),
          probes_->kernel_name(), probes_->kernel_support(), probes_->smoothing_length());
    }
  }

  // The LIGGGHTS-only equilibration in chunks (equilibration_chunk), rank 0 logging its progress
  // at most every kEquilibrationReportSeconds: a long settling is not a silent wait.
  void equilibrate(std::uint64_t steps) {
    constexpr double kEquilibrationReportSeconds = 10.0;
    const std::uint64_t chunk = equilibration_chunk(steps);
    last_balance_check_ = driver_->current_step();
    const auto start = std::chrono::steady_clock::now();
    auto last_report = start;
    for (std::uint64_t done = 0; done < steps;) {
      const std::uint64_t now_steps = std::min(chunk, steps - done);
      if (done == 0) {
        driver_->run_with_setup(now_steps);
      } else {
        driver_->run_continued(now_steps);
      }
      done += now_steps;
      if (done < steps) {
        maybe_rebalance(false);  // the fluid settles, a dam's column may move
        select_shares();         // the shares follow the particles
      }
      const auto now = std::chrono::steady_clock::now();
      if (!mpi_.root() || done == steps ||
          std::chrono::duration<double>(now - last_report).count() < kEquilibrationReportSeconds) {
        continue;
      }
      last_report = now;
      const double elapsed = std::chrono::duration<double>(now - start).count();
      const double rate = static_cast<double>(done) / elapsed;
      const auto left = static_cast<long>(static_cast<double>(steps - done) / rate);
      spdlog::info("equilibration: step {}/{} ({:.1f} %), {:.0f} steps/s, ETA {}:{:02}:{:02}", done,
                   steps, 100.0 * static_cast<double>(done) / static_cast<double>(steps), rate,
                   left / 3600, left / 60 % 60, left % 60);
    }
  }

  struct AppliedDrag {
    double rate = 0.0;           // [1/s]
    double column_height = 0.0;  // [m]
  };

  // The scene's choice of settling drag, made concrete (collective: all ranks call it).
  AppliedDrag settling_drag(const protocol::Settling& settling, const protocol::Setup& setup) {
    AppliedDrag drag;
    drag.column_height = settling.column_height;
    if (!(drag.column_height > 0.0)) {
      // The script made the particles: their extent along gravity plus one spacing, as the
      // server measures a lattice it generates.
      const FluidExtent extent = driver_->fluid_extent(settling.gravity);
      const double spacing =
          extent.mean_density > 0.0
              ? std::pow(extent.mean_mass / extent.mean_density, 1.0 / dimension_)
              : 0.0;
      drag.column_height = extent.count > 0 ? extent.height + spacing : 0.0;
    }
    if (setup.equilibration_steps == 0) return drag;
    if (settling.drag_rate >= 0.0) {
      drag.rate = settling.drag_rate;
      if (mpi_.root()) spdlog::info("settling drag {:.6g} 1/s (from the scene)", drag.rate);
      return drag;
    }
    const double gravity =
        std::hypot(settling.gravity[0], settling.gravity[1], settling.gravity[2]);
    const SettlingDrag automatic =
        automatic_settling_drag(drag.column_height, gravity, setup.time_step);
    drag.rate = automatic.rate;
    if (mpi_.root()) {
      spdlog::info(
          "settling drag {:.6g} 1/s: critical damping 2 pi sqrt(g/H) of a column of H = {:.6g} m "
          "under g = {:.6g} m/s^2{}",
          drag.rate, drag.column_height, gravity,
          automatic.limited_by_time_step ? ", bounded by the time step (0.1/dt)" : "");
    }
    return drag;
  }

  // Gathers the ranks' vertex forces onto the whole mesh (each rank sends its share's only) and
  // sums the diagnostics over all ranks; rank 0 sends them. The fluid's health (every step), on
  // probe steps the probes' partials, and whether a rank's particles near the edge of its share
  // travel in the same two reductions (no extra synchronisation of the ranks); rank 0 sends
  // FluidHealth and then ProbeValues right after the Forces.
  void send_forces(std::uint64_t step, double seconds_liggghts, double seconds_contact) {
    const bool probing = probes_ && step % probe_every_steps_ == 0;
    const probes::Partials* probe_partials = probing ? &probes_->partials(wall_samples()) : nullptr;
    if (probing) ++probe_evaluations_;
    const bool near_edge = distribution_->particles_near_edge(driver_->lammps());
    Stopwatch& communication = mpi_.mpi_time();
    communication.start();
    std::vector<double> vertex_forces = distribution_->gather_forces(boundary_->vertex_forces);
    const auto& diagnostics = boundary_->diagnostics;
    // Sums: force on fluid (3), on structure (3), magnitude sum, particles in range; then the
    // health's counts (particles, non-finite ones); then the probes' sums.
    constexpr std::size_t kDiagnostics = 8;
    std::vector<double> sums(kDiagnostics, 0.0);
    for (int k = 0; k < 3; ++k) {
      sums[k] = diagnostics.force_on_particles[k];
      sums[3 + k] = diagnostics.force_on_structure[k];
    }
    sums[6] = diagnostics.pair_force_magnitude_sum;
    sums[7] = static_cast<double>(diagnostics.particles_in_range);
    // Maxima: the closest approach as its negative (a minimum), whether this rank's particles
    // near the edge of its share; then the health's extremes (-min density, max density, max
    // speed squared); then the probes' maxima.
    std::vector<double> maxima{-diagnostics.closest_distance, near_edge ? 1.0 : 0.0};
    const bool report_health = health_agreed();
    if (report_health) {
      communication.stop();
      health_scan_.start();
      const LocalFluidHealth health = driver_->local_fluid_health();
      health_scan_.stop();
      communication.start();
      sums.push_back(static_cast<double>(driver_->local_particle_count()));
      sums.push_back(static_cast<double>(health.non_finite));
      maxima.insert(maxima.end(),
                    {-health.min_density, health.max_density, health.max_speed_squared});
    }
    const std::size_t first_probe_sum = sums.size();
    const std::size_t first_probe_maximum = maxima.size();
    if (probe_partials) {
      sums.insert(sums.end(), probe_partials->sums.begin(), probe_partials->sums.end());
      maxima.insert(maxima.end(), probe_partials->maxima.begin(), probe_partials->maxima.end());
    }
    std::vector<double> total(sums.size(), 0.0);
    MPI_Reduce(sums.data(), total.data(), static_cast<int>(sums.size()), MPI_DOUBLE, MPI_SUM, 0,
               mpi_.communicator());
    std::vector<double> maxima_total(maxima.size(), 0.0);
    MPI_Reduce(maxima.data(), maxima_total.data(), static_cast<int>(maxima.size()), MPI_DOUBLE,
               MPI_MAX, 0, mpi_.communicator());
    const double closest_total = -maxima_total[0];
    const std::uint64_t particles = driver_->particle_count();
    communication.stop();
    if (!mpi_.root()) return;
    if (maxima_total[1] > 0.0) distribution_->request_selection();

    protocol::Forces forces;
    forces.step = step;
    forces.forces = std::move(vertex_forces);
    auto& out = forces.diagnostics;
    for (int k = 0; k < 3; ++k) {
      out.force_on_fluid[k] = total[k];
      out.force_on_structure[k] = total[3 + k];
    }
    out.pair_force_magnitude_sum = total[6];
    out.particles_in_range = static_cast<std::uint64_t>(std::llround(total[7]));
    const double r0 = boundary_->law.equilibrium_distance;
    out.closest_approach_over_r0 = std::isfinite(closest_total) && r0 > 0.0
                                       ? closest_total / r0
                                       : std::numeric_limits<double>::infinity();
    out.particle_count = particles;
    out.seconds_liggghts = seconds_liggghts;
    out.seconds_contact = seconds_contact;
    out.seconds_client_communication = communication.seconds();  // since the previous Forces
    communication.reset();
    send(forces);
    if (report_health) {
      protocol::FluidHealth report;
      report.step = step;
      report.particle_count = static_cast<std::uint64_t>(std::llround(total[kDiagnostics]));
      report.non_finite_particles =
          static_cast<std::uint64_t>(std::llround(total[kDiagnostics + 1]));
      report.min_density = -maxima_total[2];
      report.max_density = maxima_total[3];
      report.max_speed = std::sqrt(maxima_total[4]);
      send(report);
    }
    if (probe_partials) {
      probes::Partials reduced;
      reduced.sums.assign(total.begin() + static_cast<long>(first_probe_sum), total.end());
      reduced.maxima.assign(maxima_total.begin() + static_cast<long>(first_probe_maximum),
                            maxima_total.end());
      send(protocol::ProbeValues{step, probes_->values(reduced)});
    }
  }

  // The wall forces at the sampling points of this rank's latest fix evaluation (recorded on the
  // steps whose probes read them; empty otherwise).
  // Their elements are named by their index in the whole mesh, as the probes name them.
  probes::WallSamples wall_samples() {
    const contact::WallSampleRecord& record = boundary_->samples;
    const std::span<const std::uint32_t> ids = distribution_->element_ids();
    sample_elements_.resize(record.elements.size());
    for (std::size_t s = 0; s < record.elements.size(); ++s)
      sample_elements_[s] = ids[record.elements[s]];
    return {record.count(),  record.positions, record.normals, record.forces,
            record.measures, sample_elements_, record.pairs};
  }

  bool health_agreed() const { return (capabilities_ & protocol::kCapabilityFluidHealth) != 0; }

  // What the per-step health scan costs, measured against the LIGGGHTS steps it accompanies.
  void log_health_scan_cost(std::uint64_t steps) const {
    if (!health_agreed() || steps == 0) return;
    spdlog::info(
        "fluid health scan: {:.3f} s over {} steps ({:.2f} us per step, {:.2f} % of the {:.2f} s "
        "of LIGGGHTS steps) on this rank",
        health_scan_.seconds(), steps, 1e6 * health_scan_.seconds() / static_cast<double>(steps),
        seconds_stepping_ > 0.0 ? 100.0 * health_scan_.seconds() / seconds_stepping_ : 0.0,
        seconds_stepping_);
  }

  void exchange_loop() {
    Stopwatch total;
    total.start();
    std::uint64_t steps = 0;
    while (true) {
      protocol::Message message = next_message();
      if (auto* step = std::get_if<protocol::Step>(&message)) {
        auto computing = busy();
        slow_step_for_tests(step->step);
        apply_step(*step);
        const SubstepTimes times = liggghts_step(step->step % probe_every_steps_ == 0);
        computing = {};
        send_forces(step->step, times.liggghts, times.contact);
        ++steps;
        maybe_rebalance(true);
      } else if (auto* motion = std::get_if<protocol::StepMotion>(&message)) {
        auto computing = busy();
        slow_step_for_tests(motion->step);
        const SubstepTimes times = take_step_motion(*motion);
        computing = {};
        send_forces(motion->step, times.liggghts, times.contact);
        steps += motion->substeps;
        maybe_rebalance(true);
      } else if (auto* placement = std::get_if<protocol::ProbePlacement>(&message)) {
        move_probes(*placement);
      } else if (auto* checkpoint = std::get_if<protocol::CheckpointRequest>(&message)) {
        auto writing = busy();
        write_checkpoint(*checkpoint);
      } else if (auto* request = std::get_if<protocol::SnapshotRequest>(&message)) {
        auto gathering = busy();
        Snapshot snapshot = driver_->gather_snapshot(dimension_);
        gathering = {};
        if (mpi_.root()) {
          protocol::Snapshot reply;
          reply.step = request->step;
          reply.time = last_time_;
          reply.dimension = static_cast<std::uint32_t>(dimension_);
          reply.ids = std::move(snapshot.ids);
          reply.positions = std::move(snapshot.positions);
          reply.velocities = std::move(snapshot.velocities);
          reply.density = std::move(snapshot.density);
          reply.pressure = std::move(snapshot.pressure);
          send(reply);
        }
      } else if (std::holds_alternative<protocol::Shutdown>(message)) {
        if (mpi_.root()) {
          protocol::Goodbye goodbye;
          goodbye.steps_done = steps;
          goodbye.seconds_total = total.stop();
          send(goodbye);
          spdlog::info("run finished after {} coupled steps", steps);
          if (probes_) {
            spdlog::info(
                "probes evaluated {} times in {:.3f} s over the particles of rank 0 (reduced "
                "with the forces)",
                probe_evaluations_, probes_->seconds_evaluating());
          }
        }
        log_health_scan_cost(steps);
        log_balance_summary();
        log_ghosts();
        log_boundary_share();
        if (const std::string shares = distribution_->summary(); mpi_.root())
          spdlog::info("{}", shares);
        log_peak_memory();
        return;
      } else if (auto* error = std::get_if<protocol::ErrorMessage>(&message)) {
        throw protocol::PeerReportedError(error->code, error->text,
                                          "fsi-server, during the coupled steps");
      } else {
        throw protocol::UnexpectedMessageError(
            "expected a Step, StepMotion, ProbePlacement, SnapshotRequest, CheckpointRequest or "
            "Shutdown message but "
            "received " +
                protocol::name(protocol::type_of(message)),
            "fsi-client, during the coupled steps",
            "use matching fsi-server and fsi-client releases");
      }
    }
  }

  struct SubstepTimes {
    double liggghts = 0.0;  // LIGGGHTS without our fix
    double contact = 0.0;   // our fix
  };

  // One LIGGGHTS step with the walls as they are; the fix records the forces at its sampling
  // points only for a step whose probes read them (`probe_step`).
  SubstepTimes liggghts_step(bool probe_step) {
    boundary_->samples.enabled = probe_step && probes_ && probes_->probes().needs_wall_samples();
    const double fix_before = boundary_->seconds_in_fix;
    Stopwatch liggghts;
    liggghts.start();
    driver_->step();
    seconds_stepping_ += liggghts.stop();
    const double contact = boundary_->seconds_in_fix - fix_before;
    return {liggghts.seconds() - contact, contact};
  }

  // Multi-rate coupling (1.5, docs/theory.md): `substeps` LIGGGHTS steps, the walls in substep j
  // at theta = j / substeps of the interpolant through the server's nodes (the last substep at
  // the last node exactly). Leaves in the boundary what send_forces reduces: this rank's vertex
  // forces and force sums averaged over the substeps (the impulse over the structure step
  // divided by its length) and the closest approach of all substeps.
  SubstepTimes take_step_motion(const protocol::StepMotion& motion) {
    const std::size_t values = boundary_->dynamic_vertex_count * dimension_;
    const std::string where = "StepMotion of step " + std::to_string(motion.step);
    if ((capabilities_ & protocol::kCapabilityMultiRate) == 0) {
      throw protocol::UnexpectedMessageError(
          "fsi-server sent a StepMotion, but multi-rate coupling was not agreed",
          "fsi-client, " + where, "use matching fsi-server and fsi-client releases");
    }
    if (motion.positions.size() != motion.nodes.size() * values) {
      throw Error("StepMotion message carries " +
                      std::to_string(motion.positions.size() / dimension_) +
                      " vertex values over " + std::to_string(motion.nodes.size()) +
                      " nodes, the mesh has " + std::to_string(boundary_->dynamic_vertex_count) +
                      " dynamic vertices",
                  where, "use matching server and client releases");
    }
    if (motion.time_step != time_step_) {
      driver_->set_time_step(motion.time_step);
      driver_->run_with_setup(0);
      time_step_ = motion.time_step;
    }
    const std::uint32_t k = motion.substeps;
    const double structure_step = static_cast<double>(k) * motion.time_step;
    std::vector<double> force_sum(values, 0.0);
    contact::ContactDiagnostics sums;
    sums.closest_distance = std::numeric_limits<double>::infinity();
    std::vector<double> positions(values), velocities(values);
    SubstepTimes times;
    for (std::uint32_t j = 1; j <= k; ++j) {
      const double theta = j == k ? 1.0 : static_cast<double>(j) / static_cast<double>(k);
      protocol::evaluate_step_motion(
          protocol::step_motion_weights(motion.nodes, structure_step, theta), motion.positions,
          motion.velocities, values, positions, velocities);
      std::copy(positions.begin(), positions.end(), boundary_->positions().begin());
      std::copy(velocities.begin(), velocities.end(), boundary_->velocities().begin());
      last_time_ = motion.time - static_cast<double>(k - j) * motion.time_step;
      // The probes read the wall forces of the last substep only.
      const SubstepTimes step = liggghts_step(j == k && motion.step % probe_every_steps_ == 0);
      times.liggghts += step.liggghts;
      times.contact += step.contact;
      for (std::size_t i = 0; i < values && i < boundary_->vertex_forces.size(); ++i)
        force_sum[i] += boundary_->vertex_forces[i];
      sums.merge(boundary_->diagnostics);
    }
    const double share = 1.0 / static_cast<double>(k);
    for (std::size_t i = 0; i < values && i < boundary_->vertex_forces.size(); ++i)
      boundary_->vertex_forces[i] = force_sum[i] * share;
    contact::ContactDiagnostics& average = boundary_->diagnostics;
    for (int c = 0; c < 3; ++c) {
      average.force_on_particles[c] = sums.force_on_particles[c] * share;
      average.force_on_structure[c] = sums.force_on_structure[c] * share;
    }
    average.pair_force_magnitude_sum = sums.pair_force_magnitude_sum * share;
    average.particles_in_range = sums.particles_in_range / k;
    average.closest_distance = sums.closest_distance;
    return times;
  }

  // The probes that move with a body, placed by the server for the step that follows (1.4).
  void move_probes(const protocol::ProbePlacement& placement) {
    const std::string where = "ProbePlacement of step " + std::to_string(placement.step);
    if ((capabilities_ & protocol::kCapabilityMovingProbes) == 0 || !probes_) {
      throw protocol::UnexpectedMessageError(
          "fsi-server placed probes that this session does not have (" +
              std::string(probes_ ? "moving probes were not agreed" : "no probes were set up") +
              ")",
          "fsi-client, " + where, "use matching fsi-server and fsi-client releases");
    }
    for (const protocol::PlacedProbe& placed : placement.probes) {
      try {
        probes_->move(placed.index, placed.parameters);
      } catch (const Error& error) {
        throw Error(error.fault(), where, error.remedy());
      }
    }
  }

  void apply_step(const protocol::Step& step) {
    const std::size_t values = boundary_->dynamic_vertex_count * dimension_;
    if (step.positions.size() != values || step.velocities.size() != values) {
      throw Error("Step message carries " + std::to_string(step.positions.size() / dimension_) +
                      " vertices, the mesh has " + std::to_string(boundary_->dynamic_vertex_count) +
                      " dynamic ones",
                  "step " + std::to_string(step.step), "use matching server and client releases");
    }
    std::copy(step.positions.begin(), step.positions.end(), boundary_->positions().begin());
    std::copy(step.velocities.begin(), step.velocities.end(), boundary_->velocities().begin());
    if (step.time_step != time_step_) {
      // A changed step size needs a run with set-up so that every fix uses it.
      driver_->set_time_step(step.time_step);
      driver_->run_with_setup(0);
      time_step_ = step.time_step;
    }
    last_time_ = step.time;
  }

  // Rank 0's sends on the channel, which the relay's watcher may use to report a fault.
  template <class Message>
  void send(const Message& message) {
    std::lock_guard lock(channel_mutex_);
    channel_->send(message);
  }

  MpiContext mpi_;
  ClientOptions options_;
  FaultRelay& relay_;
  std::unique_ptr<protocol::Channel> channel_;
  std::timed_mutex channel_mutex_;  // held by whichever thread of rank 0 uses channel_
  std::atomic<bool> told_server_{false};
  std::uint32_t capabilities_ = 0;                        // agreed in the handshake
  std::unique_ptr<protocol::HeartbeatSender> heartbeat_;  // rank 0
  protocol::HeartbeatSender::Busy setup_busy_;
  std::shared_ptr<contact::CouplingBoundary> boundary_;
  std::unique_ptr<LiggghtsDriver> driver_;
  std::unique_ptr<DistributedBoundary> distribution_;
  std::vector<std::uint32_t> sample_elements_;  // wall_samples(): whole-mesh element indices
  std::unique_ptr<FluidProbes> probes_;         // when the scene declares probes (protocol 1.3)
  std::uint64_t probe_every_steps_ = 1;
  std::uint64_t probe_evaluations_ = 0;
  double time_step_ = 0.0;
  double last_time_ = 0.0;
  Stopwatch health_scan_;          // the per-step health scans of this rank
  double seconds_stepping_ = 0.0;  // the coupled LIGGGHTS steps of this rank
  int dimension_ = 2;
  // The balance (docs/user-guide.md, "Ranks and balance").
  std::int64_t last_balance_check_ = 0;  // LIGGGHTS' step counter at the last maybe_rebalance()
  std::uint64_t rebalances_ = 0;
  double seconds_rebalancing_ = 0.0;
  double largest_imbalance_ = 1.0;
  double reached_imbalance_ = 1.0;  // by the last balance (set-up, move or checkpoint)
};

// One connection, set-up and run. A fault ends the whole MPI job (also with --persistent: the
// ranks may be stuck in different collective calls, so there is no common place to resume).
int run_one_session(MPI_Comm communicator, const ClientOptions& options, FaultRelay& relay,
                    int rank) {
  ClientSession session(communicator, options, relay);
  try {
    return session.run();
  } catch (const std::exception& failure) {
    // Whatever happened on this rank ends the whole job: the other ranks may wait in a
    // collective call forever otherwise.
    const std::string text = session.describe(failure);
    spdlog::error("fsi-client (rank {}): {}", rank, text);
    if (dynamic_cast<const protocol::ProtocolError*>(&failure) != nullptr) {
      if (const std::string heartbeats = session.heartbeat_summary(); !heartbeats.empty())
        spdlog::warn("fsi-client: {}", heartbeats);
    }
    spdlog::default_logger()->flush();
    g_exit_report.active = false;
    // Tell the server unless it reported the fault itself (docs/protocol.md §7); another rank
    // tells it through rank 0, which then ends the job.
    const auto code = dynamic_cast<const LiggghtsError*>(&failure) != nullptr
                          ? std::optional(protocol::ErrorCode::LiggghtsError)
                          : protocol::error_code_for(failure, protocol::ErrorCode::SetupFailed);
    if (rank == 0 && !code) {
      // The server reported the fault itself (it has given up on this run): nothing may answer
      // it, also not the watcher when MPI_Abort's SIGTERM reaches this rank (it did, 1 in 4
      // runs of integration_protocol_states, answering the server's Error with one).
      relay.set_handler({});
    } else if (rank == 0 && code) {
      session.report_failure(text, *code);
    } else if (code && relay.tell_root(static_cast<std::uint32_t>(*code), text)) {
      std::this_thread::sleep_for(std::chrono::seconds(15));  // rank 0 ends the job meanwhile
    }
    MPI_Abort(communicator, 1);
    return 1;
  }
}

extern "C" void on_termination_signal(int signal) {
  FaultRelay::note_termination_signal(signal);
}

}  // namespace

int run_client_session(MPI_Comm communicator, const ClientOptions& options) {
  int rank = 0;
  MPI_Comm_rank(communicator, &rank);
  int threading = MPI_THREAD_SINGLE;
  MPI_Query_thread(&threading);
  FaultRelay relay(communicator, threading == MPI_THREAD_MULTIPLE);
  int size = 1;
  MPI_Comm_size(communicator, &size);
  FaultRelay::install_crash_report(rank, size);
  if (rank == 0 && !relay.active()) {
    spdlog::warn(
        "this MPI provides no MPI_THREAD_MULTIPLE: a fault that a rank other than 0 sees ends the "
        "job with that rank's message on stderr only; fsi-server sees the connection close");
  }
  // mpirun ends every rank with SIGTERM when one crashed or aborted: rank 0's watcher tells the
  // server before the job ends.
  if (rank == 0 && relay.active()) std::signal(SIGTERM, on_termination_signal);
  for (int run = 1;; ++run) {
    const int status = run_one_session(communicator, options, relay, rank);
    if (!options.persistent) {
      // No watcher after this: a SIGTERM ends the process again.
      if (rank == 0 && relay.active()) std::signal(SIGTERM, SIG_DFL);
      return status;
    }
    if (rank == 0) {
      std::fprintf(stderr,
                   "fsi-client: run %d done; waiting for the next fsi-server at %s:%u "
                   "(--persistent; Ctrl-C ends)\n",
                   run, options.host.c_str(), static_cast<unsigned>(options.port));
      std::fflush(stderr);
    }
  }
}

}  // namespace fsi::client
