#pragma once
// Implicit Runge-Kutta integration of the constrained equations of motion (thesis §2.1.3.3):
// Radau IIA with s = 1, 2, 3 stages (orders 1, 3, 5; stiffly accurate, L-stable), or Lobatto
// IIIA with s = 2, 3 stages (orders 2, 4; stiffly accurate, A-stable but not L-stable; HOTINT's
// tableau_name), applied directly to the index-3 DAE of a ConstrainedSystem (fsi::mbd::Model or any
// other), with a fixed step given per call. Orders on the constrained problem: docs/theory.md. The
// stage equations are solved by (modified) Newton iterations with a dense LU factorisation; a step
// runs the named stages initialise, predict, Newton increment, accept/reject, finalise. Equations,
// unknowns and their scaling: mbd_server/mbd/README.md.

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fsi/mbd/constrained_system.hpp"
#include "fsi/mbd/integrand.hpp"

namespace fsi::mbd {

enum class TableauFamily { RadauIIA, LobattoIIIA };

struct ButcherTableau {
  std::string name;   // "Radau IIA", "Lobatto IIIA"
  Eigen::MatrixXd a;  // s x s
  Eigen::VectorXd b;  // weights (= last row of a: stiffly accurate)
  Eigen::VectorXd c;  // nodes (c_s = 1)
  int order = 0;      // classical order: 2s - 1 (Radau IIA), 2s - 2 (Lobatto IIIA)
};

// Radau IIA tableau with 1, 2 or 3 stages; throws fsi::Error otherwise.
ButcherTableau radau_iia(int stages);
// Lobatto IIIA tableau with 2 or 3 stages (trapezoidal rule, Hermite-Simpson); c_1 = 0 and
// a_1j = 0: the first stage is the step start. Throws fsi::Error otherwise.
ButcherTableau lobatto_iiia(int stages);
ButcherTableau butcher_tableau(TableauFamily family, int stages);

// How the Newton matrix is factorised: dense partial-pivoting LU, or Eigen's SparseLU (COLAMD
// ordering) of its non-zeros; Automatic takes SparseLU from sparse_threshold unknowns on.
enum class LinearSolver { Automatic, Dense, Sparse };

struct NewtonOptions {
  // Convergence: every block of the Newton increment (positions, velocities, multipliers) is
  // below absolute_tolerance + relative_tolerance * (size of that block), in SI units.
  double relative_tolerance = 1e-10;
  int max_iterations = 12;
  // How many steps a factorised Newton matrix may be reused (HOTINT's
  // max_modified_newton_steps); 0 = full Newton, a fresh matrix in every iteration.
  int max_modified_newton_steps = 20;
  // A reused matrix is replaced when the contraction rate |dx_k| / |dx_k-1| exceeds this.
  double max_contraction = 0.5;
  // Matters only where a whole block is zero and stays zero (e.g. no forces at all).
  double absolute_tolerance = 1e-14;
  LinearSolver linear_solver = LinearSolver::Automatic;
  // Size of the Newton matrix (stages x (2 n + m)) from which Automatic factorises sparsely.
  int sparse_threshold = 300;
};

// How position-level constraints enter the stage equations (HOTINT's choice): Index3 enforces
// C(Q_i, t_i) = 0 at the stages (no drift of the constraints, the default); Index2 enforces their
// rate G(Q_i) V_i + dC/dt = 0 instead, so the positions drift off C = 0 by the integration error
// (docs/theory.md). Velocity-level rows are the same in both.
enum class ConstraintForm { Index3, Index2 };

struct RadauOptions {
  int stages = 3;  // Radau IIA: 1, 2 or 3 (orders 1, 3, 5); Lobatto IIIA: 2 or 3 (orders 2, 4;
                   // with constraints (index 3) 2 and 2: docs/theory.md)
  NewtonOptions newton;
  TableauFamily family = TableauFamily::RadauIIA;
  ConstraintForm constraint_form = ConstraintForm::Index3;
};

struct StepStatistics {
  int newton_iterations = 0;
  int jacobian_evaluations = 0;
  int factorisations = 0;
  int retries = 0;  // attempts restarted from the prediction with a fresh Newton matrix
};

struct IntegratorStatistics {
  std::uint64_t steps = 0;
  std::uint64_t newton_iterations = 0;
  std::uint64_t jacobian_evaluations = 0;
  std::uint64_t factorisations = 0;
  std::uint64_t retries = 0;
  // Steps a caller took again in substeps after the whole step's Newton iteration failed
  // (fsi::coupling's structure side; the integrator itself leaves it 0).
  std::uint64_t substepped_steps = 0;
  void add(const StepStatistics& step);
};

// One step's stage values (dense output; docs/theory.md, "Multi-rate coupling"): the state at
// the step's start and at its collocation nodes t0 + c_i h. Multi-rate coupling sends the
// boundary vertices at these nodes to the fluid, which interpolates between them
// (fsi/protocol/step_motion.hpp).
struct StepStages {
  double start_time = 0.0;
  double step_size = 0.0;  // 0 before the first step
  // 0, then the tableau's c_i (Lobatto IIIA's c_1 = 0 only once): distinct, ascending, the last 1.
  std::vector<double> nodes;
  std::vector<Eigen::VectorXd> positions;   // q at each node
  std::vector<Eigen::VectorXd> velocities;  // v at each node
};

class RadauIIA {
 public:
  // Throws fsi::Error for an unavailable stage count or invalid Newton options.
  explicit RadauIIA(const RadauOptions& options);
  explicit RadauIIA(int stages, const NewtonOptions& newton = {});
  ~RadauIIA();
  RadauIIA(RadauIIA&&) noexcept;
  RadauIIA& operator=(RadauIIA&&) noexcept;

  // Advances `state` from state.time by `step_size`. The model's point loads are held constant
  // over the step (thesis Fig. 4.10). Throws fsi::Error naming time, step size and residual if
  // Newton does not converge; `state` is then left unchanged.
  // A constraint row released inside the step (ConstrainedSystem::release_within) splits it at
  // the release time; the returned statistics sum the parts.
  StepStatistics step(const ConstrainedSystem& system, State& state, double step_size);

  // Drops the kept factorisation; needed after changing the model's structure in place, and at
  // a checkpoint: the next step then starts from a fresh Newton matrix, as a resumed run's does
  // (bit for bit the same steps afterwards).
  void reset();
  // Continues the totals of an earlier process (a resumed run).
  void set_statistics(const IntegratorStatistics& statistics);

  // The stage values of the last step taken; of its last part when a release split it (the
  // parts' start_time then lies inside the step). The last node's values are the step's end
  // state exactly (stiffly accurate).
  const StepStages& last_step_stages() const;

  // Integrates `integrand` over every step from now on (fsi/mbd/integrand.hpp): the step adds
  // h sum_i b_i g(stage i), the tableau's quadrature on the stage values.
  void set_integrand(Integrand integrand);
  // The integrand's integral over the last step() (the sum of its parts when a release split
  // it); size 0 without an integrand.
  const Eigen::VectorXd& last_step_integral() const;

  const ButcherTableau& tableau() const;
  const NewtonOptions& options() const;
  const IntegratorStatistics& statistics() const;

 private:
  StepStatistics step_without_release(const ConstrainedSystem& system, State& state,
                                      double step_size);
  struct Workspace;
  std::unique_ptr<Workspace> work_;
};

}  // namespace fsi::mbd
