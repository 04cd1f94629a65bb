#pragma once
// The convergence test of the Newton iteration on the stage equations, independent of the
// tableau (internal; used by radau_iia.cpp for Radau IIA and Lobatto IIIA alike).
//
// Per iteration k the driver reports the scaled increment |dz_k| (<= 1: below the tolerance,
// RadauStageEquations::increment_norm), the residual |r_k| it was computed from, and whether that
// residual had reached its round-off floor (every row within a small multiple of the rounding of
// the terms it is summed from, RadauStageEquations::residual_at_floor). With Hairer & Wanner's
// rate estimate theta_k = |dz_k| / |dz_k-1| (Solving ODEs II, §IV.8) the verdict is
//   converged     |dz_k| <= 1;
//   at round-off  the residual had reached its floor and the increments stopped shrinking
//                 (theta_k >= 1/2): the iterate is as good as the arithmetic allows, and the
//                 increment is rounding amplified by the Newton matrix (near a singular
//                 configuration or with extreme mass ratios it stays above the tolerance however
//                 often Newton repeats it);
//   diverging     theta >= 1 in three consecutive iterations with a fresh Newton matrix while the
//                 residual grows above the prediction's and is not at its floor: only a smaller
//                 step helps;
//   continue      otherwise.
// Hairer & Wanner also accept when eta_k |dz_k| <= kappa (eta = theta / (1 - theta)); that test
// accepts one iteration earlier and, measured with kappa = 1 and 0.1, loosened five of the
// engine's acceptance tests (pendulum orders, car axis digits, a conical pendulum), so acceptance
// stays |dz_k| <= 1 and the rate only tells a stall from a divergence.
// A failed attempt is told apart as diverging, stalled at round-off (the increments stopped
// shrinking while the residual stopped falling, far below where it started: the tolerance is
// tighter than the arithmetic and the model's own noise allow; the tolerance that would pass is
// estimated from the stalled increments) or too slow for the iteration limit; the failure's
// advice follows from that.

#include <string>

namespace fsi::mbd::detail {

enum class NewtonVerdict { Continue, Converged, ConvergedAtRoundOff, Diverging };

// Why a Newton attempt failed, for the advice.
enum class NewtonFailureKind { Diverging, StalledAtRoundOff, TooSlow };

class NewtonConvergence {
 public:
  // `relative_tolerance` is the Newton option the scaled increment is measured against.
  explicit NewtonConvergence(double relative_tolerance) : relative_tolerance_(relative_tolerance) {}

  // Forgets the history: a new attempt from the prediction.
  void restart();

  // One iteration: the scaled increment, the residual |r_k|_inf the increment was solved from,
  // whether that residual was at its round-off floor, and whether the Newton matrix was fresh
  // (factorised at this attempt's current or a recent iterate, not kept from earlier steps).
  NewtonVerdict observe(double scaled_increment, double residual, bool residual_at_floor,
                        bool fresh_matrix);

  // Whether observe() would use residual_at_floor for this increment (the increments stopped
  // shrinking after at least one iteration): the floor costs a product with |J|, so the driver
  // evaluates it only then.
  bool floor_matters(double scaled_increment) const;

  // The last contraction rate theta_k (0 before the second iteration of a matrix).
  double contraction() const { return contraction_; }

  // After an attempt ended without convergence: what kind of failure it was ...
  NewtonFailureKind failure_kind() const;
  // ... the relative tolerance that the stalled increments would have met (a power of ten with
  // a factor 2 of margin; meaningful for StalledAtRoundOff) ...
  double reachable_relative_tolerance() const;
  // ... and what the user should change, in words.
  std::string advice(int max_iterations) const;

 private:
  double relative_tolerance_;
  int iterations_ = 0;
  double previous_increment_ = 0.0;
  double contraction_ = 0.0;
  int growing_in_a_row_ = 0;
  double previous_residual_ = 0.0;
  double first_residual_ = 0.0;
  double stall_increment_ = 0.0;  // the largest increment of the current stall
  double smallest_residual_ = 0.0;
  int stalled_in_a_row_ = 0;
  bool diverged_ = false;
};

}  // namespace fsi::mbd::detail
