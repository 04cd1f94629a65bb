#pragma once
// Constraint element interface (internal): one row of the constraint equations. A row enters
// the equations of motion with the force -G^T lambda (sign convention: fsi/mbd/model.hpp).
// Later element types (joints) implement this interface.

#include <Eigen/Dense>

#include <string>

#include "fsi/mbd/model.hpp"

namespace fsi::mbd::detail {

// A row of a column-major matrix (stride = row count).
using RowRef = Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;

class Constraint {
 public:
  virtual ~Constraint() = default;

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
  // Adds multiplier * d(G^T)/dq (n x n); rows linear in q add nothing.
  virtual void add_force_derivative(double time, const Eigen::VectorXd& q, double multiplier,
                                    Eigen::MatrixXd& derivative) const = 0;
};

// q_i - value = 0.
class CoordinateConstraint final : public Constraint {
 public:
  CoordinateConstraint(std::string description, int coordinate_index, double value);

  std::string description() const override { return description_; }
  ConstraintLevel level() const override { return ConstraintLevel::Position; }
  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void jacobian_row(double time, const Eigen::VectorXd& q, RowRef row) const override;
  double explicit_time_derivative(double, const Eigen::VectorXd&) const override { return 0.0; }
  double acceleration_remainder(double, const Eigen::VectorXd&,
                                const Eigen::VectorXd&) const override {
    return 0.0;
  }
  void add_force_derivative(double, const Eigen::VectorXd&, double,
                            Eigen::MatrixXd&) const override {}

 private:
  std::string description_;
  int index_;
  double value_;
};

// dq_i/dt - velocity = 0.
class VelocityConstraint final : public Constraint {
 public:
  VelocityConstraint(std::string description, int coordinate_index, double velocity);

  std::string description() const override { return description_; }
  ConstraintLevel level() const override { return ConstraintLevel::Velocity; }
  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void jacobian_row(double time, const Eigen::VectorXd& q, RowRef row) const override;
  double explicit_time_derivative(double, const Eigen::VectorXd&) const override { return 0.0; }
  double acceleration_remainder(double, const Eigen::VectorXd&,
                                const Eigen::VectorXd&) const override {
    return 0.0;  // the prescribed velocity is constant
  }
  void add_force_derivative(double, const Eigen::VectorXd&, double,
                            Eigen::MatrixXd&) const override {}

 private:
  std::string description_;
  int index_;
  double velocity_;
};

}  // namespace fsi::mbd::detail
