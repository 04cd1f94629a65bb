#pragma once
// The force predictor of multi-rate coupling (SolverOptions.Timeint.force_predictor = "linear";
// docs/theory.md, "Multi-rate coupling"). With k fluid steps per structure step the structure
// moves over [t(n-k), t(n)] under the average of the fluid forces of the previous k fluid steps,
// centred (k - 1) fluid steps earlier than the forces the k = 1 scheme would apply over the same
// interval. The predictor extrapolates the average linearly over that lag from the last two
// averages, k dt apart:
//   f_applied = f(n-k) + (k - 1)/k (f(n-k) - f(n-2k)).
// It is exact for forces that change linearly in time; for k = 1 it is the identity.

#include <span>
#include <vector>

#include "fsi/output/state_archive.hpp"

namespace fsi::coupling {

class ForcePredictor {
 public:
  explicit ForcePredictor(int substeps) : substeps_(substeps) {}

  // The force to apply for the next structure step, given this exchange's average. The first
  // average is returned as it is (there is no slope yet). The span stays valid until the next
  // call.
  std::span<const double> apply(std::span<const double> average);

  // Checkpoints: the last average (the slope's start), bit for bit.
  void save_state(output::StateWriter& out) const;
  void restore_state(output::StateReader& in);

 private:
  int substeps_;
  std::vector<double> previous_;
  std::vector<double> predicted_;
};

}  // namespace fsi::coupling
