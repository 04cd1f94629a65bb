#pragma once
// The fluid side over TCP: fsi-client (LIGGGHTS under MPI) as the peer of fsi::protocol
// (docs/protocol.md). Listens and accepts the client at set-up, then maps each FluidSide call to
// its messages: Setup, Mesh and Particles; Ready and Forces of step 0; Step and Forces;
// SnapshotRequest and Snapshot; Shutdown and Goodbye; Error.

#include <memory>

#include "fsi/coupling/fluid_side.hpp"
#include "fsi/coupling/session.hpp"

namespace fsi::protocol {
class Channel;
class HeartbeatSender;
}  // namespace fsi::protocol

namespace fsi::coupling {

class TcpFluidSide final : public FluidSide {
 public:
  explicit TcpFluidSide(const ServerOptions& options);
  ~TcpFluidSide() override;

  void set_up(const scene::Scene& scene, const std::vector<double>& boundary_positions,
              const std::vector<double>& boundary_velocities) override;
  FluidReady equilibrate() override;
  std::string checkpoint(std::uint64_t step) override;
  bool can_checkpoint() const override {
    return (capabilities_ & protocol::kCapabilityCheckpoint) != 0;
  }
  bool peer_lost(const std::exception& failure) const override;
  FluidReady resume(const scene::Scene& scene, const std::vector<double>& boundary_positions,
                    const std::vector<double>& boundary_velocities, std::uint64_t step, double time,
                    std::string_view fluid_state) override;
  FluidForces exchange(const BoundaryMotion& motion) override;
  ParticleSnapshot snapshot(std::uint64_t step) override;
  void finish() override;
  void report_fault(const std::exception& failure, bool during_coupled_steps) noexcept override;
  std::unique_ptr<WaitScope> waiting() override;
  std::optional<FluidPeer> peer() const override;

 private:
  // Connects, refuses a client that lacks what the scene needs, sends Setup and Mesh.
  void send_setup_and_mesh(const scene::Scene& scene, const std::vector<double>& positions,
                           const std::vector<double>& velocities);
  // The scene's particles (a new run's, and a resumed run's before its Resume).
  void send_particles(const scene::Scene& scene);
  // The client's Ready after its set-up (and equilibration): waited for as long as the client
  // sends heartbeats.
  protocol::Ready expect_ready();
  void connect();
  FluidForces expect_forces(std::uint64_t step);
  bool settling_agreed() const { return (capabilities_ & protocol::kCapabilitySettling) != 0; }
  bool probes_agreed() const { return (capabilities_ & protocol::kCapabilityProbes) != 0; }
  // Refuses a client that lacks what the scene needs (probes, moving probes, multi-rate).
  void refuse_client_lacking(const scene::Scene& scene) const;
  void send_probes(const scene::Scene& scene);

  ServerOptions options_;
  std::uint16_t bound_port_ = 0;  // the port of the first connection; later ones come there
  std::unique_ptr<protocol::Channel> channel_;
  std::optional<protocol::Hello> client_;
  std::uint32_t capabilities_ = 0;
  std::unique_ptr<protocol::HeartbeatSender> heartbeat_;
  // Steps after which ProbeValues follow the Forces: multiples of probe_every_steps_, when the
  // scene has probes.
  bool probes_expected_ = false;
  std::uint64_t probe_every_steps_ = 1;
};

}  // namespace fsi::coupling
