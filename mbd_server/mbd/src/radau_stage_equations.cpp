#include "radau_stage_equations.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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

void RadauStageEquations::begin_step(const ConstrainedSystem& system, const State& start,
                                     double step_size) {
  system_ = &system;
  start_ = start;
  step_size_ = step_size;
  n_ = system.coordinate_count();
  m_ = system.constraint_count();
  block_ = 2 * n_ + m_;
  position_level_.resize(m_);
  for (int k = 0; k < m_; ++k)
    position_level_[k] = system.constraint_level(k) == ConstraintLevel::Position;
  released_ = system.released_rows(start.time, start.time + step_size);
  stage_force_.assign(stages_, Eigen::VectorXd::Zero(n_));
  if (sparse_) {
    stage_constraint_jacobian_.clear();
    stage_sparse_constraint_jacobian_.assign(stages_, Eigen::SparseMatrix<double>(m_, n_));
  } else {
    stage_constraint_jacobian_.assign(stages_, Eigen::MatrixXd::Zero(m_, n_));
    stage_sparse_constraint_jacobian_.clear();
  }
}

void RadauStageEquations::predict(Eigen::VectorXd& unknowns) const {
  unknowns.resize(size());
  for (int i = 0; i < stages_; ++i) {
    unknowns.segment(z_offset(i), n_) = c_(i) * start_.v;
    unknowns.segment(v_offset(i), n_) = start_.v;
    unknowns.segment(l_offset(i), m_) = step_size_ * start_.lambda;
    for (int k = 0; k < m_; ++k) {
      if (released_[k]) unknowns(l_offset(i) + k) = 0.0;
    }
  }
}

bool RadauStageEquations::any_released() const {
  return std::find(released_.begin(), released_.end(), true) != released_.end();
}

void RadauStageEquations::drop_released(Eigen::MatrixXd& jacobian) const {
  for (int k = 0; k < m_; ++k) {
    if (released_[k]) jacobian.row(k).setZero();
  }
}

void RadauStageEquations::drop_released(Eigen::SparseMatrix<double>& jacobian) const {
  if (!any_released()) return;
  jacobian.prune([this](Eigen::Index row, Eigen::Index, double) { return !released_[row]; });
}

