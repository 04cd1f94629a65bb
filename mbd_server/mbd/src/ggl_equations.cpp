#include "ggl_equations.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "fsi/common/error.hpp"

namespace fsi::mbd::detail {

void GglEquations::bind(const ConstrainedSystem& system, std::vector<bool> released) {
  system_ = &system;
  n_ = system.coordinate_count();
  m_ = system.constraint_count();
  released_ = std::move(released);
  released_.resize(static_cast<std::size_t>(m_), false);
  position_rows_.clear();
  for (int k = 0; k < m_; ++k) {
    if (system.constraint_level(k) == ConstraintLevel::Position) position_rows_.push_back(k);
  }
  p_ = static_cast<int>(position_rows_.size());
}

void GglEquations::drop_released_rows(Eigen::MatrixXd& matrix) const {
  for (int k = 0; k < m_; ++k) {
    if (released_[k]) matrix.row(k).setZero();
  }
}

void GglEquations::residual(double time, const Eigen::VectorXd& y, const Eigen::VectorXd& yp,
                            Eigen::VectorXd& residual) {
  FSI_ASSERT(system_ != nullptr && y.size() == size() && yp.size() == size(),
             "GGL equations not bound");
  const ConstrainedSystem& system = *system_;
  q_ = y.segment(q_offset(), n_);
  v_ = y.segment(v_offset(), n_);
  system.applied_force(time, q_, v_, force_);
  system.constraint_jacobian(time, q_, g_);
  drop_released_rows(g_);
  system.constraint_residual(time, q_, v_, constraint_);
  system.constraint_rate(time, q_, v_, rate_);
  residual.resize(size());
  auto kinematic = residual.segment(q_offset(), n_);
  kinematic = yp.segment(q_offset(), n_) - v_;
  for (int r = 0; r < p_; ++r)
    kinematic += g_.row(position_rows_[r]).transpose() * y(mu_offset() + r);
  residual.segment(v_offset(), n_) = system.mass_matrix() * yp.segment(v_offset(), n_) - force_ +
                                     g_.transpose() * y.segment(lambda_offset(), m_);
  // Position rows of C, then the velocity level of every row (rows in the order of the unknowns
  // lambda and mu: the velocity rows take lambda's place, the position rows mu's).
  for (int r = 0; r < p_; ++r)
    residual(mu_offset() + r) = constraint_(position_rows_[r]);
  residual.segment(lambda_offset(), m_) = rate_;
  for (int r = 0; r < p_; ++r) {
    if (released_[position_rows_[r]]) residual(mu_offset() + r) = y(mu_offset() + r);
  }
  for (int k = 0; k < m_; ++k) {
    if (released_[k]) residual(lambda_offset() + k) = y(lambda_offset() + k);
  }
}

void GglEquations::jacobian(double time, double cj, const Eigen::VectorXd& y,
                            Eigen::Ref<Eigen::MatrixXd> jacobian) {
  FSI_ASSERT(system_ != nullptr && y.size() == size() && jacobian.rows() == size() &&
                 jacobian.cols() == size(),
             "GGL equations not bound");
  const ConstrainedSystem& system = *system_;
  q_ = y.segment(q_offset(), n_);
  v_ = y.segment(v_offset(), n_);
  lambda_ = y.segment(lambda_offset(), m_);
  mu_full_.setZero(m_);
  for (int r = 0; r < p_; ++r)
    mu_full_(position_rows_[r]) = y(mu_offset() + r);
  for (int k = 0; k < m_; ++k) {
    if (released_[k]) lambda_(k) = mu_full_(k) = 0.0;
  }
  system.constraint_jacobian(time, q_, g_);
  drop_released_rows(g_);
  system.applied_force_derivatives(time, q_, v_, by_position_, by_velocity_);
  jacobian.setZero();

  const int qo = q_offset(), vo = v_offset(), lo = lambda_offset(), mo = mu_offset();
  // kinematic rows
  system.constraint_force_derivative(time, q_, mu_full_, derivative_);
  jacobian.block(qo, qo, n_, n_) = derivative_;
  jacobian.block(qo, qo, n_, n_).diagonal().array() += cj;
  jacobian.block(qo, vo, n_, n_).diagonal().array() -= 1.0;
  for (int r = 0; r < p_; ++r)
    jacobian.block(qo, mo + r, n_, 1) = g_.row(position_rows_[r]).transpose();
  // dynamic rows
  system.constraint_force_derivative(time, q_, lambda_, derivative_);
  jacobian.block(vo, qo, n_, n_) = derivative_ - by_position_;
  jacobian.block(vo, vo, n_, n_) = cj * system.mass_matrix() - by_velocity_;
  jacobian.block(vo, lo, n_, m_) = g_.transpose();
  // position rows
  for (int r = 0; r < p_; ++r)
    jacobian.block(mo + r, qo, 1, n_) = g_.row(position_rows_[r]);
  // velocity level: d(G v + C_t)/dq for position rows, G for all rows
  jacobian.block(lo, vo, m_, n_) = g_;
  // Released rows: lambda_k = 0 and mu = 0 (their G rows are zero above).
  for (int k = 0; k < m_; ++k) {
    if (released_[k]) jacobian(lo + k, lo + k) = 1.0;
  }
  for (int r = 0; r < p_; ++r) {
    if (released_[position_rows_[r]]) jacobian(mo + r, mo + r) = 1.0;
  }
  if (p_ == 0) return;
  const double dt =
      std::cbrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, std::abs(time));
  system.constraint_jacobian(time + dt, q_, g_plus_);
  system.constraint_jacobian(time - dt, q_, g_minus_);
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(m_);
  for (int r = 0; r < p_; ++r) {
    const int k = position_rows_[r];
    if (released_[k]) continue;
    unit(k) = 1.0;
    system.constraint_force_derivative(time, q_, unit, hessian_);
    unit(k) = 0.0;
    jacobian.block(lo + k, qo, 1, n_) =
        (hessian_.transpose() * v_).transpose() + (g_plus_.row(k) - g_minus_.row(k)) / (2.0 * dt);
  }
}

