#pragma once
// What the integrators see of a multibody system (Chrono's ChIntegrableIIorder plays this role
// there): the constrained equations of motion of thesis eq. 2.1-2.2 in coordinates q (n),
// velocities v = dq/dt (n) and multipliers lambda (m),
//
//     M dv/dt = F(t, q, v) - G(q)^T lambda
//     C(q, t) = 0                 position-level rows (index 3), G = dC/dq
//     G v - g(t) = 0              velocity-level rows (index 2)
//
// with the sign convention of fsi/mbd/model.hpp (the constraints push the bodies with
// -G^T lambda). Radau IIA / Lobatto IIIA, the adaptive Radau IIA, SUNDIALS IDA and the modal
// analysis take `const ConstrainedSystem&`; Model implements it for bodies, joints and force
// elements, and a hand-written system (a test problem in Cartesian coordinates) can implement
// it directly. Every matrix is assembled into a MatrixSink; the dense and sparse forms below
// are wrappers shared by every implementation.

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fsi/mbd/constraint_element.hpp"
#include "fsi/mbd/matrix_sink.hpp"

namespace fsi::mbd {

struct State {
  double time = 0.0;
  Eigen::VectorXd q;       // generalised coordinates
  Eigen::VectorXd v;       // their time derivatives
  Eigen::VectorXd lambda;  // one multiplier per constraint row (see the sign convention above)
};

class ConstrainedSystem {
 public:
  virtual ~ConstrainedSystem() = default;

  // --- dimensions ---
  virtual int coordinate_count() const = 0;  // n
  virtual int constraint_count() const = 0;  // m

  // --- mass: constant, so the three forms are computed once and kept ---
  virtual const Eigen::MatrixXd& mass_matrix() const = 0;
  virtual const Eigen::SparseMatrix<double>& sparse_mass_matrix() const = 0;
  virtual const Eigen::VectorXd& mass_diagonal() const = 0;

  // --- applied forces F(t, q, v), including the point loads held over a step ---
  virtual void applied_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                             Eigen::VectorXd& force) const = 0;
  // Adds dF/dq and dF/dv (sinks sized n x n).
  virtual void add_applied_force_derivatives(double time, const Eigen::VectorXd& q,
                                             const Eigen::VectorXd& v, MatrixSink& by_position,
                                             MatrixSink& by_velocity) const = 0;
  void applied_force_derivatives(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                 Eigen::MatrixXd& by_position, Eigen::MatrixXd& by_velocity) const;
  void applied_force_derivatives(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                 Eigen::SparseMatrix<double>& by_position,
                                 Eigen::SparseMatrix<double>& by_velocity) const;

  // --- constraint rows ---
  virtual ConstraintLevel constraint_level(int row) const = 0;
  // C(q, t) for position-level rows, G v - g(t) for velocity-level rows (size m).
  virtual void constraint_residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                   Eigen::VectorXd& residual) const = 0;
  // The rows on velocity level (size m): G v + C_t for position-level rows, G v - g(t) for
  // velocity-level rows (the index-2 form of IDA).
  virtual void constraint_rate(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                               Eigen::VectorXd& rate) const = 0;
  // The acceleration-free part of the rows' second time derivative (size m): d^2C/dt^2 =
  // G a + remainder (position rows), d(G v - g)/dt = G a + remainder (velocity rows).
  virtual void constraint_acceleration_remainder(double time, const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& v,
                                                 Eigen::VectorXd& remainder) const = 0;
  // Adds G (m x n): dC/dq for position-level rows, d(G v - g)/dv for velocity-level rows.
  virtual void add_constraint_jacobian(double time, const Eigen::VectorXd& q,
                                       MatrixSink& jacobian) const = 0;
  void constraint_jacobian(double time, const Eigen::VectorXd& q, Eigen::MatrixXd& jacobian) const;
  void constraint_jacobian(double time, const Eigen::VectorXd& q,
                           Eigen::SparseMatrix<double>& jacobian) const;
  // Adds d/dq (G(q)^T lambda) (n x n); nothing while every row is linear in q.
  virtual void add_constraint_force_derivative(double time, const Eigen::VectorXd& q,
                                               const Eigen::VectorXd& lambda,
                                               MatrixSink& derivative) const = 0;
  void constraint_force_derivative(double time, const Eigen::VectorXd& q,
                                   const Eigen::VectorXd& lambda,
                                   Eigen::MatrixXd& derivative) const;
  void constraint_force_derivative(double time, const Eigen::VectorXd& q,
                                   const Eigen::VectorXd& lambda,
                                   Eigen::SparseMatrix<double>& derivative) const;
  // Adds d/dq (G(q) v) at fixed v (m x n): row k is v^T times the Hessian of C_k (the Newton
  // matrix of the index-2 form). Velocity-level rows add nothing (G independent of q).
  virtual void add_constraint_velocity_derivative(double time, const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& v,
                                                  MatrixSink& derivative) const = 0;

  // --- release: a row holds until its release time and is removed from then on ---
  // The time from which row `row` no longer acts (+infinity, the default: it always holds).
  // A released row's equation becomes lambda = 0, so the system keeps its size m for every
  // integrator and the multiplier (the constraint force a sensor reads) is zero from then on.
  virtual double release_time(int row) const;
  // Does the row hold over the step [start, end]? The integrators never step across a release
  // (release_within), so a row holds over all of a step or over none of it; the step's midpoint
  // decides, which is robust against the rounding of accumulated step times. A row releasing at
  // t_r therefore holds over the step ending at t_r (its multiplier there is the holding force)
  // and is released over the step starting at t_r.
  bool holds_over(int row, double start, double end) const;
  // Does the row hold at the instant `time` (time <= release time)? For readouts of a state.
  bool holds_at(int row, double time) const;
  // The rows released over the step [start, end], one flag per row.
  std::vector<bool> released_rows(double start, double end) const;
  // The earliest release time strictly inside (start, end), farther than a relative 1e-9 of the
  // step from both ends, or nullopt: where an integrator must end a step. A release closer to an
  // end than that is taken at that end (the row holds over a step ending within rounding of its
  // release time and is released from there).
  std::optional<double> release_within(double start, double end) const;

  // --- point loads: the values the caller set for this step (held over its stages) ---
  virtual std::span<const double> point_loads() const = 0;

  // --- names for the integrators' messages ---
  // "body 'link' coordinate angle"; default "coordinate <index>".
  virtual std::string coordinate_description(int index) const;
  // "revolute joint 'hinge' (x)"; default "constraint row <row>".
  virtual std::string constraint_description(int row) const;
  // What may keep Newton from converging in coordinate `index`'s equation of motion at (t, q, v)
  // that no step size cures, as "; ..." for the message, or empty (default: empty).
  virtual std::string equation_of_motion_note(int index, double time, const Eigen::VectorXd& q,
                                              const Eigen::VectorXd& v) const;
  // The first contribution that is not finite at (t, q, v), by description, or empty (default:
  // empty, the messages then name the largest residual instead).
  virtual std::string non_finite_source(double time, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& v) const;
};

}  // namespace fsi::mbd
