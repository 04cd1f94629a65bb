#pragma once
// The evaluation of probes over a set of particles, pure C++ (no LIGGGHTS, no MPI): each rank
// computes partial values over the particles it owns, the partials are reduced over the ranks
// (element-wise sums and maxima: MPI_Reduce with MPI_SUM and MPI_MAX), and the reduced partials
// give the values of sensors.csv. docs/user-guide.md, "Probes", states each kind's rule.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "fsi/probes/probe.hpp"

namespace fsi::probes {

// The particles of one rank. The first `owned` entries are the rank's own; the ones after them
// are ghosts (copies of neighbouring ranks' particles), which count only as neighbours (front),
// so that every particle is summed exactly once over the ranks.
struct ParticleSet {
  std::size_t owned = 0;
  std::span<const double> positions;   // dimension values per particle, owned and ghosts
  std::span<const double> velocities;  // dimension values per owned particle
  std::span<const double> density;     // one per owned particle [kg/m^3]
  std::span<const double> pressure;    // one per owned particle [Pa]
  std::span<const double> mass;        // one per owned particle [kg; 2D kg/m]
};

// The force of the fluid on the boundary mesh at the sampling points of the wall law (fix
// fsi/sph's quadrature points, thesis eq. 4.2) on one rank: what the wall-pressure probes read.
// Every rank holds every sampling point, with the force of the particles it owns, so that the
// forces sum over the ranks to the total. `dimension` values per sample in positions, normals,
// forces.
struct WallSamples {
  std::size_t count = 0;
  std::span<const double> positions;  // [m]
  std::span<const double> normals;    // unit normal of the sample's element (either orientation)
  std::span<const double> forces;     // force of the fluid on the wall [N; 2D N/m]
  std::span<const double> measures;   // length (2D) or area (3D) the sample stands for [m; m^2]
  std::span<const std::uint32_t> elements;  // the sample's element in the boundary mesh
  std::span<const std::uint32_t> pairs;     // particles within the wall law's range
};

// The SPH kernel W(r) [1/m^dimension] the fluid uses and its support radius [m] (W = 0 beyond).
struct Kernel {
  double support = 0.0;
  std::function<double(double distance)> value;
};

// Partial values of a probe set on one rank, to be reduced element-wise over the ranks.
struct Partials {
  std::vector<double> sums;
  std::vector<double> maxima;
};

class ProbeSet {
 public:
  // Throws fsi::Error naming the first definition that does not fit its kind (or a front probe
  // without a particle spacing in the context).
  ProbeSet(std::vector<ProbeDefinition> probes, ProbeContext context);

  const std::vector<ProbeDefinition>& probes() const { return probes_; }
  const ProbeContext& context() const { return context_; }
  // Every column of every probe, in order (the values below follow it).
  std::vector<Column> columns() const;
  std::size_t column_count() const { return column_count_; }

  // Gives probe `index` the parameters `parameters` (protocol 1.4, ProbePlacement: a probe that
  // moves with a body, placed where the body is): of the same count, fitting the kind, with the
  // same partials and columns. Throws fsi::Error naming what does not fit; the probe keeps its
  // parameters then.
  void move(std::size_t index, std::vector<double> parameters);

  // This rank's partials; the same sizes on every rank. `wall` is read by the wall-pressure
  // probes only (needs_wall_samples()).
  Partials partials(const ParticleSet& particles, const Kernel& kernel,
                    const WallSamples& wall = {}) const;
  // Does a probe of the set read the wall's sampling points?
  bool needs_wall_samples() const;
  // Empty when every probe that reads the wall finds sampling points in its patch; otherwise
  // one line per probe whose patch holds none (fsi-client checks the first evaluation with it).
  std::string wall_problems(const WallSamples& wall) const;
  // The probes' values from the partials reduced over all ranks, one per column.
  std::vector<double> values(const Partials& reduced) const;

 private:
  struct Slots {
    std::size_t first_sum = 0, sums = 0, first_maximum = 0, maxima = 0, first_column = 0,
                columns = 0;
  };
  std::vector<ProbeDefinition> probes_;
  ProbeContext context_;
  std::vector<Slots> slots_;
  std::size_t sum_count_ = 0, maximum_count_ = 0, column_count_ = 0;
};

}  // namespace fsi::probes
