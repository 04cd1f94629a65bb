#include "fsi/mbd/static_analysis.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"

namespace fsi::mbd {

namespace {

// Holds the model's gravity and point loads and puts them back when the solve ends.
class LoadScaling {
 public:
  explicit LoadScaling(Model& model)
      : model_(model),
        gravity_(model.gravity()),
        loads_(model.point_loads().begin(), model.point_loads().end()) {}
  ~LoadScaling() { apply(1.0); }
  LoadScaling(const LoadScaling&) = delete;
  LoadScaling& operator=(const LoadScaling&) = delete;

  void apply(double factor) {
    if (model_.dimension() == 3) {
      model_.set_spatial_gravity(factor * gravity_);
    } else {
      model_.set_gravity(factor * Eigen::Vector2d(gravity_.head<2>()));
    }
    scaled_ = loads_;
    for (double& load : scaled_)
      load *= factor;
    model_.set_point_loads(scaled_);
  }

 private:
  Model& model_;
  Eigen::Vector3d gravity_;
  std::vector<double> loads_;
  std::vector<double> scaled_;
};

double max_abs(const Eigen::VectorXd& x) {
  return x.size() == 0 ? 0.0 : x.lpNorm<Eigen::Infinity>();
}

}  // namespace

StaticResult solve_static(Model& model, const State& start, const StaticOptions& options) {
  const int n = model.coordinate_count();
  const int m = model.constraint_count();
  FSI_ASSERT(start.q.size() == n, "the start state does not match the model");
  if (options.load_steps < 1 || options.max_iterations < 1 || !(options.tolerance > 0.0)) {
    throw Error("invalid static solver options", "static solve",
                "give at least one load step and one iteration and a positive tolerance");
  }
  for (int k = 0; k < m; ++k) {
    if (model.constraint_level(k) != ConstraintLevel::Position) {
      throw Error(model.constraint_description(k) + " is a velocity-level constraint",
                  "static solve", "a static equilibrium has position-level constraints only");
    }
  }

  StaticResult result;
  result.state.time = start.time;
  result.state.q = start.q;
  result.state.v = Eigen::VectorXd::Zero(n);
  result.state.lambda =
      start.lambda.size() == m ? Eigen::VectorXd(start.lambda) : Eigen::VectorXd::Zero(m);
  Eigen::VectorXd& q = result.state.q;
  Eigen::VectorXd& lambda = result.state.lambda;
  const double t = start.time;

  LoadScaling loads(model);
  Eigen::VectorXd force, constraint, right(n + m);
  Eigen::MatrixXd by_position, by_velocity, jacobian, force_derivative;
  Eigen::MatrixXd system(n + m, n + m);
  for (int step = 1; step <= options.load_steps; ++step) {
    const double factor = static_cast<double>(step) / options.load_steps;
    loads.apply(factor);
    bool converged = false;
    double last_step = 0.0;
    for (int iteration = 0; iteration < options.max_iterations && !converged; ++iteration) {
      model.applied_force(t, q, result.state.v, force);
      model.constraint_jacobian(t, q, jacobian);
      model.constraint_residual(t, q, result.state.v, constraint);
      model.applied_force_derivatives(t, q, result.state.v, by_position, by_velocity);
      model.constraint_force_derivative(t, q, lambda, force_derivative);
      // The constraint rows and multiplier columns are scaled by the stiffness so that the
      // pivoting of the LU sees entries of one size; unknowns (dq, dlambda / scale).
      const Eigen::MatrixXd tangent = by_position - force_derivative;
      const double scale = std::max(1.0, tangent.cwiseAbs().maxCoeff());
      system.topLeftCorner(n, n) = tangent;
      system.topRightCorner(n, m) = -scale * jacobian.transpose();
      system.bottomLeftCorner(m, n) = scale * jacobian;
      system.bottomRightCorner(m, m).setZero();
      right.head(n) = -(force - jacobian.transpose() * lambda);
      right.tail(m) = -scale * constraint;
      const Eigen::VectorXd increment = Eigen::PartialPivLU<Eigen::MatrixXd>(system).solve(right);
      if (!increment.allFinite()) break;
      const Eigen::VectorXd dq = increment.head(n);
      const Eigen::VectorXd dlambda = scale * increment.tail(m);
      q += dq;
      lambda += dlambda;
      ++result.newton_iterations;
      last_step = max_abs(dq) / (1.0 + max_abs(q));
      // Once q no longer moves beyond its round-off, the multipliers just solved the force
      // balance at it: what they still change by is the round-off of the stiffness-scaled
      // solve (scale eps, far above a small load's tolerance when EA is large), not progress.
      const bool at_round_off = last_step <= 16.0 * std::numeric_limits<double>::epsilon();
      converged = last_step <= options.tolerance &&
                  (at_round_off || max_abs(dlambda) <= options.tolerance * (1.0 + max_abs(lambda)));
    }
    if (!converged) {
      throw Error("Newton did not converge at load factor " + significant(factor, 9) +
                      " (load step " + std::to_string(step) + " of " +
                      std::to_string(options.load_steps) + "); last relative increment " +
                      significant(last_step, 9),
                  "static solve",
                  "raise StaticOptions::load_steps or max_iterations, or check that the "
                  "constraints hold the model (no free rigid-body motion)");
    }
  }
  return result;
}

std::vector<double> natural_frequencies(const ConstrainedSystem& system, const State& state,
                                        int count) {
  const int n = system.coordinate_count();
  const int m = system.constraint_count();
  FSI_ASSERT(state.q.size() == n && state.v.size() == n, "the state does not match the model");
  Eigen::MatrixXd by_position, by_velocity, jacobian, force_derivative;
  system.applied_force_derivatives(state.time, state.q, state.v, by_position, by_velocity);
  system.constraint_jacobian(state.time, state.q, jacobian);
  const Eigen::VectorXd lambda =
      state.lambda.size() == m ? Eigen::VectorXd(state.lambda) : Eigen::VectorXd::Zero(m);
  system.constraint_force_derivative(state.time, state.q, lambda, force_derivative);
  const Eigen::MatrixXd tangent = force_derivative - by_position;
  const Eigen::MatrixXd stiffness = 0.5 * (tangent + tangent.transpose());

  // An orthonormal basis Z of the null space of G: the last n - rank columns of Q in G^T = Q R.
  Eigen::MatrixXd basis;
  if (m == 0) {
    basis = Eigen::MatrixXd::Identity(n, n);
  } else {
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(jacobian.transpose());
    const int rank = static_cast<int>(qr.rank());
    const Eigen::MatrixXd q_full = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
    basis = q_full.rightCols(n - rank);
  }
  const Eigen::MatrixXd reduced_stiffness = basis.transpose() * stiffness * basis;
  const Eigen::MatrixXd reduced_mass = basis.transpose() * system.mass_matrix() * basis;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      0.5 * (reduced_stiffness + reduced_stiffness.transpose()),
      0.5 * (reduced_mass + reduced_mass.transpose()), Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) {
    throw Error("the generalised eigenproblem (K, M) did not converge", "natural frequencies",
                "check that the mass matrix is positive definite");
  }
  std::vector<double> frequencies;
  const Eigen::VectorXd& squares = solver.eigenvalues();
  for (Eigen::Index k = 0; k < squares.size() && static_cast<int>(frequencies.size()) < count;
       ++k) {
    const double omega = std::sqrt(std::abs(squares(k)));
    frequencies.push_back(std::copysign(omega, squares(k)) / (2.0 * std::numbers::pi));
  }
  return frequencies;
}

}  // namespace fsi::mbd
