#include "fsi/mbd/constrained_system.hpp"

#include <cmath>
#include <limits>

namespace fsi::mbd {

double ConstrainedSystem::release_time(int) const {
  return std::numeric_limits<double>::infinity();
}

bool ConstrainedSystem::holds_over(int row, double start, double end) const {
  return 0.5 * (start + end) < release_time(row);
}

bool ConstrainedSystem::holds_at(int row, double time) const {
  return time <= release_time(row);
}

std::vector<bool> ConstrainedSystem::released_rows(double start, double end) const {
  std::vector<bool> released(static_cast<std::size_t>(constraint_count()));
  for (int k = 0; k < constraint_count(); ++k)
    released[static_cast<std::size_t>(k)] = !holds_over(k, start, end);
  return released;
}

std::optional<double> ConstrainedSystem::release_within(double start, double end) const {
  const double margin = 1e-9 * std::abs(end - start);
  std::optional<double> earliest;
  for (int k = 0; k < constraint_count(); ++k) {
    const double release = release_time(k);
    if (release > start + margin && release < end - margin && (!earliest || release < *earliest))
      earliest = release;
  }
  return earliest;
}

void ConstrainedSystem::applied_force_derivatives(double time, const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& v,
                                                  Eigen::MatrixXd& by_position,
                                                  Eigen::MatrixXd& by_velocity) const {
  const int n = coordinate_count();
  by_position.setZero(n, n);
  by_velocity.setZero(n, n);
  DenseMatrixSink position_sink(by_position), velocity_sink(by_velocity);
  add_applied_force_derivatives(time, q, v, position_sink, velocity_sink);
}

void ConstrainedSystem::applied_force_derivatives(double time, const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& v,
                                                  Eigen::SparseMatrix<double>& by_position,
                                                  Eigen::SparseMatrix<double>& by_velocity) const {
  const int n = coordinate_count();
  TripletSink position_sink, velocity_sink;
  add_applied_force_derivatives(time, q, v, position_sink, velocity_sink);
  position_sink.to_matrix(n, n, by_position);
  velocity_sink.to_matrix(n, n, by_velocity);
}

void ConstrainedSystem::constraint_jacobian(double time, const Eigen::VectorXd& q,
                                            Eigen::MatrixXd& jacobian) const {
  jacobian.setZero(constraint_count(), coordinate_count());
  DenseMatrixSink sink(jacobian);
  add_constraint_jacobian(time, q, sink);
}

void ConstrainedSystem::constraint_jacobian(double time, const Eigen::VectorXd& q,
                                            Eigen::SparseMatrix<double>& jacobian) const {
  TripletSink sink;
  add_constraint_jacobian(time, q, sink);
  sink.to_matrix(constraint_count(), coordinate_count(), jacobian);
}

void ConstrainedSystem::constraint_force_derivative(double time, const Eigen::VectorXd& q,
                                                    const Eigen::VectorXd& lambda,
                                                    Eigen::MatrixXd& derivative) const {
  derivative.setZero(coordinate_count(), coordinate_count());
  DenseMatrixSink sink(derivative);
  add_constraint_force_derivative(time, q, lambda, sink);
}

void ConstrainedSystem::constraint_force_derivative(double time, const Eigen::VectorXd& q,
                                                    const Eigen::VectorXd& lambda,
                                                    Eigen::SparseMatrix<double>& derivative) const {
  TripletSink sink;
  add_constraint_force_derivative(time, q, lambda, sink);
  sink.to_matrix(coordinate_count(), coordinate_count(), derivative);
}

std::string ConstrainedSystem::coordinate_description(int index) const {
  return "coordinate " + std::to_string(index);
}

std::string ConstrainedSystem::constraint_description(int row) const {
  return "constraint row " + std::to_string(row);
}

std::string ConstrainedSystem::equation_of_motion_note(int, double, const Eigen::VectorXd&,
                                                       const Eigen::VectorXd&) const {
  return {};
}

std::string ConstrainedSystem::non_finite_source(double, const Eigen::VectorXd&,
                                                 const Eigen::VectorXd&) const {
  return {};
}

}  // namespace fsi::mbd