void RadauStageEquations::drop_released(Eigen::VectorXd& multipliers) const {
  for (int k = 0; k < m_; ++k) {
    if (released_[k]) multipliers(k) = 0.0;
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
  FSI_ASSERT(system_ != nullptr && unknowns.size() == size(), "stage equations not bound");
  const ConstrainedSystem& system = *system_;
  const double h = step_size_;
  for (int j = 0; j < stages_; ++j) {
    q_ = position(unknowns, j);
    v_ = velocity(unknowns, j);
    system.applied_force(stage_time(j), q_, v_, stage_force_[j]);
    if (sparse_) {
      system.constraint_jacobian(stage_time(j), q_, stage_sparse_constraint_jacobian_[j]);
      drop_released(stage_sparse_constraint_jacobian_[j]);
    } else {
      system.constraint_jacobian(stage_time(j), q_, stage_constraint_jacobian_[j]);
      drop_released(stage_constraint_jacobian_[j]);
    }
  }
  residual.resize(size());
  position_residual_ = 0.0;
  for (int i = 0; i < stages_; ++i) {
    auto kinematic = residual.segment(z_offset(i), n_);
    auto dynamic = residual.segment(v_offset(i), n_);
    kinematic = unknowns.segment(z_offset(i), n_);
    if (sparse_) {
      dynamic = system.sparse_mass_matrix() * (unknowns.segment(v_offset(i), n_) - start_.v);
    } else {
      dynamic = system.mass_matrix() * (unknowns.segment(v_offset(i), n_) - start_.v);
    }
    for (int j = 0; j < stages_; ++j) {
      kinematic -= a_(i, j) * unknowns.segment(v_offset(j), n_);
      if (sparse_) {
        dynamic -=
            a_(i, j) * (h * stage_force_[j] - stage_sparse_constraint_jacobian_[j].transpose() *
                                                  unknowns.segment(l_offset(j), m_));
      } else {
        dynamic -= a_(i, j) * (h * stage_force_[j] - stage_constraint_jacobian_[j].transpose() *
                                                         unknowns.segment(l_offset(j), m_));
      }
    }
    constraint_rows_residual(unknowns, i, residual);
  }
}

void RadauStageEquations::constraint_rows_residual(const Eigen::VectorXd& unknowns, int stage,
                                                   Eigen::VectorXd& residual) {
  const ConstrainedSystem& system = *system_;
  const double h = step_size_;
  auto rows = residual.segment(l_offset(stage), m_);
  if (stage == 0 && first_stage_is_start_) {
    rows = unknowns.segment(l_offset(0), m_) - h * start_.lambda;
  } else if (index2_) {
    // G V + dC/dt for position rows, G V - g for velocity rows: all on velocity level.
    q_ = position(unknowns, stage);
    v_ = velocity(unknowns, stage);
    system.constraint_rate(stage_time(stage), q_, v_, rate_);
    rows = rate_;
  } else {
    q_ = position(unknowns, stage);
    v_ = velocity(unknowns, stage);
    system.constraint_residual(stage_time(stage), q_, v_, constraint_);
    for (int k = 0; k < m_; ++k) {
      rows(k) = position_level_[k] ? constraint_(k) / h : constraint_(k);
      if (position_level_[k] && !released_[k])
        position_residual_ = std::max(position_residual_, std::abs(constraint_(k)));
    }
  }
  for (int k = 0; k < m_; ++k) {
    if (released_[k]) rows(k) = unknowns(l_offset(stage) + k);
  }
}

void RadauStageEquations::jacobian(const Eigen::VectorXd& unknowns, Eigen::MatrixXd& jacobian) {
  FSI_ASSERT(system_ != nullptr && unknowns.size() == size(), "stage equations not bound");
  const ConstrainedSystem& system = *system_;
  const double h = step_size_;
  const Eigen::MatrixXd& mass = system.mass_matrix();
  jacobian.setZero(size(), size());
  force_rounding_ = 0.0;
  force_velocity_rounding_ = 0.0;
  for (int j = 0; j < stages_; ++j) {
    q_ = position(unknowns, j);
    v_ = velocity(unknowns, j);
    const double t = stage_time(j);
    system.applied_force_derivatives(t, q_, v_, by_position_, by_velocity_);
    // F_r is evaluated from coordinates of size |q|: its rounding is ~eps sum_k |dF_r/dq_k| |q_k|
    // (plus the same for v). Newton passes it to V_r damped by the inertia and the stiffness.
    add_force_rounding(
        by_position_.cwiseAbs() * q_.cwiseAbs() + by_velocity_.cwiseAbs() * v_.cwiseAbs(),
        by_position_.diagonal(), by_velocity_.diagonal());
    system.constraint_jacobian(t, q_, stage_constraint_jacobian_[j]);
    drop_released(stage_constraint_jacobian_[j]);
    lambda_ = unknowns.segment(l_offset(j), m_);
    drop_released(lambda_);
    // d/dZ_j (G(Q_j)^T L_j) = h * [d(G^T mu)/dq at mu = L_j].
    system.constraint_force_derivative(t, q_, lambda_, constraint_force_derivative_);
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
    } else if (index2_) {
      // d(G V)/dV = G; d(G(Q) V)/dZ = h d(G v)/dq at v = V_j.
      jacobian.block(l_offset(j), v_offset(j), m_, n_) = g;
      velocity_derivative_.setZero(m_, n_);
      DenseMatrixSink sink(velocity_derivative_);
      system.add_constraint_velocity_derivative(t, q_, v_, sink);
      drop_released(velocity_derivative_);
      jacobian.block(l_offset(j), z_offset(j), m_, n_) = h * velocity_derivative_;
    } else {
      for (int k = 0; k < m_; ++k) {
        const int column = position_level_[k] ? z_offset(j) : v_offset(j);
        jacobian.block(l_offset(j) + k, column, 1, n_) = g.row(k);
      }
    }
    // A released row is L_jk = 0: its G row is dropped above, leaving the unit entry.
    for (int k = 0; k < m_; ++k) {
      if (released_[k]) jacobian(l_offset(j) + k, l_offset(j) + k) = 1.0;
    }
  }
}

void RadauStageEquations::add_force_rounding(const Eigen::VectorXd& rounding,
                                             const Eigen::VectorXd& by_position_diagonal,
                                             const Eigen::VectorXd& by_velocity_diagonal) {
  const double h = step_size_;
  const Eigen::VectorXd& mass = system_->mass_diagonal();
  for (int r = 0; r < n_; ++r) {
    const double resistance = mass(r) + h * std::abs(by_velocity_diagonal(r)) +
                              h * h * std::abs(by_position_diagonal(r)) +
                              std::numeric_limits<double>::min();
    force_rounding_ = std::max(force_rounding_, rounding(r));
    force_velocity_rounding_ = std::max(force_velocity_rounding_, h * rounding(r) / resistance);
  }
}

