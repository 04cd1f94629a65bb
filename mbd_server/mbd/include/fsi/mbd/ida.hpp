#pragma once
// SUNDIALS IDA (variable-order, variable-step BDF, orders 1-5; linked as IDAS, IDA with
// quadratures, for the integrands) as the alternative integrator of a ConstrainedSystem
// (fsi::mbd::Model), for runs of the multibody system alone. The constraints
// are posed in the stabilised index-2 form of Gear, Gupta and Leimkuhler (position and velocity
// level both enforced, the multipliers excluded from the error test); the Newton matrix is the
// model's analytic Jacobian, factorised by SUNDIALS' dense LU. Formulation and why: docs/theory.md;
// the equations: src/ggl_equations.hpp.
//
// The SUNDIALS types stay in the source file: this header needs only Eigen and the model.

#include <cstdint>
#include <memory>

#include "fsi/mbd/constrained_system.hpp"
#include "fsi/mbd/integrand.hpp"

namespace fsi::mbd {

struct IdaOptions {
  // Local error test on q and v: |e_i| <= relative_tolerance |y_i| + absolute_tolerance
  // (weighted RMS norm, SUNDIALS' convention).
  double relative_tolerance = 1e-8;
  double absolute_tolerance = 1e-10;
  int max_order = 5;                 // 1 ... 5
  std::int64_t max_steps = 1000000;  // per advance() call
  double max_step = 0.0;             // [s]; 0 = no limit
  double initial_step = 0.0;         // [s]; 0 = IDA's estimate
};

struct IdaStatistics {
  std::uint64_t steps = 0;
  std::uint64_t newton_iterations = 0;
  std::uint64_t jacobian_evaluations = 0;  // = factorisations (dense LU per Jacobian)
  std::uint64_t residual_evaluations = 0;
  std::uint64_t error_test_failures = 0;
  std::uint64_t convergence_failures = 0;
  std::uint64_t initialisations = 0;  // (re)starts from a consistent state
};

class IdaIntegrator {
 public:
  // Throws fsi::Error naming the option for invalid options.
  explicit IdaIntegrator(const IdaOptions& options = {});
  ~IdaIntegrator();
  IdaIntegrator(IdaIntegrator&&) noexcept;
  IdaIntegrator& operator=(IdaIntegrator&&) noexcept;

  // Integrates `state` from state.time to end_time (> state.time), landing on end_time exactly.
  // IDA keeps its history between calls as long as `state` is the one it returned, the model is
  // the same and its point loads have not changed; otherwise it restarts from `state` with
  // multipliers and accelerations made consistent ([M G^T; G 0] [a; lambda] = [F; -remainder]).
  // Throws fsi::Error naming the time reached, IDA's reason, its last step and the variable with
  // the largest weighted local error (with the user's laws on its equation) on failure; `state` is
  // then left unchanged.
  // A constraint row released before end_time (ConstrainedSystem::release_within) stops IDA at
  // its release time, from where it restarts with the row's multiplier zero.
  void advance(const ConstrainedSystem& system, State& state, double end_time);

  // Integrates `integrand` along the solution (fsi/mbd/integrand.hpp) by IDAS' quadrature over
  // IDA's own steps (not error-tested: the steps are the motion's). Takes effect at the next
  // advance(), which restarts IDA.
  void set_integrand(Integrand integrand);
  // The integrand's integral over the last advance(); size 0 without an integrand.
  const Eigen::VectorXd& last_advance_integral() const;

  // Forgets the history: the next advance() restarts.
  void reset();

  const IdaOptions& options() const;
  // Totals since construction.
  IdaStatistics statistics() const;

 private:
  void advance_without_release(const ConstrainedSystem& system, State& state, double end_time);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsi::mbd
