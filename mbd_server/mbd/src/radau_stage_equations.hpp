#pragma once
// The nonlinear stage equations of one Radau IIA (or Lobatto IIIA) step on the index-3 DAE of
// a ConstrainedSystem (fsi::mbd::Model or any other), in scaled unknowns (internal; the Newton
// driver is radau_iia.cpp).
//
// Physical stage values at t_i = t_n + c_i h: positions Q_i, velocities V_i, multipliers Lambda_i.
// Unknowns per stage i, in this order:
//     Z_i = (Q_i - q_n) / h   (n)   mean velocity over the stage, O(v)
//     V_i                     (n)
//     L_i = h Lambda_i        (m)   constraint impulse, O(h F)
// Equations per stage i (rows in the same order):
//     kinematic   Z_i - sum_j a_ij V_j = 0                                        [m/s]
//     dynamic     M (V_i - v_n) - sum_j a_ij (h F(t_j, Q_j, V_j) - G(Q_j)^T L_j) = 0   [N s]
//     constraint  C(Q_i, t_i) / h = 0 (position level),  G V_i - g(t_i) = 0 (velocity level)
// Why: with unknowns (Q, V, Lambda) the constraint rows and multiplier columns scale with h and
// 1/h, so for the coupled steps (h ~ 5e-6 s) the Newton matrix has entries from h to 1/h and
// Lambda loses digits. In these unknowns every block of the Newton matrix is O(1) as h -> 0:
//     d kinematic = [I, -a_ij I, 0]
//     d dynamic   = [-a_ij (h^2 dF/dq - h d(G^T L)/dq), M delta_ij - h a_ij dF/dv, a_ij G^T]
//     d constraint = [G, 0, 0] (position) or [0, G, 0] (velocity)
// and its limit h -> 0 is non-singular whenever M is and G has full rank.
//
// Lobatto IIIA (a_1j = 0, c_1 = 0): the first stage is the step start, Z_1 = 0 and V_1 = v_n
// follow from its kinematic and dynamic rows, and C(Q_1) = C(q_n) = 0 holds already, so its
// constraint rows would repeat G Z_1 = 0 and leave L_1 undetermined (singular Newton matrix).
// They are replaced by L_1 - h lambda_n = 0: the first stage takes the multipliers of the step
// start, and the constraints are enforced at the stages 2..s (docs/theory.md).
//
// Released rows (ConstrainedSystem::release_time): a row released over the step has the
// equation L_i = 0 at every stage instead of its constraint, and no G row, so the unknowns keep
// their number and the multiplier is exactly zero; the Newton matrix row is the unit row.

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <vector>

#include "fsi/mbd/constrained_system.hpp"
#include "fsi/mbd/integrator.hpp"

namespace fsi::mbd::detail {

class RadauStageEquations {
 public:
  explicit RadauStageEquations(const ButcherTableau& tableau);

  // Binds the model and the start of the step (t_n, q_n, v_n, lambda_n) and the step size.
  void begin_step(const ConstrainedSystem& system, const State& start, double step_size);

  // Sparse matrices (large systems): residual() multiplies the sparse M and G, and the sparse
  // jacobian() is assembled from triplets in O(non-zeros). Dense (the default): dense M and G,
  // the dense jacobian(). Both give the same equations and matrices up to the rounding of sums.
  void set_sparse(bool sparse) { sparse_ = sparse; }
  // Index2: position rows G(Q_i) V_i + dC/dt = 0 instead of C(Q_i, t_i) / h = 0 (their
  // derivatives: G in the V columns, h d(G V)/dq in the Z columns).
  void set_constraint_form(ConstraintForm form) { index2_ = form == ConstraintForm::Index2; }
  bool sparse() const { return sparse_; }

  // The rows released over the bound step (one flag per row).
  const std::vector<bool>& released() const { return released_; }
  int stages() const { return stages_; }
  int size() const { return stages_ * block_; }

  // Constant-velocity prediction with the multipliers of the step start: Z_i = c_i v_n,
  // V_i = v_n, L_i = h lambda_n. A held coordinate (v = 0) starts exactly on its constraint.
  void predict(Eigen::VectorXd& unknowns) const;
  void residual(const Eigen::VectorXd& unknowns, Eigen::VectorXd& residual);
  // The exact derivative of residual() with respect to the unknowns, dense or sparse (the same
  // entries; the sparse one holds the structural non-zeros of the model's elements, explicit
  // zeros dropped).
  void jacobian(const Eigen::VectorXd& unknowns, Eigen::MatrixXd& jacobian);
  void jacobian(const Eigen::VectorXd& unknowns, Eigen::SparseMatrix<double>& jacobian);

