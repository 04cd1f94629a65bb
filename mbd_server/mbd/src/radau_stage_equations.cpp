#include "radau_stage_equations.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fsi/common/error.hpp"

namespace fsi::mbd::detail {
namespace {

double max_abs(const Eigen::VectorXd& x) {
  return x.size() == 0 ? 0.0 : x.lpNorm<Eigen::Infinity>();
}

}  // namespace

RadauStageEquations::RadauStageEquations(const ButcherTableau& tableau)
    : a_(tableau.a),
      c_(tableau.c),
      stages_(static_cast<int>(tableau.c.size())),
      first_stage_is_start_(tableau.a.row(0).isZero(0.0)) {}

void RadauStageEquations::begin_step(const Model& model, const State& start, double step_size) {
  model_ = &model;
  start_ = start;
  step_size_ = step_size;
  n_ = model.coordinate_count();
  m_ = model.constraint_count();
  block_ = 2 * n_ + m_;
  position_level_.resize(m_);
  for (int k = 0; k < m_; ++k)
    position_level_[k] = model.constraint_level(k) == ConstraintLevel::Position;
  stage_force_.assign(stages_, Eigen::VectorXd::Zero(n_));
  stage_constraint_jacobian_.assign(stages_, Eigen::MatrixXd::Zero(m_, n_));
}

void RadauStageEquations::predict(Eigen::VectorXd& unknowns) const {
  unknowns.resize(size());
  for (int i = 0; i < stages_; ++i) {
    unknowns.segment(z_offset(i), n_) = c_(i) * start_.v;
    unknowns.segment(v_offset(i), n_) = start_.v;
    unknowns.segment(l_offset(i), m_) = step_size_ * start_.lambda;
  }
}

Eigen::VectorXd RadauStageEquations::position(const Eigen::VectorXd& unknowns, int stage) const {
  return start_.q + step_size_ * unknowns.segment(z_offset(stage), n_);
}

Eigen::VectorXd RadauStageEquations::velocity(const Eigen::VectorXd& unknowns, int stage) const {
  return unknowns.segment(v_offset(stage), n_);
}

Eigen::VectorXd RadauStageEquations::multiplier(const Eigen::VectorXd& unknowns, int stage) const {
  return unknowns.segment(l_offset(stage), m_) / step_size_;
}

void RadauStageEquations::residual(const Eigen::VectorXd& unknowns, Eigen::VectorXd& residual) {
  FSI_ASSERT(model_ != nullptr && unknowns.size() == size(), "stage equations not bound");
  const Model& model = *model_;
  const double h = step_size_;
  const Eigen::MatrixXd& mass = model.mass_matrix();
  for (int j = 0; j < stages_; ++j) {
    q_ = position(unknowns, j);
    v_ = velocity(unknowns, j);
    model.applied_force(stage_time(j), q_, v_, stage_force_[j]);
    model.constraint_jacobian(stage_time(j), q_, stage_constraint_jacobian_[j]);
  }
  residual.resize(size());
  position_residual_ = 0.0;
  for (int i = 0; i < stages_; ++i) {
    auto kinematic = residual.segment(z_offset(i), n_);
    auto dynamic = residual.segment(v_offset(i), n_);
    kinematic = unknowns.segment(z_offset(i), n_);
    dynamic = mass * (unknowns.segment(v_offset(i), n_) - start_.v);
    for (int j = 0; j < stages_; ++j) {
      kinematic -= a_(i, j) * unknowns.segment(v_offset(j), n_);
      dynamic -= a_(i, j) * (h * stage_force_[j] - stage_constraint_jacobian_[j].transpose() *
                                                       unknowns.segment(l_offset(j), m_));
    }
    if (i == 0 && first_stage_is_start_) {
      residual.segment(l_offset(0), m_) = unknowns.segment(l_offset(0), m_) - h * start_.lambda;
      continue;
    }
    q_ = position(unknowns, i);
    v_ = velocity(unknowns, i);
    model.constraint_residual(stage_time(i), q_, v_, constraint_);
    for (int k = 0; k < m_; ++k) {
      residual(l_offset(i) + k) = position_level_[k] ? constraint_(k) / h : constraint_(k);
      if (position_level_[k])
        position_residual_ = std::max(position_residual_, std::abs(constraint_(k)));
    }
  }
}

void RadauStageEquations::jacobian(const Eigen::VectorXd& unknowns, Eigen::MatrixXd& jacobian) {
  FSI_ASSERT(model_ != nullptr && unknowns.size() == size(), "stage equations not bound");
  const Model& model = *model_;
  const double h = step_size_;
  const Eigen::MatrixXd& mass = model.mass_matrix();
  jacobian.setZero(size(), size());
  force_rounding_ = 0.0;
  force_velocity_rounding_ = 0.0;
  for (int j = 0; j < stages_; ++j) {
    q_ = position(unknowns, j);
    v_ = velocity(unknowns, j);
    const double t = stage_time(j);
    model.applied_force_derivatives(t, q_, v_, by_position_, by_velocity_);
    // F_r is evaluated from coordinates of size |q|: its rounding is ~eps sum_k |dF_r/dq_k| |q_k|
    // (plus the same for v). Newton passes it to V_r damped by the inertia and the stiffness.
    const Eigen::VectorXd rounding =
        by_position_.cwiseAbs() * q_.cwiseAbs() + by_velocity_.cwiseAbs() * v_.cwiseAbs();
    for (int r = 0; r < n_; ++r) {
      const double resistance = mass(r, r) + h * std::abs(by_velocity_(r, r)) +
                                h * h * std::abs(by_position_(r, r)) +
                                std::numeric_limits<double>::min();
      force_rounding_ = std::max(force_rounding_, rounding(r));
      force_velocity_rounding_ = std::max(force_velocity_rounding_, h * rounding(r) / resistance);
    }
    model.constraint_jacobian(t, q_, stage_constraint_jacobian_[j]);
    lambda_ = unknowns.segment(l_offset(j), m_);
    // d/dZ_j (G(Q_j)^T L_j) = h * [d(G^T mu)/dq at mu = L_j].
    model.constraint_force_derivative(t, q_, lambda_, constraint_force_derivative_);
    const Eigen::MatrixXd& g = stage_constraint_jacobian_[j];
    for (int i = 0; i < stages_; ++i) {
      const double a = a_(i, j);
      jacobian.block(z_offset(i), v_offset(j), n_, n_).diagonal().array() -= a;
      jacobian.block(v_offset(i), z_offset(j), n_, n_) =
          -a * (h * h * by_position_ - h * constraint_force_derivative_);
      jacobian.block(v_offset(i), v_offset(j), n_, n_) = -a * h * by_velocity_;
      jacobian.block(v_offset(i), l_offset(j), n_, m_) = a * g.transpose();
    }
    jacobian.block(z_offset(j), z_offset(j), n_, n_).diagonal().array() += 1.0;
    jacobian.block(v_offset(j), v_offset(j), n_, n_) += mass;
    if (j == 0 && first_stage_is_start_) {
      jacobian.block(l_offset(0), l_offset(0), m_, m_).setIdentity();
      continue;
    }
    for (int k = 0; k < m_; ++k) {
      const int column = position_level_[k] ? z_offset(j) : v_offset(j);
      jacobian.block(l_offset(j) + k, column, 1, n_) = g.row(k);
    }
  }
}

double RadauStageEquations::increment_norm(const Eigen::VectorXd& unknowns,
                                           const Eigen::VectorXd& increment,
                                           const NewtonOptions& options) const {
  const double h = step_size_;
  const double round_off = 100.0 * std::numeric_limits<double>::epsilon();
  const Eigen::MatrixXd& mass = model_->mass_matrix();
  double force = 0.0;
  for (const auto& f : stage_force_)
    force = std::max(force, max_abs(f));
  const double smallest_mass = n_ > 0 ? mass.diagonal().minCoeff() : 1.0;
  const double mass_size = n_ > 0 ? mass.diagonal().maxCoeff() : 0.0;

  double position_scale = max_abs(start_.q);
  double velocity_scale = std::max(max_abs(start_.v), h * force / smallest_mass);
  double multiplier_scale = std::max(max_abs(start_.lambda), force);
  double position_step = 0.0, velocity_step = 0.0, multiplier_step = 0.0;
  for (int i = 0; i < stages_; ++i) {
    position_scale = std::max(position_scale, max_abs(position(unknowns, i)));
    velocity_scale = std::max(velocity_scale, max_abs(velocity(unknowns, i)));
    multiplier_scale = std::max(multiplier_scale, max_abs(multiplier(unknowns, i)));
    position_step = std::max(position_step, h * max_abs(increment.segment(z_offset(i), n_)));
    velocity_step = std::max(velocity_step, max_abs(increment.segment(v_offset(i), n_)));
    multiplier_step = std::max(multiplier_step, max_abs(increment.segment(l_offset(i), m_)) / h);
  }
  auto weight = [&](double scale, double rounding) {
    return options.absolute_tolerance + options.relative_tolerance * scale + round_off * rounding +
           std::numeric_limits<double>::min();
  };
  // A position row that is not exactly zero in floating point (a nonlinear joint, unlike a held
  // coordinate) carries its rounding eps |q| into C / h; the Newton matrix passes that on to the
  // velocities as eps |q| / h and to lambda as eps M |q| / h^2: the index-3 round-off floor.
  // |C| / eps is the size whose rounding |C| can be, at most |q|; a held coordinate has C = 0.
  const double constraint_rounding =
      std::min(position_residual_ / std::numeric_limits<double>::epsilon(), position_scale) / h;
  const double multiplier_rounding = multiplier_scale + force_rounding_ +
                                     mass_size * (velocity_scale + constraint_rounding / h) / h;
  return std::max({position_step / weight(position_scale, position_scale),
                   velocity_step / weight(velocity_scale, velocity_scale + constraint_rounding +
                                                              force_velocity_rounding_),
                   multiplier_step / weight(multiplier_scale, multiplier_rounding)});
}

}  // namespace fsi::mbd::detail
