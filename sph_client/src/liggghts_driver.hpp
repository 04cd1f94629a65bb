#pragma once
// Drives one LIGGGHTS instance (a library, on all ranks of a communicator) for the coupling:
// variables, scripts fed line by line with `fix fsi/sph` intercepted (ARCHITECTURE.md §3),
// particle insertion from server data, stepping, and gathering of particle snapshots.
// Every method is collective: all ranks call it with the same arguments.

#include <mpi.h>

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "decomposition.hpp"
#include "fsi/contact/liggghts_fix.hpp"
#include "output_capture.hpp"

namespace LAMMPS_NS {
class LAMMPS;
}

namespace fsi::client {

struct DriverOptions {
  std::string log_file;      // LIGGGHTS log file; empty: none
  bool echo_output = false;  // echo LIGGGHTS' screen output to stdout (rank 0)
  // Run script commands the command policy refuses (`shell`, files outside the run directory).
  bool allow_unsafe_commands = false;
};

struct ParticleBlock {
  int dimension = 2;
  int atom_type = 1;
  double mass = 0.0;
  double density = 0.0;
  std::vector<double> densities;   // one per particle (a hydrostatic start); empty: all density
  std::vector<double> positions;   // dimension per particle
  std::vector<double> velocities;  // dimension per particle
};

// The fluid's mass and energies, summed over all particles and ranks (2D: per unit depth).
struct FluidEnergies {
  double mass = 0.0;
  double kinetic = 0.0;    // sum of m v^2 / 2
  double potential = 0.0;  // sum of m |g| (height above the lowest particle), heights along -g
};

// The particles' extent and mean properties, over all ranks.
struct FluidExtent {
  std::uint64_t count = 0;
  double height = 0.0;  // highest minus lowest particle along -g (0 without gravity)
  double mean_mass = 0.0;
  double mean_density = 0.0;
};

// The health of this rank's particles (not reduced): the extremes over the particles whose
// position, velocity and density are all finite, and how many are not.
struct LocalFluidHealth {
  std::uint64_t non_finite = 0;
  double min_density = std::numeric_limits<double>::infinity();
  double max_density = -std::numeric_limits<double>::infinity();
  double max_speed_squared = 0.0;
};

struct Snapshot {
  std::vector<std::uint64_t> ids;
  std::vector<double> positions, velocities, density, pressure;  // gathered on rank 0 only
};

// Where the driver is in the scripts, for messages about LIGGGHTS errors.
struct ScriptPosition {
  std::string script;
  int line = 0;
  std::string command;
};

class LiggghtsDriver {
 public:
  LiggghtsDriver(MPI_Comm communicator, const DriverOptions& options,
                 std::shared_ptr<contact::CouplingBoundary> boundary);
  ~LiggghtsDriver();
  LiggghtsDriver(const LiggghtsDriver&) = delete;
  LiggghtsDriver& operator=(const LiggghtsDriver&) = delete;

  // Defines `variable NAME string VALUE` for each pair (values arrive as exact text).
  void define_variables(std::span<const std::pair<std::string, std::string>> variables);
  // Executes a script line by line; `&` continues a line; `fix ... fsi/sph ...` is created by us.
  // after_create_box runs right after the script's create_box command (where the client inserts
  // the server's particles: fixes and `set` commands later in the script then see them).
  // Throws fsi::Error naming script:line for problems we detect before LIGGGHTS does.
  void run_script(const std::string& name, const std::string& text,
                  const std::function<void()>& after_create_box = {});
  // The processor grid a script gets right before its create_box when it has no `processors`
  // command of its own (docs/user-guide.md, "Ranks and balance"); unset: LIGGGHTS' default grid.
  void set_automatic_grid(std::optional<ProcessorGrid> grid) {
    automatic_grid_ = grid;
    script_chose_grid_ = false;
  }
  // Whether the script that created the box named its processor grid itself.
  bool script_chose_grid() const { return script_chose_grid_; }
  // Executes one LIGGGHTS command.
  void command(const std::string& line);
  // Creates the particles on the ranks owning their positions, sets per-type mass and density.
  void insert_particles(const ParticleBlock& particles);

  void set_time_step(double time_step);
  double time_step() const;
  // LIGGGHTS' step counter (restored with a checkpoint's fluid).
  std::int64_t current_step() const;
  // A run with set-up: re-initialises styles and fixes (needed after changed settings, and for a
  // newly added fix), evaluates forces at the current state.
  void run_with_setup(std::uint64_t steps);
  // Continues the last run by `steps` steps without set-up (nothing changed since).
  void run_continued(std::uint64_t steps);
  // The coupled step: one LIGGGHTS step without set-up. Steps in a row form one LIGGGHTS run
  // (Integrate::run(1) each), without the per-run bookkeeping of a `run 1 pre no post no` (output
  // set-up with a thermo evaluation, timer barriers, the run's summary): 0.16-0.35 ms per step on
  // the thesis tank, 2-5 % (docs/performance.md). The run ends at the next command, which every
  // other member function issues, so a `thermo N` or `dump ... N` of the scripts fires every N
  // steps, as in a plain LIGGGHTS run.
  void step();

  FluidExtent fluid_extent(const std::array<double, 3>& gravity) const;
  FluidEnergies fluid_energies(const std::array<double, 3>& gravity) const;
  // A velocity drag -rate m v on every particle (LIGGGHTS fix viscous, scaled by each type's
  // mass), until remove_velocity_drag(); takes effect at the next run with set-up.
  void add_velocity_drag(double rate);
  void remove_velocity_drag();

  std::uint64_t particle_count() const;
  // Particles owned by this rank.
  std::uint64_t local_particle_count() const;
  bool has_fsi_fix() const { return fsi_fix_count_ > 0; }
  // This rank's particles only (not collective): one pass over them, for the per-step health
  // report (docs/protocol.md, FluidHealth).
  LocalFluidHealth local_fluid_health() const;
  // Gathers id, position, velocity, density and pressure of every particle on rank 0, sorted by id.
  Snapshot gather_snapshot(int dimension) const;

  const OutputCapture& output() const { return *capture_; }
  const ScriptPosition& position() const { return position_; }
  LAMMPS_NS::LAMMPS& lammps() { return *lammps_; }

 private:
  std::vector<std::string> substituted_words(const std::string& line);
  // The run that step() continues: LIGGGHTS' Run::command with `pre no` up to its loop, and after
  // it (Verlet::cleanup; the update's run bounds cleared).
  void begin_steps();
  void end_steps();

  MPI_Comm communicator_;
  DriverOptions options_;
  int rank_ = 0;
  std::unique_ptr<OutputCapture> capture_;
  LAMMPS_NS::LAMMPS* lammps_ = nullptr;
  std::shared_ptr<contact::CouplingBoundary> boundary_;
  int fsi_fix_count_ = 0;
  ScriptPosition position_;
  std::optional<ProcessorGrid> automatic_grid_;
  bool script_chose_grid_ = false;
  bool stepping_ = false;  // inside the run of step()s (it ends at update->laststep)
};

}  // namespace fsi::client
