#pragma once
// Constraint rows on coordinates themselves (internal; the row interface is
// fsi/mbd/constraint_element.hpp, the common part ConstraintRow in sink_elements.hpp): a held
// coordinate, a fixed linear combination of coordinates (a clamped beam slope's direction), a
// prescribed velocity, a prescribed motion s(t) and velocity g(t), and the relative angle of two
// planar rigid bodies (lambda: a torque).

#include <Eigen/Dense>

#include <functional>
#include <string>
#include <utility>

#include "fsi/mbd/constraint_element.hpp"
#include "sink_elements.hpp"

namespace fsi::mbd::detail {

// The common part of the rows on one coordinate q_i or its rate: G is the unit row e_i. Base is
// LinearConstraintRow for a constant target, ConstraintRow for one that moves with time.
template <typename Base>
class SingleCoordinateRow : public Base {
 public:
  SingleCoordinateRow(std::string description, ConstraintLevel level, int coordinate_index)
      : Base(std::move(description), level), index_(coordinate_index) {}

  void add_jacobian_entries(double, const Eigen::VectorXd&, int row,
                            MatrixSink& jacobian) const final {
    jacobian.add(row, index_, 1.0);
  }

 protected:
  int coordinate_index() const { return index_; }

 private:
  int index_;
};

// q_i - value = 0.
class CoordinateConstraint final : public SingleCoordinateRow<LinearConstraintRow> {
 public:
  CoordinateConstraint(std::string description, int coordinate_index, double value);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;

 private:
  double value_;
};

// sum_k w_k q_(i_k) - value = 0: a fixed linear combination of coordinates (a clamped beam
// slope's direction).
class LinearCoordinateConstraint final : public LinearConstraintRow {
 public:
  LinearCoordinateConstraint(std::string description, Eigen::VectorXi indices,
                             Eigen::VectorXd weights, double value);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;

 private:
  Eigen::VectorXi indices_;
  Eigen::VectorXd weights_;
  double value_;
};

// dq_i/dt - velocity = 0.
class VelocityConstraint final : public SingleCoordinateRow<LinearConstraintRow> {
 public:
  VelocityConstraint(std::string description, int coordinate_index, double velocity);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;

 private:
  double velocity_;
};

// q_i - s(t) = 0 with the rate s'(t) given; s'' by central differences of s' (initial lambda).
class PrescribedCoordinate final : public SingleCoordinateRow<ConstraintRow> {
 public:
  PrescribedCoordinate(std::string description, int coordinate_index,
                       std::function<double(double)> position, std::function<double(double)> rate);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  double explicit_time_derivative(double time, const Eigen::VectorXd&) const override {
    return -rate_(time);
  }
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;

 private:
  std::function<double(double)> position_;
  std::function<double(double)> rate_;
};

// dq_i/dt - g(t) = 0; dg/dt by central differences (initial lambda only).
class TimeVelocityConstraint final : public SingleCoordinateRow<ConstraintRow> {
 public:
  TimeVelocityConstraint(std::string description, int coordinate_index,
                         std::function<double(double)> velocity);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  double acceleration_remainder(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;

 private:
  std::function<double(double)> velocity_;
};

// phi_a - phi_b - offset = 0; an angle index < 0 stands for the ground.
class RelativeAngleConstraint final : public LinearConstraintRow {
 public:
  RelativeAngleConstraint(std::string description, int angle_a, int angle_b, double offset);

  double residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  void add_jacobian_entries(double time, const Eigen::VectorXd& q, int row,
                            MatrixSink& jacobian) const override;

 private:
  int angle_a_;
  int angle_b_;
  double offset_;
};

}  // namespace fsi::mbd::detail
