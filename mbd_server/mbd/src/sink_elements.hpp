#pragma once
// Bases of the model's own force elements and constraint rows (internal): they write their
// derivatives as entries into a MatrixSink, only their non-zeros; the dense forms of the public
// interfaces are thin wrappers around that.

#include <Eigen/Dense>

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

class SparseForceElement : public ForceElement {
 public:
  bool add_jacobians(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                     Eigen::MatrixXd& force_by_position,
                     Eigen::MatrixXd& force_by_velocity) const final {
    DenseMatrixSink position_sink(force_by_position), velocity_sink(force_by_velocity);
    return add_jacobian_entries(time, q, v, position_sink, velocity_sink);
  }
  bool add_jacobian_entries(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            MatrixSink& force_by_position,
                            MatrixSink& force_by_velocity) const override = 0;
};

class SparseConstraint : public ConstraintElement {
 public:
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
  // Rows linear in q add nothing.
  void add_force_derivative_entries(double, const Eigen::VectorXd&, double,
                                    MatrixSink&) const override {}
};

}  // namespace fsi::mbd::detail
