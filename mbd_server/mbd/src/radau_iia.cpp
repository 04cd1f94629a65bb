#include <cmath>
#include <cstdio>
#include <limits>

#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"

namespace fsi::mbd {

ButcherTableau radau_iia(int stages) {
  ButcherTableau t;
  const double r6 = std::sqrt(6.0);
  switch (stages) {
    case 1:
      t.a = Eigen::MatrixXd::Constant(1, 1, 1.0);
      t.c = Eigen::VectorXd::Constant(1, 1.0);
      t.order = 1;
      break;
    case 2:
      t.a.resize(2, 2);
      t.a << 5.0 / 12.0, -1.0 / 12.0, 3.0 / 4.0, 1.0 / 4.0;
      t.c.resize(2);
      t.c << 1.0 / 3.0, 1.0;
      t.order = 3;
      break;
    case 3:
      t.a.resize(3, 3);
      t.a << (88.0 - 7.0 * r6) / 360.0, (296.0 - 169.0 * r6) / 1800.0, (-2.0 + 3.0 * r6) / 225.0,
          (296.0 + 169.0 * r6) / 1800.0, (88.0 + 7.0 * r6) / 360.0, (-2.0 - 3.0 * r6) / 225.0,
          (16.0 - r6) / 36.0, (16.0 + r6) / 36.0, 1.0 / 9.0;
      t.c.resize(3);
      t.c << (4.0 - r6) / 10.0, (4.0 + r6) / 10.0, 1.0;
      t.order = 5;
      break;
    default:
      throw Error("Radau IIA with " + std::to_string(stages) + " stages is not available",
                  "SolverOptions.Timeint.stages", "choose 1, 2 or 3 stages (orders 1, 3, 5)");
  }
  t.b = t.a.row(stages - 1).transpose();  // stiffly accurate
  return t;
}

void IntegratorStatistics::add(const StepStatistics& step) {
  ++steps;
  newton_iterations += step.newton_iterations;
  jacobian_evaluations += step.jacobian_evaluations;
  factorisations += step.factorisations;
}

// Unknowns per stage i: [Q_i (n), V_i (n), L_i = h Lambda_i (m)]. Position-level constraint rows
// are divided by h and the multipliers carry a factor h, so every block of the Newton matrix is
// O(1) for small steps (otherwise the constraint rows would scale like h and the multiplier
// columns like h, and lambda would lose digits).
struct RadauIIA::Workspace {
  int n = -1;
  int m = -1;
  double step_size = 0.0;
  Eigen::VectorXd x;  // stage unknowns
  Eigen::VectorXd residual;
  Eigen::MatrixXd jacobian;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  bool factorised = false;
  int steps_with_factorisation = 0;
  Eigen::MatrixXd stiffness;  // dF/dq
  Eigen::MatrixXd damping;    // dF/dv
  Eigen::VectorXd force, perturbed, q, v, constraint;
  std::vector<Eigen::VectorXd> stage_force;
};

RadauIIA::RadauIIA(int stages, const NewtonOptions& options)
    : tableau_(radau_iia(stages)), options_(options), work_(std::make_unique<Workspace>()) {
  if (options_.relative_tolerance <= 0.0 || options_.max_iterations < 1) {
    throw Error("Newton tolerance must be > 0 and max iterations >= 1", "SolverOptions.Newton",
                "use e.g. relative_tolerance = 1e-10, max_iterations = 12");
  }
}
RadauIIA::~RadauIIA() = default;
RadauIIA::RadauIIA(RadauIIA&&) noexcept = default;

const ButcherTableau& RadauIIA::tableau() const {
  return tableau_;
}
const IntegratorStatistics& RadauIIA::statistics() const {
  return statistics_;
}

namespace {

// Forward-difference derivative of the applied force with respect to q and v.
void force_derivatives(const Model& model, double time, const Eigen::VectorXd& q,
                       const Eigen::VectorXd& v, Eigen::MatrixXd& stiffness,
                       Eigen::MatrixXd& damping, Eigen::VectorXd& base, Eigen::VectorXd& shifted) {
  const int n = static_cast<int>(q.size());
  model.applied_force(time, q, v, base);
  stiffness.resize(n, n);
  damping.resize(n, n);
  Eigen::VectorXd qq = q;
  Eigen::VectorXd vv = v;
  const double root_epsilon = std::sqrt(std::numeric_limits<double>::epsilon());
  for (int j = 0; j < n; ++j) {
    const double dq = root_epsilon * std::max(1.0, std::abs(q(j)));
    qq(j) += dq;
    model.applied_force(time, qq, v, shifted);
    stiffness.col(j) = (shifted - base) / dq;
    qq(j) = q(j);
    const double dv = root_epsilon * std::max(1.0, std::abs(v(j)));
    vv(j) += dv;
    model.applied_force(time, q, vv, shifted);
    damping.col(j) = (shifted - base) / dv;
    vv(j) = v(j);
  }
}

}  // namespace

StepStatistics RadauIIA::step(const Model& model, State& state, double h) {
  Workspace& w = *work_;
  const auto& A = tableau_.a;
  const auto& c = tableau_.c;
  const int s = static_cast<int>(c.size());
  const int n = model.coordinate_count();
  const int m = model.constraint_count();
  const int block = 2 * n + m;
  const Eigen::MatrixXd& M = model.mass_matrix();
  const Eigen::MatrixXd& G = model.constraint_jacobian();
  std::vector<bool> position_row(m);
  for (int k = 0; k < m; ++k)
    position_row[k] = model.constraints()[k].level == ConstraintLevel::Position;
  StepStatistics stats;

  // --- initialise: sizes and validity of a kept factorisation ---
  if (!(h > 0.0) || !std::isfinite(h)) {
    throw Error("step size must be positive, got " + std::to_string(h), "integrator",
                "set SolverOptions.Timeint.step_size > 0");
  }
  if (w.n != n || w.m != m || w.step_size != h) {
    w.n = n;
    w.m = m;
    w.step_size = h;
    w.factorised = false;
    w.x.resize(s * block);
    w.stage_force.assign(s, Eigen::VectorXd::Zero(n));
  }
  const double t0 = state.time;

  // --- predict: constant velocity, previous multipliers ---
  auto Q = [&](int i) { return w.x.segment(i * block, n); };
  auto V = [&](int i) { return w.x.segment(i * block + n, n); };
  auto L = [&](int i) { return w.x.segment(i * block + 2 * n, m); };
  auto predict = [&] {
    for (int i = 0; i < s; ++i) {
      Q(i) = state.q + h * c(i) * state.v;
      V(i) = state.v;
      L(i) = h * state.lambda;
    }
  };

  auto evaluate_residual = [&] {
    w.residual.resize(s * block);
    for (int j = 0; j < s; ++j) {
      w.q = Q(j);
      w.v = V(j);
      model.applied_force(t0 + c(j) * h, w.q, w.v, w.stage_force[j]);
    }
    for (int i = 0; i < s; ++i) {
      auto rq = w.residual.segment(i * block, n);
      auto rv = w.residual.segment(i * block + n, n);
      rq = Q(i) - state.q;
      rv = M * (V(i) - state.v);
      for (int j = 0; j < s; ++j) {
        rq -= h * A(i, j) * V(j);
        rv -= A(i, j) * (h * w.stage_force[j] - G.transpose() * L(j));
      }
      w.q = Q(i);
      w.v = V(i);
      model.constraint_residual(t0 + c(i) * h, w.q, w.v, w.constraint);
      for (int k = 0; k < m; ++k) {
        w.residual(i * block + 2 * n + k) = position_row[k] ? w.constraint(k) / h : w.constraint(k);
      }
    }
  };

  auto build_jacobian = [&] {
    w.q = Q(0);
    w.v = V(0);
    force_derivatives(model, t0 + c(0) * h, w.q, w.v, w.stiffness, w.damping, w.force, w.perturbed);
    w.jacobian.setZero(s * block, s * block);
    for (int i = 0; i < s; ++i) {
      const int row = i * block;
      w.jacobian.block(row, row, n, n).setIdentity();
      w.jacobian.block(row + n, row + n, n, n) = M;
      for (int j = 0; j < s; ++j) {
        const int col = j * block;
        w.jacobian.block(row, col + n, n, n).diagonal().array() -= h * A(i, j);
        w.jacobian.block(row + n, col, n, n) -= h * A(i, j) * w.stiffness;
        w.jacobian.block(row + n, col + n, n, n) -= h * A(i, j) * w.damping;
        w.jacobian.block(row + n, col + 2 * n, n, m) += A(i, j) * G.transpose();
      }
      for (int k = 0; k < m; ++k) {
        if (position_row[k]) {
          w.jacobian.block(row + 2 * n + k, row, 1, n) = G.row(k) / h;
        } else {
          w.jacobian.block(row + 2 * n + k, row + n, 1, n) = G.row(k);
        }
      }
    }
    ++stats.jacobian_evaluations;
    w.lu.compute(w.jacobian);
    ++stats.factorisations;
    w.factorised = true;
    w.steps_with_factorisation = 0;
  };

  // Increment size relative to the stage values, block by block (positions, velocities,
  // scaled multipliers); <= 1 means converged. A block that is exactly zero (a held body has
  // V = 0) is measured against what one step can change it by: h F / m for velocities, h F for
  // the scaled multipliers.
  const double smallest_mass = M.diagonal().minCoeff();
  auto increment_error = [&](const Eigen::VectorXd& delta) {
    double force_scale = 0.0;
    for (const auto& f : w.stage_force)
      force_scale = std::max(force_scale, f.cwiseAbs().maxCoeff());
    double scale[3] = {0.0, state.v.cwiseAbs().maxCoeff(), h * force_scale};
    scale[1] = std::max(scale[1], h * force_scale / smallest_mass);
    for (int i = 0; i < s; ++i) {
      scale[0] = std::max(scale[0], Q(i).cwiseAbs().maxCoeff());
      scale[1] = std::max(scale[1], V(i).cwiseAbs().maxCoeff());
      if (m > 0) scale[2] = std::max(scale[2], L(i).cwiseAbs().maxCoeff());
    }
    scale[0] = std::max(scale[0], h * scale[1]);
    double error = 0.0;
    const double tiny = std::numeric_limits<double>::min();
    for (int i = 0; i < s; ++i) {
      for (int k = 0; k < block; ++k) {
        const int kind = k < n ? 0 : (k < 2 * n ? 1 : 2);
        const double x = std::abs(w.x(i * block + k));
        const double weight = options_.relative_tolerance * (x + scale[kind]) + tiny;
        error = std::max(error, std::abs(delta(i * block + k)) / weight);
      }
    }
    return error;
  };

  const bool full_newton = options_.max_modified_newton_steps <= 0;
  bool converged = false;
  double last_error = 0.0;
  for (int attempt = 0; attempt < 2 && !converged; ++attempt) {
    predict();
    bool fresh = false;
    if (!w.factorised || attempt > 0) {
      build_jacobian();
      fresh = true;
    }
    double previous = std::numeric_limits<double>::infinity();
    for (int iteration = 1; iteration <= options_.max_iterations; ++iteration) {
      // --- Newton increment ---
      evaluate_residual();
      if (!w.residual.allFinite()) break;
      if (full_newton && iteration > 1) {
        build_jacobian();
        fresh = true;
      }
      const Eigen::VectorXd delta = -w.lu.solve(w.residual);
      w.x += delta;
      ++stats.newton_iterations;
      last_error = increment_error(delta);
      if (!std::isfinite(last_error)) break;
      if (last_error <= 1.0) {
        converged = true;
        break;
      }
      // Slow contraction with an old Jacobian: take a new one at the current iterate.
      if (iteration > 1 && last_error > options_.max_contraction * previous && !fresh) {
        build_jacobian();
        fresh = true;
      }
      previous = last_error;
    }
    if (!converged && fresh) break;  // a fresh Jacobian did not help: give up
  }

  // --- accept / reject ---
  if (!converged) {
    w.factorised = false;
    char text[256];
    std::snprintf(text, sizeof text,
                  "Newton iterations of Radau IIA (%d stages) did not converge at t = %.9g s with "
                  "step %.3g s (scaled increment %.3g after %d iterations)",
                  s, t0, h, last_error, options_.max_iterations);
    throw Error(text, "multibody integration",
                "reduce SolverOptions.Timeint.step_size, check that constraints are consistent "
                "and loads finite, or raise SolverOptions.Newton.max_iterations");
  }

  // --- finalise: the last stage is the solution (stiffly accurate) ---
  state.q = Q(s - 1);
  state.v = V(s - 1);
  state.lambda = L(s - 1) / h;
  state.time = t0 + h;
  if (++w.steps_with_factorisation >= options_.max_modified_newton_steps) w.factorised = false;
  statistics_.add(stats);
  return stats;
}

}  // namespace fsi::mbd
