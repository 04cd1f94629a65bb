#pragma once
// The fluid as the coupling loop sees it (thesis §4.4, Fig. 4.10): set it up around the
// structure's boundary, let it settle, then per step hand it the boundary's motion over dt and
// take back the forces on the dynamic vertices. The loop knows nothing of how the fluid is
// computed: TcpFluidSide (tcp_fluid_side.hpp) drives fsi-client over fsi::protocol, the unit
// tests of the loop use an in-process fake.

#include <cstdint>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/coupling/output.hpp"
#include "fsi/protocol/messages.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::coupling {

// Forces of the fluid on the dynamic boundary vertices (dimension values each, in the mesh's
// vertex order) and the fluid's account of that exchange.
struct FluidForces {
  std::vector<double> forces;
  protocol::ForceDiagnostics diagnostics;
  // The scene's probes at the end of the step, one value per column (fsi::probes::columns):
  // at every sensor step of a scene with probes, empty otherwise.
  std::vector<double> probe_values;
  // The state of every particle at the same time (protocol 1.3); absent when the fluid side does
  // not report it (a client of protocol 1.2).
  std::optional<protocol::FluidHealth> health;
};

// Where the dynamic boundary vertices are at the end of a step, and, on a probe step, the probes
// that move with a body.
struct BoundaryMotion {
  std::uint64_t step = 0;
  double time = 0.0;  // end of the step
  double time_step = 0.0;
  std::vector<double> positions;   // dynamic vertices only, dimension values each
  std::vector<double> velocities;  // as positions
  // Scene::attached_probes placed at the end of the step (index into Scene::probes, parameters);
  // empty on other steps and in scenes without them.
  std::vector<protocol::PlacedProbe> probe_placements;
  // Multi-rate coupling (SolverOptions.Timeint.substeps > 1, docs/theory.md): the fluid takes
  // `substeps` steps of time_step up to `time`, the walls moving on the interpolant
  // (fsi/protocol/step_motion.hpp) through the dynamic vertices at the structure step's nodes
  // (theta in [0, 1], the last 1; node-major, dimension values per vertex). positions and
  // velocities above are the last node's. Empty with substeps = 1.
  std::uint32_t substeps = 1;
  std::vector<double> nodes;
  std::vector<double> node_positions;
  std::vector<double> node_velocities;
};

// The fluid after its set-up and equilibration, with its forces on the initial configuration.
struct FluidReady {
  std::uint64_t particle_count = 0;
  std::string liggghts_version;
  double seconds_setup = 0.0;
  double seconds_equilibration = 0.0;
  FluidForces initial_forces;
  // The fluid at release, for the check that it is at rest; absent when the fluid side does not
  // take part in the settling (a client of protocol 1.1).
  std::optional<protocol::ReleaseState> release;
};

// Who computed the fluid, for run.json; a fluid side without a remote peer has none.
struct FluidPeer {
  std::uint32_t capabilities = 0;  // agreed in the handshake
  bool authenticated = false;
  std::string software_version;
  std::string host;
  std::uint32_t mpi_ranks = 1;
};

class FluidSide {
 public:
  virtual ~FluidSide() = default;

  // Sends everything the fluid needs before it can settle: the scene's fluid and scripts, and
  // the whole boundary (static vertices included, all dimension values each) at t = 0.
  virtual void set_up(const scene::Scene& scene, const std::vector<double>& boundary_positions,
                      const std::vector<double>& boundary_velocities) = 0;
  // Waits until the fluid has settled around the initial configuration.
  virtual FluidReady equilibrate() = 0;
  // One coupled step: the fluid advances over motion.time_step with the walls at `motion`.
  virtual FluidForces exchange(const BoundaryMotion& motion) = 0;
  // Every particle at the end of `step`.
  virtual ParticleSnapshot snapshot(std::uint64_t step) = 0;
  // Checkpoints (issue 16; docs/user-guide.md, "Checkpoints and resume"): the fluid's complete
  // state at the end of the exchange of `step`, as bytes only the fluid side reads back
  // (resume()). The fluid then goes on from exactly the state a resume from these bytes starts
  // in, so a resumed run continues bit for bit. Throws fsi::Error when the fluid side cannot
  // (the default: a fluid side without checkpoints).
  virtual std::string checkpoint(std::uint64_t step);
  // Whether checkpoint() and resume() work (a client of protocol 1.6 or later).
  virtual bool can_checkpoint() const { return false; }
  // Whether `failure` means the fluid's process is gone (its connection closed or silent, its
  // job ended from outside) rather than a fault it would meet again (a script error): then a
  // run with a reconnect timeout rolls back and calls resume() again, which waits for a new one.
  virtual bool peer_lost(const std::exception& /*failure*/) const { return false; }
  // A resumed run, in place of set_up() and equilibrate(): sets the fluid up from a checkpoint's
  // bytes around the whole boundary (static vertices included) at the checkpoint's `step` and
  // `time`. The returned Ready's initial forces and release are not used. Throws fsi::Error
  // when the fluid side cannot (the default).
  virtual FluidReady resume(const scene::Scene& scene,
                            const std::vector<double>& boundary_positions,
                            const std::vector<double>& boundary_velocities, std::uint64_t step,
                            double time, std::string_view fluid_state);

  // The end time is reached: the fluid side closes its resources in good order.
  virtual void finish() = 0;
  // The run ends because of `failure` (during_coupled_steps: after equilibration). Never throws:
  // it is called while the run is already failing.
  virtual void report_fault(const std::exception& failure, bool during_coupled_steps) noexcept = 0;

  // While the structure computes (or the server writes output) the fluid side waits; a remote
  // one may keep its peer informed meanwhile (heartbeats). Ends when the returned scope does.
  class WaitScope {
   public:
    virtual ~WaitScope() = default;
  };
  [[nodiscard]] virtual std::unique_ptr<WaitScope> waiting() { return nullptr; }

  virtual std::optional<FluidPeer> peer() const { return std::nullopt; }
};

}  // namespace fsi::coupling
