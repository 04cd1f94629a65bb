#pragma once
// The fluid's complete LIGGGHTS state as bytes, for coupled checkpoints (docs/user-guide.md,
// "Checkpoints and resume"): every particle's restart record (the atom style's own
// AtomVec::pack_restart, which includes the per-atom restart data of fixes such as `fix
// property/atom ... yes ...`), the step and the simulation time, and the counters of LIGGGHTS fixes
// that hold hidden state across steps (the Shepard filter's step counter).
//
// Bitwise continuation (measured, docs/validation.md "Checkpoints"): capture at step N, restore,
// then continue with a run WITH set-up. Done the same way in the running process (restore from its
// own bytes) and in a resumed one (same scripts, then restore), both continue bit for bit
// identically on the same number of ranks. restore_fluid_state enforces the set-up itself: the next
// `run`, even one with `pre no`, re-initialises and sets up (neighbour lists, ghosts, forces).
//
// Both functions are collective over `communicator`, the communicator LIGGGHTS runs on; every
// error is detected on all ranks together (they all throw the same error), and restore checks
// everything it can before it touches a particle, so a refused restore leaves the fluid as it was.

#include <mpi.h>

#include <string>
#include <string_view>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace fsi::client {

// The checkpoint format this code writes and reads (the first field after the magic bytes).
inline constexpr unsigned kFluidStateFormatVersion = 1;

// Gathers every particle's state on rank 0, sorted by atom tag, behind a header (format version,
// atom style, dimension, record count, step, simulation time, carried fixes, fix counters).
// Rank 0 returns the bytes, the other ranks an empty string. A particle that has left the box
// across a non-periodic face (which LIGGGHTS deletes as lost at its next re-neighbouring anyway)
// is left out and counted in the header. Nothing in LIGGGHTS changes.
// Throws Error (all ranks) if a fix holds per-atom state that the records do not carry.
std::string capture_fluid_state(LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator);

// Replaces every particle by the records of `bytes` (read on rank 0 only; broadcast here). Each
// rank deletes its particles and unpacks, in tag order, the records whose position lies in its
// sub-domain (periodic coordinates mapped into the box the way LIGGGHTS' set-up will). Restores
// the fixes' per-atom restart data, the particle count, the atom map, the step and simulation
// time, and the Shepard filter counters; forces the next run to set up.
// Throws Error (all ranks, nothing changed) on malformed bytes, another atom style or dimension,
// a record count that does not match, a record outside the box, fixes whose per-atom or hidden
// state differs from what was captured, or a step change with a time-dependent fix.
void restore_fluid_state(LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator, std::string_view bytes);

// The last step's rates that the next step's first half-kick uses: the force f and the density
// rate drho of every particle, by atom id. A set-up recomputes them from the state at the step's
// end, where the step computed them from its middle (the half-step velocities of the viscosity,
// the continuity equation), so a set-up in mid-run would move the run off its course (measured:
// 7e-6 of the largest speed on the coarse elastic plate per checkpoint). Captured with the state
// (rank 0 returns the bytes) and applied after the set-up that follows a restore, on the
// particles the restore placed; collective. apply_step_rates throws Error (all ranks) when the
// bytes do not fit the particles.
std::string capture_step_rates(LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator);
void apply_step_rates(LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator, std::string_view bytes);

// Rank 0's verdict to every rank (collective): when `rank0_problem` (read on rank 0 only) is not
// empty, every rank throws Error(rank0_problem, where, fix), so that a problem seen on rank 0 alone
// ends all ranks together.
void share_verdict(const std::string& rank0_problem, MPI_Comm communicator, const char* where,
                   const char* fix);

}  // namespace fsi::client
