#include "fluid_decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "irregular.h"
#include "lammps.h"
#include "neighbor.h"

namespace fsi::client {
namespace {

// Bins per axis: the cuts land within 1/4096 of the fluid's extent of the exact quantile.
constexpr std::size_t kBins = 4096;

// The narrowest slab a cut may leave, as a fraction of the box: keeps every rank a sub-domain
// even where the balance would squeeze it to nothing (all particles on one plane).
constexpr double kMinSlabFraction = 1e-3;

double clamp_into_box(const LAMMPS_NS::Domain& domain, int axis, double value) {
  return std::clamp(value, domain.boxlo[axis], domain.boxhi[axis]);
}

// Bins `coordinate(i, axis)` of `count` particles over [lo, hi] per split axis.
template <class Coordinate>
std::array<AxisHistogram, 3> histograms(const LAMMPS_NS::Domain& domain, const ProcessorGrid& grid,
                                        const std::array<double, 3>& lo,
                                        const std::array<double, 3>& hi, std::size_t count,
                                        const Coordinate& coordinate) {
  std::array<AxisHistogram, 3> result;
  for (int axis = 0; axis < 3; ++axis) {
    if (grid[axis] < 2 || !(hi[axis] > lo[axis])) continue;
    AxisHistogram& histogram = result[axis];
    histogram.lo = lo[axis];
    histogram.hi = hi[axis];
    histogram.counts.assign(kBins, 0.0);
    const double scale = static_cast<double>(kBins) / (hi[axis] - lo[axis]);
    for (std::size_t i = 0; i < count; ++i) {
      const double x = clamp_into_box(domain, axis, coordinate(i, axis));
      const auto bin = static_cast<std::size_t>(
          std::clamp((x - lo[axis]) * scale, 0.0, static_cast<double>(kBins - 1)));
      histogram.counts[bin] += 1.0;
    }
  }
  return result;
}

DomainCuts cuts_from(const LAMMPS_NS::LAMMPS& lammps, const std::array<AxisHistogram, 3>& bins) {
  const auto& domain = *lammps.domain;
  const ProcessorGrid grid = processor_grid(lammps);
  DomainCuts cuts;
  for (int axis = 0; axis < 3; ++axis) {
    const double box = domain.boxhi[axis] - domain.boxlo[axis];
    cuts[axis] = grid[axis] < 2 ? uniform_cuts(grid[axis])
                                : balanced_cuts(bins[axis], domain.boxlo[axis], domain.boxhi[axis],
                                                grid[axis], kMinSlabFraction * box);
  }
  return cuts;
}

// This rank's count next to every other rank's, on every rank.
std::vector<std::uint64_t> gathered_counts(std::uint64_t local, MPI_Comm communicator) {
  int ranks = 1;
  MPI_Comm_size(communicator, &ranks);
  std::vector<std::uint64_t> counts(static_cast<std::size_t>(ranks), 0);
  MPI_Allgather(&local, 1, MPI_UINT64_T, counts.data(), 1, MPI_UINT64_T, communicator);
  return counts;
}

}  // namespace

ProcessorGrid processor_grid(const LAMMPS_NS::LAMMPS& lammps) {
  const auto& comm = *lammps.comm;
  return {comm.procgrid[0], comm.procgrid[1], comm.procgrid[2]};
}

DomainCuts current_cuts(const LAMMPS_NS::LAMMPS& lammps) {
  const auto& comm = *lammps.comm;
  const double* splits[3] = {comm.xsplit, comm.ysplit, comm.zsplit};
  DomainCuts cuts;
  for (int axis = 0; axis < 3; ++axis)
    cuts[axis].assign(splits[axis], splits[axis] + comm.procgrid[axis] + 1);
  return cuts;
}

DomainCuts balanced_cuts_of_particles(const LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator) {
  const auto& atom = *lammps.atom;
  const auto& domain = *lammps.domain;
  const auto count = static_cast<std::size_t>(atom.nlocal);
  // The particles' extent over all ranks: {-lo, hi} per axis in one reduction of maxima.
  double extent[6];
  for (int axis = 0; axis < 3; ++axis) {
    extent[2 * axis] = -std::numeric_limits<double>::infinity();
    extent[2 * axis + 1] = -std::numeric_limits<double>::infinity();
  }
  for (std::size_t i = 0; i < count; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const double x = clamp_into_box(domain, axis, atom.x[i][axis]);
      extent[2 * axis] = std::max(extent[2 * axis], -x);
      extent[2 * axis + 1] = std::max(extent[2 * axis + 1], x);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, extent, 6, MPI_DOUBLE, MPI_MAX, communicator);
  const std::array<double, 3> lo{-extent[0], -extent[2], -extent[4]};
  const std::array<double, 3> hi{extent[1], extent[3], extent[5]};
  const ProcessorGrid grid = processor_grid(lammps);
  std::array<AxisHistogram, 3> bins = histograms(
      domain, grid, lo, hi, count, [&](std::size_t i, int axis) { return atom.x[i][axis]; });
  for (AxisHistogram& histogram : bins) {
    if (histogram.counts.empty()) continue;
    MPI_Allreduce(MPI_IN_PLACE, histogram.counts.data(), static_cast<int>(histogram.counts.size()),
                  MPI_DOUBLE, MPI_SUM, communicator);
  }
  // Every rank took part in the same reductions; an axis without particles on any rank (the
  // extent stayed -inf..-inf) has no histogram on any rank either.
  return cuts_from(lammps, bins);
}

void apply_cuts(LAMMPS_NS::LAMMPS& lammps, const DomainCuts& cuts) {
  auto& comm = *lammps.comm;
  double* splits[3] = {comm.xsplit, comm.ysplit, comm.zsplit};
  bool even = true;
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<double> evenly = uniform_cuts(comm.procgrid[axis]);
    for (int j = 0; j <= comm.procgrid[axis]; ++j) {
      splits[axis][j] = cuts[axis][static_cast<std::size_t>(j)];
      even = even && std::abs(splits[axis][j] - evenly[static_cast<std::size_t>(j)]) < 1e-15;
    }
  }
  // LIGGGHTS' set-up computes the ghost exchange from the sub-domain size when the cuts are even,
  // from the cuts themselves (Comm::updown) when not.
  comm.uniform = even ? 1 : 0;
  lammps.domain->set_local_box();
}

