#pragma once
// Error-controlled adaptive step for Radau IIA / Lobatto IIIA when the multibody system runs
// alone (coupled runs use the fixed step of the fluid). The local error is estimated by step
// doubling: each step of size h is taken once whole and once as two halves; the two halves are
// the solution, and their difference from the whole step is the error estimate
//     err = weighted RMS of (dq_i / wq_i, dv_i / wv_i),
//     wq_i = rtol |q_i| + atol,   wv_i = rtol |v_i| + atol + 100 eps max|q| / h.
// The last term is the round-off floor of the velocities on the index-3 system: they carry the
// rounding eps |q| / h of the position rows (docs/theory.md), so without it a tight tolerance on
// a velocity near zero demands ever smaller steps and is never met (measured on the pendulum at
// rtol 1e-10: the step fell to 1e-12 s at t = 4.6e-5 s). The multipliers (O(h^(s-1)), index 3)
// are not tested. A step is accepted when err <= 1; the next step is
// h * min(max_growth, max(min_shrink, safety * err^(-1/(s+1)))): the local error of the
// velocities is O(h^(s+1)), the lower of q and v (q: O(h^(2s))). A trial whose Newton iteration
// fails counts as rejected and quarters h.

#include <cstdint>
#include <memory>

#include "fsi/mbd/integrator.hpp"

namespace fsi::mbd {

struct AdaptiveOptions {
  double relative_tolerance = 1e-6;
  double absolute_tolerance = 1e-8;
  double initial_step = 1e-3;  // [s]
  double min_step = 1e-12;     // [s]; below this the integration fails
  double max_step = 0.0;       // [s]; 0 = no limit
  double safety = 0.9;
  double max_growth = 4.0;
  double min_shrink = 0.2;
};

struct AdaptiveStatistics {
  std::uint64_t accepted = 0;
  std::uint64_t rejected = 0;         // by the error test or by Newton failure
  std::uint64_t newton_failures = 0;  // of those, trial steps whose Newton did not converge
  std::uint64_t radau_steps = 0;      // every Radau IIA step taken: 3 per trial (h, h/2, h/2)
  std::uint64_t newton_iterations = 0;
  std::uint64_t jacobian_evaluations = 0;
  std::uint64_t factorisations = 0;
};

class AdaptiveRadau {
 public:
  // Throws fsi::Error naming the option for invalid options.
  AdaptiveRadau(const RadauOptions& radau, const AdaptiveOptions& adaptive);
  ~AdaptiveRadau();
  AdaptiveRadau(AdaptiveRadau&&) noexcept;
  AdaptiveRadau& operator=(AdaptiveRadau&&) noexcept;

  // Integrates from state.time to end_time, landing on it exactly (the last step is shortened).
  // The step size carries over to the next call. Throws fsi::Error with the time reached if the
  // step falls below min_step; `state` is then the last accepted state.
  void advance(const ConstrainedSystem& system, State& state, double end_time);

  // Integrates `integrand` along the solution (fsi/mbd/integrand.hpp): every accepted step adds
  // the tableau's quadrature over its two half steps (the solution it keeps).
  void set_integrand(Integrand integrand);
  // The integrand's integral over the last advance(); size 0 without an integrand.
  const Eigen::VectorXd& last_advance_integral() const;

  double step_size() const;  // the next step size the controller proposes
  const AdaptiveStatistics& statistics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsi::mbd
