#include "fsi/mbd/constrained_system.hpp"

namespace fsi::mbd {

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

std::string ConstrainedSystem::non_finite_source(double, const Eigen::VectorXd&,
                                                 const Eigen::VectorXd&) const {
  return {};
}

}  // namespace fsi::mbd