void RadauStageEquations::jacobian(const Eigen::VectorXd& unknowns,
                                   Eigen::SparseMatrix<double>& jacobian) {
  FSI_ASSERT(system_ != nullptr && unknowns.size() == size(), "stage equations not bound");
  const ConstrainedSystem& system = *system_;
  const double h = step_size_;
  const Eigen::SparseMatrix<double>& mass = system.sparse_mass_matrix();
  using Iterator = Eigen::SparseMatrix<double>::InnerIterator;
  // The same blocks as the dense jacobian(), entry by entry.
  triplets_.clear();
  force_rounding_ = 0.0;
  force_velocity_rounding_ = 0.0;
  Eigen::VectorXd rounding(n_);
  for (int j = 0; j < stages_; ++j) {
    q_ = position(unknowns, j);
    v_ = velocity(unknowns, j);
    const double t = stage_time(j);
    system.applied_force_derivatives(t, q_, v_, sparse_by_position_, sparse_by_velocity_);
    rounding = sparse_by_position_.cwiseAbs() * q_.cwiseAbs() +
               sparse_by_velocity_.cwiseAbs() * v_.cwiseAbs();
    add_force_rounding(rounding, sparse_by_position_.diagonal(), sparse_by_velocity_.diagonal());
    Eigen::SparseMatrix<double>& g = stage_sparse_constraint_jacobian_[j];
    system.constraint_jacobian(t, q_, g);
    drop_released(g);
    lambda_ = unknowns.segment(l_offset(j), m_);
    drop_released(lambda_);
    system.constraint_force_derivative(t, q_, lambda_, sparse_constraint_force_derivative_);
    for (int i = 0; i < stages_; ++i) {
      const double a = a_(i, j);
      if (a == 0.0) continue;
      for (int r = 0; r < n_; ++r)
        triplets_.emplace_back(z_offset(i) + r, v_offset(j) + r, -a);
      for (int c = 0; c < n_; ++c) {
        for (Iterator it(sparse_by_position_, c); it; ++it)
          triplets_.emplace_back(v_offset(i) + it.row(), z_offset(j) + c, -a * h * h * it.value());
        for (Iterator it(sparse_constraint_force_derivative_, c); it; ++it)
          triplets_.emplace_back(v_offset(i) + it.row(), z_offset(j) + c, a * h * it.value());
        for (Iterator it(sparse_by_velocity_, c); it; ++it)
          triplets_.emplace_back(v_offset(i) + it.row(), v_offset(j) + c, -a * h * it.value());
        for (Iterator it(g, c); it; ++it)
          triplets_.emplace_back(v_offset(i) + c, l_offset(j) + it.row(), a * it.value());
      }
    }
    for (int r = 0; r < n_; ++r)
      triplets_.emplace_back(z_offset(j) + r, z_offset(j) + r, 1.0);
    for (int c = 0; c < n_; ++c) {
      for (Iterator it(mass, c); it; ++it)
        triplets_.emplace_back(v_offset(j) + it.row(), v_offset(j) + c, it.value());
    }
    if (j == 0 && first_stage_is_start_) {
      for (int k = 0; k < m_; ++k)
        triplets_.emplace_back(l_offset(0) + k, l_offset(0) + k, 1.0);
      continue;
    }
    // A released row is L_jk = 0 (g has no entries in its row any more).
    for (int k = 0; k < m_; ++k) {
      if (released_[k]) triplets_.emplace_back(l_offset(j) + k, l_offset(j) + k, 1.0);
    }
    if (index2_) {
      for (int c = 0; c < n_; ++c) {
        for (Iterator it(g, c); it; ++it)
          triplets_.emplace_back(l_offset(j) + it.row(), v_offset(j) + c, it.value());
      }
      TripletSink velocity_derivative;
      system.add_constraint_velocity_derivative(t, q_, v_, velocity_derivative);
      for (const auto& entry : velocity_derivative.triplets()) {
        if (released_[entry.row()]) continue;
        triplets_.emplace_back(l_offset(j) + entry.row(), z_offset(j) + entry.col(),
                               h * entry.value());
      }
      continue;
    }
    for (int c = 0; c < n_; ++c) {
      for (Iterator it(g, c); it; ++it) {
        const int k = static_cast<int>(it.row());
        triplets_.emplace_back(l_offset(j) + k,
                               (position_level_[k] ? z_offset(j) : v_offset(j)) + c, it.value());
      }
    }
  }
  jacobian.resize(size(), size());
  jacobian.setFromTriplets(triplets_.begin(), triplets_.end());
  // Exact zeros (a joint at angle 0, a body at rest) are dropped, as sparseView() of the dense
  // matrix does: the COLAMD ordering and so the rounding of the solve stay those of the dense
  // matrix's non-zeros. A pattern that changes with them is analysed again (radau_iia.cpp).
  jacobian.prune(0.0);
}