void migrate_particles(LAMMPS_NS::LAMMPS& lammps) {
  lammps.domain->pbc();
  LAMMPS_NS::Irregular irregular(&lammps);
  irregular.migrate_atoms();
}

std::vector<std::uint64_t> particles_per_rank(const LAMMPS_NS::LAMMPS& lammps,
                                              MPI_Comm communicator) {
  return gathered_counts(static_cast<std::uint64_t>(lammps.atom->nlocal), communicator);
}

std::vector<std::uint64_t> ghosts_per_rank(const LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator) {
  return gathered_counts(static_cast<std::uint64_t>(lammps.atom->nghost), communicator);
}

double ghost_cutoff(const LAMMPS_NS::LAMMPS& lammps) {
  return lammps.neighbor->cutneighmax;
}

std::string cuts_text(const LAMMPS_NS::LAMMPS& lammps) {
  const DomainCuts cuts = current_cuts(lammps);
  const auto& domain = *lammps.domain;
  std::string text;
  const char* names = "xyz";
  for (int axis = 0; axis < 3; ++axis) {
    if (cuts[axis].size() < 3) continue;
    if (!text.empty()) text += "; ";
    text += names[axis];
    text += " at";
    for (std::size_t j = 1; j + 1 < cuts[axis].size(); ++j) {
      char value[32];
      std::snprintf(value, sizeof value, " %.6g",
                    domain.boxlo[axis] + cuts[axis][j] * (domain.boxhi[axis] - domain.boxlo[axis]));
      text += value;
    }
    text += " m";
  }
  return text.empty() ? "one sub-domain" : text;
}

}  // namespace fsi::client
