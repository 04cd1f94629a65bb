#include "fsi/coupling/force_predictor.hpp"

namespace fsi::coupling {

std::span<const double> ForcePredictor::apply(std::span<const double> average) {
  if (previous_.size() != average.size()) {
    previous_.assign(average.begin(), average.end());
    return previous_;
  }
  const double k = static_cast<double>(substeps_);
  const double lead = (k - 1.0) / k;
  predicted_.resize(average.size());
  for (std::size_t i = 0; i < average.size(); ++i)
    predicted_[i] = average[i] + lead * (average[i] - previous_[i]);
  previous_.assign(average.begin(), average.end());
  return predicted_;
}

void ForcePredictor::save_state(output::StateWriter& out) const {
  out.section("force predictor");
  out.put(previous_);
}

void ForcePredictor::restore_state(output::StateReader& in) {
  in.section("force predictor");
  previous_ = in.doubles("previous average force");
}

}  // namespace fsi::coupling
