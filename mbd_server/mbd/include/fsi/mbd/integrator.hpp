#pragma once
// Implicit Runge-Kutta integration of the constrained equations of motion (thesis §2.1.3.3).
// Radau IIA with s = 1, 2, 3 stages (orders 1, 3, 5; stiffly accurate, L-stable) on the
// index-3 DAE, solved by (modified) Newton iterations with dense LU, structured as named stages:
// initialise, predict, Newton increment, accept/reject, finalise.

#include <Eigen/Dense>

#include <cstdint>
#include <memory>

#include "fsi/mbd/model.hpp"

namespace fsi::mbd {

struct ButcherTableau {
  Eigen::MatrixXd a;
  Eigen::VectorXd b;
  Eigen::VectorXd c;
  int order = 0;
};

// Radau IIA tableau with 1, 2 or 3 stages; throws fsi::Error otherwise.
ButcherTableau radau_iia(int stages);

struct NewtonOptions {
  double relative_tolerance = 1e-10;  // on the Newton increment, relative to the stage values
  int max_iterations = 12;
  // Reuse of a factorised Jacobian across steps (HOTINT's max_modified_newton_steps):
  // 0 = full Newton (new Jacobian every iteration).
  int max_modified_newton_steps = 20;
  // A contraction rate above this triggers a fresh Jacobian.
  double max_contraction = 0.5;
};

struct StepStatistics {
  int newton_iterations = 0;
  int jacobian_evaluations = 0;
  int factorisations = 0;
};

struct IntegratorStatistics {
  std::uint64_t steps = 0;
  std::uint64_t newton_iterations = 0;
  std::uint64_t jacobian_evaluations = 0;
  std::uint64_t factorisations = 0;
  void add(const StepStatistics& step);
};

class RadauIIA {
 public:
  RadauIIA(int stages, const NewtonOptions& options = {});
  ~RadauIIA();
  RadauIIA(RadauIIA&&) noexcept;

  // Advances `state` by `step_size`. Point loads of the model are held constant over the step.
  // Throws fsi::Error if Newton does not converge (the state is left unchanged).
  StepStatistics step(const Model& model, State& state, double step_size);

  const ButcherTableau& tableau() const;
  const IntegratorStatistics& statistics() const;

 private:
  struct Workspace;
  ButcherTableau tableau_;
  NewtonOptions options_;
  IntegratorStatistics statistics_;
  std::unique_ptr<Workspace> work_;
};

}  // namespace fsi::mbd
