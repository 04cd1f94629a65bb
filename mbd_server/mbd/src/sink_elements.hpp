#pragma once
// Bases of the model's own force elements and constraint rows (internal): they write their
// derivatives as entries into a MatrixSink, only their non-zeros; the dense forms of the public
// interfaces are thin wrappers around that.

#include <Eigen/Dense>

#include <string>
#include <utility>

#include "fsi/mbd/constraint_element.hpp"
#include "fsi/mbd/force_element.hpp"
#include "fsi/mbd/matrix_sink.hpp"

namespace fsi::mbd::detail {

// Adds into one row of a dense matrix; the sink's row index is ignored.
class RowSink final : public MatrixSink {
 public:
  explicit RowSink(RowRef row) : row_(row) {}
  void add(int, int column, double value) override { row_(column) += value; }

 private:
  RowRef row_;
};

// The common part of the model's own force elements: a fixed description (the name in messages
// and sensors), and the dense Jacobians as a wrapper around the sink entries.
class SparseForceElement : public ForceElement {
 public:
  explicit SparseForceElement(std::string description) : description_(std::move(description)) {}

  std::string description() const final { return description_; }
  bool add_jacobians(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                     Eigen::MatrixXd& force_by_position,
                     Eigen::MatrixXd& force_by_velocity) const final {
    DenseMatrixSink position_sink(force_by_position), velocity_sink(force_by_velocity);
    return add_jacobian_entries(time, q, v, position_sink, velocity_sink);
  }
  bool add_jacobian_entries(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            MatrixSink& force_by_position,
                            MatrixSink& force_by_velocity) const override = 0;

 private:
  std::string description_;
};

// The common part of the model's own constraint rows: a fixed description and level, the dense
// forms of the derivatives as wrappers around the sink entries, no d(G^T)/dq (rows linear in q;
// nonlinear rows override it) and no explicit time dependence (rows driven by a function of time
// override it).
class ConstraintRow : public ConstraintElement {
 public:
  explicit ConstraintRow(std::string description, ConstraintLevel level = ConstraintLevel::Position)
      : description_(std::move(description)), level_(level) {}

  std::string description() const final { return description_; }
  ConstraintLevel level() const final { return level_; }
  double explicit_time_derivative(double, const Eigen::VectorXd&) const override { return 0.0; }
  void jacobian_row(double time, const Eigen::VectorXd& q, RowRef row) const final {
    RowSink sink(row);
    add_jacobian_entries(time, q, 0, sink);
  }
  void add_force_derivative(double time, const Eigen::VectorXd& q, double multiplier,
                            Eigen::MatrixXd& derivative) const final {
    DenseMatrixSink sink(derivative);
    add_force_derivative_entries(time, q, multiplier, sink);
  }
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override = 0;
  void add_force_derivative_entries(double, const Eigen::VectorXd&, double,
                                    MatrixSink&) const override {}

 private:
  std::string description_;
  ConstraintLevel level_;
};

// A row with constant coefficients and a constant right-hand side (a held coordinate, a relative
// angle, a constant prescribed velocity): its second time derivative is G a alone.
class LinearConstraintRow : public ConstraintRow {
 public:
  using ConstraintRow::ConstraintRow;
  double acceleration_remainder(double, const Eigen::VectorXd&,
                                const Eigen::VectorXd&) const final {
    return 0.0;
  }
};

}  // namespace fsi::mbd::detail
