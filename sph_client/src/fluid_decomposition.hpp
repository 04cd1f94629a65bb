#pragma once
// Balanced sub-domains for LIGGGHTS' ranks (docs/user-guide.md, "Ranks and balance"): the cuts
// between the ranks' sub-domains set so that each rank owns an equal share of the particles, and
// the particles moved to their new owners. LIGGGHTS 3.8 has no `balance` command; its Comm keeps
// fractional cuts (xsplit, ysplit, zsplit) and a `uniform` flag that its own set-up honours
// (ARCHITECTURE.md §13). The arithmetic is in decomposition.hpp.
//
// Collective over `communicator` (the one LIGGGHTS runs on) unless said otherwise.

#include <mpi.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "decomposition.hpp"

namespace LAMMPS_NS {
class LAMMPS;
}

namespace fsi::client {

// Fractional cuts along x, y and z (parts + 1 values each, as LIGGGHTS' xsplit).
using DomainCuts = std::array<std::vector<double>, 3>;

// The processor grid LIGGGHTS formed at create_box (not collective).
ProcessorGrid processor_grid(const LAMMPS_NS::LAMMPS& lammps);
// The cuts LIGGGHTS uses now (not collective).
DomainCuts current_cuts(const LAMMPS_NS::LAMMPS& lammps);

// Cuts that give every rank of the grid an equal share of the particles LIGGGHTS holds (their
// coordinates binned per axis, the bins summed over the ranks).
DomainCuts balanced_cuts_of_particles(const LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator);

// Makes `cuts` LIGGGHTS' decomposition (Comm's splits and this rank's sub-domain). The particles
// stay where they are: call migrate_particles() if there are any (not collective, but every rank
// must pass the same cuts).
void apply_cuts(LAMMPS_NS::LAMMPS& lammps, const DomainCuts& cuts);

// Moves every particle to the rank whose sub-domain holds it (periodic coordinates mapped into the
// box first, as LIGGGHTS' set-up would). Ghost particles and neighbour lists are gone: the next
// `run` must be one with set-up.
void migrate_particles(LAMMPS_NS::LAMMPS& lammps);

// Particles owned by each rank, on every rank.
std::vector<std::uint64_t> particles_per_rank(const LAMMPS_NS::LAMMPS& lammps,
                                              MPI_Comm communicator);

// Ghost particles held by each rank (copies of other ranks' particles within the neighbour
// cut-off of its sub-domain, and periodic images), on every rank.
std::vector<std::uint64_t> ghosts_per_rank(const LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator);

// The distance to which LIGGGHTS keeps ghosts: the largest pair cut-off plus the neighbour skin
// [m] (not collective; set by the latest run with set-up).
double ghost_cutoff(const LAMMPS_NS::LAMMPS& lammps);

// "x 0 0.3121 1" per split axis (those of more than one part), for the log (not collective).
std::string cuts_text(const LAMMPS_NS::LAMMPS& lammps);

}  // namespace fsi::client