bool GglEquations::consistent_vectors(const State& state, Eigen::VectorXd& y, Eigen::VectorXd& yp) {
  FSI_ASSERT(system_ != nullptr, "GGL equations not bound");
  const ConstrainedSystem& system = *system_;
  system.applied_force(state.time, state.q, state.v, force_);
  system.constraint_jacobian(state.time, state.q, g_);
  drop_released_rows(g_);
  Eigen::VectorXd remainder;
  system.constraint_acceleration_remainder(state.time, state.q, state.v, remainder);
  Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(n_ + m_, n_ + m_);
  augmented.topLeftCorner(n_, n_) = system.mass_matrix();
  augmented.topRightCorner(n_, m_) = g_.transpose();
  augmented.bottomLeftCorner(m_, n_) = g_;
  Eigen::VectorXd right(n_ + m_);
  right.head(n_) = force_;
  right.tail(m_) = -remainder;
  for (int k = 0; k < m_; ++k) {
    if (!released_[k]) continue;
    augmented(n_ + k, n_ + k) = 1.0;  // lambda_k = 0
    right(n_ + k) = 0.0;
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(augmented);
  if (!lu.isInvertible()) return false;
  const Eigen::VectorXd solution = lu.solve(right);
  y.setZero(size());
  yp.setZero(size());
  y.segment(q_offset(), n_) = state.q;
  y.segment(v_offset(), n_) = state.v;
  y.segment(lambda_offset(), m_) = solution.tail(m_);
  yp.segment(q_offset(), n_) = state.v;
  yp.segment(v_offset(), n_) = solution.head(n_);
  return solution.allFinite();
}

std::string GglEquations::describe_row(int row) const {
  FSI_ASSERT(system_ != nullptr && row >= 0 && row < size(), "row out of range");
  if (row < v_offset()) return "kinematics of " + system_->coordinate_description(row);
  if (row < lambda_offset()) {
    return "equation of motion of " + system_->coordinate_description(row - v_offset());
  }
  if (row < mu_offset()) {
    return "velocity level of " + system_->constraint_description(row - lambda_offset());
  }
  return "position level of " + system_->constraint_description(position_rows_[row - mu_offset()]);
}

std::string GglEquations::non_finite_source(double time, const Eigen::VectorXd& y) const {
  FSI_ASSERT(system_ != nullptr, "equations not bound");
  State state;
  to_state(y, time, state);
  return system_->non_finite_source(time, state.q, state.v);
}

std::string GglEquations::describe_variable(int index) const {
  FSI_ASSERT(system_ != nullptr && index >= 0 && index < size(), "variable out of range");
  if (index < v_offset()) return "position of " + system_->coordinate_description(index);
  if (index < lambda_offset()) {
    return "velocity of " + system_->coordinate_description(index - v_offset());
  }
  if (index < mu_offset()) {
    return "multiplier of " + system_->constraint_description(index - lambda_offset());
  }
  return "position-level multiplier of " +
         system_->constraint_description(position_rows_[index - mu_offset()]);
}

void GglEquations::to_state(const Eigen::VectorXd& y, double time, State& state) const {
  state.time = time;
  state.q = y.segment(q_offset(), n_);
  state.v = y.segment(v_offset(), n_);
  state.lambda = y.segment(lambda_offset(), m_);
}

}  // namespace fsi::mbd::detail
