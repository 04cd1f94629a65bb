#include "newton_convergence.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fsi/common/text.hpp"

namespace fsi::mbd::detail {
namespace {

// Increments shrinking by less than this factor per iteration are not converging usefully.
constexpr double kStalledContraction = 0.5;
// A residual that still falls by this factor per iteration is not stalled.
constexpr double kResidualProgress = 0.1;
// Iterations in a row that make a stall or a divergence.
constexpr int kStalledIterations = 2;
constexpr int kDivergingIterations = 3;
// How far the residual must have fallen from the prediction's for a stall to be round-off
// rather than an iteration stuck far from the solution.
constexpr double kRoundOffDrop = 1e-6;

// Three significant digits, and a power of ten for tolerances.
std::string number(double value) {
  return significant(value, 3);
}
std::string tolerance(double value) {
  char text[48];
  std::snprintf(text, sizeof text, "%.0e", value);
  return text;
}

}  // namespace

void NewtonConvergence::restart() {
  *this = NewtonConvergence(relative_tolerance_);
}

bool NewtonConvergence::floor_matters(double scaled_increment) const {
  return iterations_ >= 1 && scaled_increment > 1.0 &&
         scaled_increment >= kStalledContraction * previous_increment_;
}

NewtonVerdict NewtonConvergence::observe(double scaled_increment, double residual,
                                         bool residual_at_floor, bool fresh_matrix) {
  ++iterations_;
  if (iterations_ == 1) {
    first_residual_ = residual;
    smallest_residual_ = residual;
  } else {
    contraction_ = scaled_increment / previous_increment_;
    smallest_residual_ = std::min(smallest_residual_, residual);
    const bool not_shrinking = contraction_ >= kStalledContraction;
    const bool residual_stuck = residual >= kResidualProgress * previous_residual_;
    if (not_shrinking && residual_stuck) {
      stall_increment_ = stalled_in_a_row_ == 0 ? std::max(previous_increment_, scaled_increment)
                                                : std::max(stall_increment_, scaled_increment);
      ++stalled_in_a_row_;
    } else {
      stalled_in_a_row_ = 0;
    }
    // Rounding noise also grows now and then; divergence is growth beyond the prediction's
    // residual.
    const bool growing = contraction_ >= 1.0 && fresh_matrix && residual > previous_residual_ &&
                         residual > first_residual_ && !residual_at_floor;
    growing_in_a_row_ = growing ? growing_in_a_row_ + 1 : 0;
  }
  previous_increment_ = scaled_increment;
  previous_residual_ = residual;

  if (scaled_increment <= 1.0) return NewtonVerdict::Converged;
  // Only once the increments stopped shrinking: while they still contract, the next iteration is
  // cheaper than doubting it.
  if (residual_at_floor && iterations_ > 1 && contraction_ >= kStalledContraction) {
    return NewtonVerdict::ConvergedAtRoundOff;
  }
  if (growing_in_a_row_ >= kDivergingIterations) {
    diverged_ = true;
    return NewtonVerdict::Diverging;
  }
  return NewtonVerdict::Continue;
}

NewtonFailureKind NewtonConvergence::failure_kind() const {
  if (diverged_) return NewtonFailureKind::Diverging;
  if (stalled_in_a_row_ >= kStalledIterations &&
      smallest_residual_ <= kRoundOffDrop * first_residual_) {
    return NewtonFailureKind::StalledAtRoundOff;
  }
  return NewtonFailureKind::TooSlow;
}

double NewtonConvergence::reachable_relative_tolerance() const {
  // The weights of the scaled increment grow in proportion to the relative tolerance where it
  // dominates them, so the stalled increments pass at tolerance * (largest stalled increment).
  const double needed = 2.0 * relative_tolerance_ * std::max(stall_increment_, 1.0);
  return std::pow(10.0, std::ceil(std::log10(needed)));
}

std::string NewtonConvergence::advice(int max_iterations) const {
  const std::string consistency =
      "check that the constraints are consistent with each other and with the initial state, "
      "and that loads and force elements are finite";
  switch (failure_kind()) {
    case NewtonFailureKind::Diverging:
      return "the iteration diverges (contraction rate " + number(contraction_) +
             " >= 1 with a fresh Newton matrix): reduce the step size; " + consistency;
    case NewtonFailureKind::StalledAtRoundOff:
      return "the residual fell to round-off (" + number(first_residual_) + " -> " +
             number(smallest_residual_) + ") but the increments stalled at " +
             number(stall_increment_) + " times the tolerance (contraction rate " +
             number(contraction_) +
             "): the tolerance is tighter than the rounding of this model's equations allows at "
             "this step; "
             "loosen Newton.relative_tolerance to " +
             tolerance(reachable_relative_tolerance()) + " (now " + tolerance(relative_tolerance_) +
             "); do not reduce the step size, which raises the round-off of the increments "
             "(eps |q| / h)";
    case NewtonFailureKind::TooSlow:
      break;
  }
  std::string text = "reduce the step size, or raise Newton.max_iterations (now " +
                     std::to_string(max_iterations) + ")";
  if (iterations_ > 1 && contraction_ > 0.0 && contraction_ < 1.0 && previous_increment_ > 1.0) {
    // Hairer & Wanner: the increments shrink like theta^k.
    const double more = std::ceil(std::log(previous_increment_) / -std::log(contraction_) - 1e-9);
    text += " (contraction rate " + number(contraction_) + ": about " +
            std::to_string(static_cast<long long>(more)) + " more iterations)";
  }
  return text + "; " + consistency;
}

}  // namespace fsi::mbd::detail