bool RadauStageEquations::residual_at_floor(const Eigen::VectorXd& unknowns,
                                            const Eigen::VectorXd& residual,
                                            const Eigen::VectorXd& solve_rounding) const {
  // Rounding of a sum of terms is a few eps times the sum of their magnitudes; the factor leaves
  // room for the number of terms and operations per row while staying far below the residuals
  // of an iteration that still converges.
  constexpr double kFloorMultiple = 32.0;
  const double eps = std::numeric_limits<double>::epsilon();
  const double h = step_size_;
  if (!residual.allFinite()) return false;
  std::vector<Eigen::VectorXd> constraint_forces(stages_);
  for (int j = 0; j < stages_; ++j) {
    const Eigen::VectorXd impulses = unknowns.segment(l_offset(j), m_).cwiseAbs();
    constraint_forces[j] =
        sparse_ ? Eigen::VectorXd(stage_sparse_constraint_jacobian_[j].cwiseAbs().transpose() *
                                  impulses)
                : Eigen::VectorXd(stage_constraint_jacobian_[j].cwiseAbs().transpose() * impulses);
  }
  // Partial pivoting mixes the rows, so the solve's backward error is normwise.
  const double from_solve =
      solve_rounding.size() == residual.size() ? max_abs(solve_rounding) : 0.0;
  auto within = [&](Eigen::Index row, double magnitude) {
    return std::abs(residual(row)) <= kFloorMultiple * eps * (magnitude + from_solve);
  };
  for (int i = 0; i < stages_; ++i) {
    const Eigen::VectorXd z = unknowns.segment(z_offset(i), n_).cwiseAbs();
    const Eigen::VectorXd v = unknowns.segment(v_offset(i), n_).cwiseAbs();
    Eigen::VectorXd kinematic = z;
    Eigen::VectorXd dynamic =
        sparse_
            ? Eigen::VectorXd(system_->sparse_mass_matrix().cwiseAbs() * (v + start_.v.cwiseAbs()))
            : Eigen::VectorXd(system_->mass_matrix().cwiseAbs() * (v + start_.v.cwiseAbs()));
    for (int j = 0; j < stages_; ++j) {
      const double weight = std::abs(a_(i, j));
      kinematic += weight * unknowns.segment(v_offset(j), n_).cwiseAbs();
      dynamic += weight * (h * (stage_force_[j].cwiseAbs().array() + force_rounding_).matrix() +
                           constraint_forces[j]);
    }
    for (int k = 0; k < n_; ++k) {
      if (!within(z_offset(i) + k, kinematic(k)) || !within(v_offset(i) + k, dynamic(k))) {
        return false;
      }
    }
    if (i == 0 && first_stage_is_start_) {
      for (int k = 0; k < m_; ++k) {
        const double start_impulse = h * std::abs(start_.lambda(k));
        if (!within(l_offset(0) + k, std::abs(unknowns(l_offset(0) + k)) + start_impulse)) {
          return false;
        }
      }
      continue;
    }
    const Eigen::VectorXd q = position(unknowns, i).cwiseAbs();
    const double largest_q = max_abs(q), largest_v = max_abs(v);
    Eigen::VectorXd by_position, by_velocity, row_sums;
    if (sparse_) {
      const Eigen::SparseMatrix<double> g = stage_sparse_constraint_jacobian_[i].cwiseAbs();
      by_position = g * q;
      by_velocity = g * v;
      row_sums = g * Eigen::VectorXd::Ones(n_);
    } else {
      const Eigen::MatrixXd g = stage_constraint_jacobian_[i].cwiseAbs();
      by_position = g * q;
      by_velocity = g * v;
      row_sums = g.rowwise().sum();
    }
    for (int k = 0; k < m_; ++k) {
      if (released_[k]) {
        if (residual(l_offset(i) + k) != 0.0) return false;
        continue;
      }
      // Position rows are C / h (index 3); velocity rows and the index-2 rates are G V - g.
      const bool position_row = position_level_[k] && !index2_;
      const double magnitude = position_row ? (by_position(k) + row_sums(k) * largest_q) / h
                                            : by_velocity(k) + row_sums(k) * largest_v;
      if (!within(l_offset(i) + k, magnitude)) return false;
    }
  }
  return true;
}

double RadauStageEquations::increment_norm(const Eigen::VectorXd& unknowns,
                                           const Eigen::VectorXd& increment,
                                           const NewtonOptions& options) const {
  const double h = step_size_;
  const double round_off = 100.0 * std::numeric_limits<double>::epsilon();
  const Eigen::VectorXd& mass = system_->mass_diagonal();
  double force = 0.0;
  for (const auto& f : stage_force_)
    force = std::max(force, max_abs(f));
  const double smallest_mass = n_ > 0 ? mass.minCoeff() : 1.0;
  const double mass_size = n_ > 0 ? mass.maxCoeff() : 0.0;

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
