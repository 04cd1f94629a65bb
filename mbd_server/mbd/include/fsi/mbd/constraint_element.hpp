#pragma once
// Extension point for constraint rows: one scalar equation on position level, C(q, t) = 0, or on
// velocity level, G v - g(t) = 0. A row enters the equations of motion with the force
// -G^T lambda (sign convention: fsi/mbd/model.hpp). The model's own joints implement it
// (src/constraint.hpp); Model::add_constraint_element takes user rows such as a prescribed
// time-dependent motion.

#include <Eigen/Dense>

#include <string>

#include "fsi/mbd/matrix_sink.hpp"

namespace fsi::mbd {

enum class ConstraintLevel { Position, Velocity };

// A row of a column-major matrix (stride = row count).
using RowRef = Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;

class ConstraintElement {
 public:
  virtual ~ConstraintElement() = default;

  virtual std::string description() const = 0;
  virtual ConstraintLevel level() const = 0;
  // Position level: C(q, t). Velocity level: G v - g(t).
  virtual double residual(double time, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& v) const = 0;
  // G, written into a zeroed row of length n: dC/dq (position level) or d(G v - g)/dv (velocity
  // level). Velocity-level rows must have G independent of q: the Newton matrix of the
  // integrator has no d(G v)/dq term.
  virtual void jacobian_row(double time, const Eigen::VectorXd& q, RowRef row) const = 0;
  // Position level: dC/dt at fixed q, so that dC/dt = G v + (this). Velocity level: unused.
  virtual double explicit_time_derivative(double time, const Eigen::VectorXd& q) const = 0;
  // The acceleration-free part of the next time derivative: d^2C/dt^2 = G a + (this) on position
  // level, d(G v - g)/dt = G a + (this) on velocity level. Used for consistent initial lambda.
  virtual double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& v) const = 0;
  // Adds multiplier * d(G^T)/dq (n x n); rows linear in q add nothing. Must be exact: it enters
  // the Newton matrix, and a wrong one slows or stops the convergence.
  virtual void add_force_derivative(double time, const Eigen::VectorXd& q, double multiplier,
                                    Eigen::MatrixXd& derivative) const = 0;

  // The two matrices as entries at global positions, what the model assembles (dense for small
  // systems, sparse for large ones); the model's own rows write only their non-zeros. The
  // defaults are dense fallbacks for rows that only implement the functions above: jacobian_row
  // into a scratch row of length n (O(n) per row), add_force_derivative into an n x n scratch
  // matrix (O(n^2) per row); override them for rows of large models.
  // G's row `row`: adds dC/dq (or d(G v - g)/dv) at (row, column).
  virtual void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                                    MatrixSink& jacobian) const {
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(1, q.size());
    jacobian_row(time, q, dense.row(0));
    for (Eigen::Index j = 0; j < dense.cols(); ++j) {
      if (dense(0, j) != 0.0) jacobian.add(row, static_cast<int>(j), dense(0, j));
    }
  }
  // Adds multiplier * d(G^T)/dq at (row, column) (n x n).
  virtual void add_force_derivative_entries(double time, const Eigen::VectorXd& q,
                                            double multiplier, MatrixSink& derivative) const {
    const auto n = q.size();
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
    add_force_derivative(time, q, multiplier, dense);
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index i = 0; i < n; ++i) {
        if (dense(i, j) != 0.0)
          derivative.add(static_cast<int>(i), static_cast<int>(j), dense(i, j));
      }
    }
  }
};

}  // namespace fsi::mbd
