#pragma once
// The probes of protocol 1.3 on the client (docs/user-guide.md, "Probes"): fsi::probes evaluated
// over this rank's particles in LIGGGHTS, with LIGGGHTS' own SPH kernel and smoothing length,
// reduced over the ranks onto rank 0 together with the vertex forces (one reduction for both).

#include <mpi.h>

#include "fsi/common/stopwatch.hpp"

#include <string>
#include <vector>

#include "fsi/probes/evaluation.hpp"

namespace LAMMPS_NS {
class LAMMPS;
}

namespace fsi::client {

class FluidProbes {
 public:
  // The kernel and h are read from the pair style and `fix property/global sl` of the script's
  // set-up; `fluid_atom_type` is the type whose smoothing length counts. Throws fsi::Error when
  // the scripts define no SPH pair style or smoothing length.
  FluidProbes(LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator, probes::ProbeSet probes,
              int fluid_atom_type);

  const probes::ProbeSet& probes() const { return probes_; }
  // Places probe `index` anew (protocol 1.4, ProbePlacement; probes::ProbeSet::move).
  void move(std::size_t index, std::vector<double> parameters) {
    probes_.move(index, std::move(parameters));
  }
  double smoothing_length() const { return smoothing_length_; }
  double kernel_support() const { return kernel_.support; }
  const std::string& kernel_name() const { return kernel_name_; }

  // This rank's partials over its own particles and the wall forces at the sampling points of
  // this rank's latest fix fsi/sph evaluation (read by the wall-pressure probes only), to be
  // reduced element-wise onto rank 0 (sums with MPI_SUM, maxima with MPI_MAX).
  const probes::Partials& partials(const probes::WallSamples& wall);
  // The values of every column from the reduced partials (rank 0).
  std::vector<double> values(const probes::Partials& reduced) const {
    return probes_.values(reduced);
  }
  // Wall time of this rank in partials().
  double seconds_evaluating() const { return evaluating_.seconds(); }

 private:
  LAMMPS_NS::LAMMPS& lammps_;
  MPI_Comm communicator_;
  probes::ProbeSet probes_;
  probes::Kernel kernel_;
  double smoothing_length_ = 0.0;
  std::string kernel_name_;
  // Reused from one evaluation to the next.
  std::vector<double> positions_, velocities_, density_, pressure_, mass_;
  probes::Partials partials_;
  Stopwatch evaluating_;
};

}  // namespace fsi::client