  // Weighted max norm of a Newton increment; <= 1 means converged. Each block (positions
  // h dZ, velocities dV, multipliers dL / h) is measured against
  //     absolute_tolerance + relative_tolerance * scale + 100 eps * round-off scale,
  // where scale is the block's size over the start and all stages (for velocities at least
  // h |F| / min diag M, for multipliers at least |F|), and the round-off term keeps the
  // criterion reachable in floating point (multipliers: L / h carries the rounding of M V / h;
  // and the rounding of the position rows' C / h in the last residual() call reaches the
  // velocities as |q| / h and the multipliers as M |q| / h^2: the index-3 floor; held
  // coordinates have C = 0 exactly and no such term). Stiff forces (an elastic beam) add the
  // rounding of F they are computed from, sum_k |dF_j/dq_k| |q_k| per coordinate j, to the
  // multipliers and, through h / (M_jj + h^2 |dF_j/dq_j|), to the velocities (from the last
  // jacobian() call). Uses the stage forces of the last residual() call.
  double increment_norm(const Eigen::VectorXd& unknowns, const Eigen::VectorXd& increment,
                        const NewtonOptions& options) const;

  // Whether `residual` (from the last residual() call, at `unknowns`) has reached its round-off
  // floor: every row within a small multiple of eps times the magnitudes of the terms it is
  // summed from (kinematic: |Z_i| + sum |a_ij| |V_j|; dynamic: |M| (|V_i| + |v_n|) +
  // sum |a_ij| (h (|F_j| + rounding of F) + |G_j|^T |L_j|); position rows: |G_i| (|Q_i| +
  // |Q_i|_inf) / h; velocity rows: |G_i| (|V_i| + |V_i|_inf)), plus `solve_rounding` per row (|J|
  // |dz| of the increment that led to `unknowns`: the backward error of the LU solve puts that much
  // rounding into the rows it updates; empty: none). Below it Newton cannot improve the iterate:
  // its increments are rounding, amplified by the Newton matrix (newton_convergence.hpp).
  bool residual_at_floor(const Eigen::VectorXd& unknowns, const Eigen::VectorXd& residual,
                         const Eigen::VectorXd& solve_rounding) const;

  // Physical stage values.
  Eigen::VectorXd position(const Eigen::VectorXd& unknowns, int stage) const;
  Eigen::VectorXd velocity(const Eigen::VectorXd& unknowns, int stage) const;
  Eigen::VectorXd multiplier(const Eigen::VectorXd& unknowns, int stage) const;

 private:
  int z_offset(int stage) const { return stage * block_; }
  int v_offset(int stage) const { return stage * block_ + n_; }
  int l_offset(int stage) const { return stage * block_ + 2 * n_; }
  double stage_time(int stage) const { return start_.time + c_(stage) * step_size_; }
  // The constraint rows of stage `stage` (released rows: L = 0).
  void constraint_rows_residual(const Eigen::VectorXd& unknowns, int stage,
                                Eigen::VectorXd& residual);
  // force_rounding_ and force_velocity_rounding_ from the per-coordinate rounding of F and the
  // diagonals of dF/dq, dF/dv of one stage (see increment_norm).
  // Removes the released rows from a stage's G (a released joint's G may not even be defined,
  // e.g. a rod whose ends meet), and their multipliers from `multipliers`.
  void drop_released(Eigen::MatrixXd& jacobian) const;
  void drop_released(Eigen::SparseMatrix<double>& jacobian) const;
  void drop_released(Eigen::VectorXd& multipliers) const;
  bool any_released() const;
  void add_force_rounding(const Eigen::VectorXd& rounding,
                          const Eigen::VectorXd& by_position_diagonal,
                          const Eigen::VectorXd& by_velocity_diagonal);

  Eigen::MatrixXd a_;
  Eigen::VectorXd c_;
  int stages_;
  bool first_stage_is_start_;  // Lobatto IIIA: a_1j = 0
  const ConstrainedSystem* system_ = nullptr;
  State start_;
  double step_size_ = 0.0;
  int n_ = 0;
  int m_ = 0;
  int block_ = 0;
  std::vector<bool> position_level_;
  std::vector<bool> released_;
  double position_residual_ = 0.0;  // max |C(Q_i)| of position rows in the last residual() call
  // Sizes whose rounding the stiff forces carry (last jacobian() call, see increment_norm).
  double force_rounding_ = 0.0;
  double force_velocity_rounding_ = 0.0;
  // Scratch, per stage where needed.
  std::vector<Eigen::VectorXd> stage_force_;
  std::vector<Eigen::MatrixXd> stage_constraint_jacobian_;
  Eigen::VectorXd q_, v_, lambda_, constraint_;
  Eigen::MatrixXd by_position_, by_velocity_, constraint_force_derivative_;
  bool sparse_ = false;
  bool index2_ = false;
  Eigen::VectorXd rate_;
  Eigen::MatrixXd velocity_derivative_;
  std::vector<Eigen::SparseMatrix<double>> stage_sparse_constraint_jacobian_;
  Eigen::SparseMatrix<double> sparse_by_position_, sparse_by_velocity_,
      sparse_constraint_force_derivative_;
  std::vector<Eigen::Triplet<double>> triplets_;
};

}  // namespace fsi::mbd::detail
