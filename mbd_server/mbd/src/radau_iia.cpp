// Newton driver of Radau IIA: one step runs the named stages
//   initialise -> predict -> Newton increments -> accept/reject -> finalise.
// The stage equations and their scaling live in radau_stage_equations.{hpp,cpp}.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"
#include "integrand_check.hpp"
#include "newton_convergence.hpp"
#include "radau_stage_equations.hpp"

namespace fsi::mbd {

void IntegratorStatistics::add(const StepStatistics& step) {
  ++steps;
  newton_iterations += static_cast<std::uint64_t>(step.newton_iterations);
  jacobian_evaluations += static_cast<std::uint64_t>(step.jacobian_evaluations);
  factorisations += static_cast<std::uint64_t>(step.factorisations);
  retries += static_cast<std::uint64_t>(step.retries);
}

namespace {

void validate(const RadauOptions& options) {
  const NewtonOptions& newton = options.newton;
  std::string problems;
  if (!(newton.relative_tolerance > 0.0 && newton.relative_tolerance < 1.0)) {
    problems += " relative_tolerance must be in (0, 1);";
  }
  if (!(newton.absolute_tolerance >= 0.0 && std::isfinite(newton.absolute_tolerance))) {
    problems += " absolute_tolerance must be >= 0;";
  }
  if (newton.max_iterations < 1) problems += " max_iterations must be >= 1;";
  if (newton.sparse_threshold < 1) problems += " sparse_threshold must be >= 1;";
  if (newton.max_modified_newton_steps < 0) problems += " max_modified_newton_steps must be >= 0;";
  if (!(newton.max_contraction > 0.0 && newton.max_contraction < 1.0)) {
    problems += " max_contraction must be in (0, 1);";
  }
  if (!problems.empty()) {
    problems.pop_back();
    throw Error("invalid Newton options:" + problems, "integrator options",
                "use e.g. relative_tolerance = 1e-10, max_iterations = 12, "
                "max_modified_newton_steps = 20, max_contraction = 0.5");
  }
}

// How one Newton attempt ended, for the error message.
struct Attempt {
  bool converged = false;
  int iterations = 0;
  double increment = std::numeric_limits<double>::infinity();
  double residual = std::numeric_limits<double>::infinity();
  const char* reason = "";
  // What the user should change; empty: the general advice (non-finite values).
  std::string advice;
};

}  // namespace

struct RadauIIA::Workspace {
  ButcherTableau tableau;
  NewtonOptions options;
  IntegratorStatistics statistics;
  StepStages last_stages;
  Integrand integrand;
  Eigen::VectorXd step_integral, integrand_values;
  detail::RadauStageEquations equations;
  Eigen::VectorXd unknowns, residual, increment, previous_increment, solve_rounding;
  Eigen::MatrixXd jacobian;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  Eigen::SparseMatrix<double> sparse_jacobian;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> sparse_lu;
  bool sparse = false;    // the kept factorisation is sparse_lu
  bool singular = false;  // SparseLU found the matrix singular
  // The pattern sparse_lu analysed (COLAMD ordering, elimination tree): fixed while the model and
  // h are, so refreshes only factorize; a changed pattern (a point load switched on, a
  // different model) is analysed again.
  bool pattern_analysed = false;
  std::vector<int> analysed_outer, analysed_inner;
  // What the kept factorisation belongs to.
  bool factorised = false;
  const ConstrainedSystem* factorised_system = nullptr;
  int factorised_size = -1;
  double factorised_step_size = 0.0;
  std::vector<bool> factorised_released;  // a release changes the Newton matrix's rows
  int steps_with_factorisation = 0;
  double last_contraction = 0.0;
  detail::NewtonConvergence convergence;
  const ConstrainedSystem* current_system = nullptr;
  double current_step_size = 0.0;

  explicit Workspace(const RadauOptions& o)
      : tableau(butcher_tableau(o.family, o.stages)),
        options(o.newton),
        equations(tableau),
        convergence(o.newton.relative_tolerance),
        constraint_form(o.constraint_form) {}
  ConstraintForm constraint_form;

  bool full_newton() const { return options.max_modified_newton_steps == 0; }
  // Steps taken in full Newton after one that only full Newton could take (step_without_release).
  static constexpr int kFullNewtonSteps = 20;
  int full_newton_steps_left = 0;

  // --- initialise: check the input, bind the step, keep or drop the factorisation ---
  void initialise(const ConstrainedSystem& system, const State& state, double h) {
    if (!(h > 0.0) || !std::isfinite(h)) {
      char text[96];
      std::snprintf(text, sizeof text, "step size must be positive and finite, got %g", h);
      throw Error(text, "Radau IIA step", "give a positive step size");
    }
    if (state.q.size() != system.coordinate_count() ||
        state.v.size() != system.coordinate_count() ||
        state.lambda.size() != system.constraint_count()) {
      throw Error("the state does not match the model (" + std::to_string(state.q.size()) +
                      " coordinates, " + std::to_string(state.lambda.size()) + " multipliers for " +
                      std::to_string(system.coordinate_count()) + " and " +
                      std::to_string(system.constraint_count()) + ")",
                  "Radau IIA step", "start from Model::initial_state() of this model");
    }
    // Automatic: SparseLU from sparse_threshold unknowns on; the stage equations then use the
    // sparse M and G as well.
    const int size = system.constraint_count() + 2 * system.coordinate_count();
    equations.set_constraint_form(constraint_form);
    equations.set_sparse(options.linear_solver == LinearSolver::Sparse ||
                         (options.linear_solver == LinearSolver::Automatic &&
                          equations.stages() * size >= options.sparse_threshold));
    equations.begin_step(system, state, h);
    current_system = &system;
    current_step_size = h;
    if (factorised_system != &system || factorised_size != equations.size() ||
        factorised_step_size != h || factorised_released != equations.released()) {
      factorised = false;
    }
  }

  // --- predict ---
  void predict() { equations.predict(unknowns); }

  void refactorise(StepStatistics& stats) {
    ++stats.jacobian_evaluations;
    sparse = equations.sparse();
    if (sparse) {
      equations.jacobian(unknowns, sparse_jacobian);
      if (!same_pattern()) {
        sparse_lu.analyzePattern(sparse_jacobian);
        keep_pattern();
      }
      sparse_lu.factorize(sparse_jacobian);
      singular = sparse_lu.info() != Eigen::Success;
    } else {
      equations.jacobian(unknowns, jacobian);
      lu.compute(jacobian);
    }
    ++stats.factorisations;
    factorised = true;
    factorised_system = current_system;
    factorised_size = equations.size();
    factorised_step_size = current_step_size;
    factorised_released = equations.released();
    steps_with_factorisation = 0;
  }

  bool same_pattern() const {
    const Eigen::Index columns = sparse_jacobian.outerSize();
    const Eigen::Index entries = sparse_jacobian.nonZeros();
    return pattern_analysed && static_cast<Eigen::Index>(analysed_outer.size()) == columns + 1 &&
           static_cast<Eigen::Index>(analysed_inner.size()) == entries &&
           std::equal(analysed_outer.begin(), analysed_outer.end(),
                      sparse_jacobian.outerIndexPtr()) &&
           std::equal(analysed_inner.begin(), analysed_inner.end(),
                      sparse_jacobian.innerIndexPtr());
  }
  void keep_pattern() {
    const Eigen::Index columns = sparse_jacobian.outerSize();
    analysed_outer.assign(sparse_jacobian.outerIndexPtr(),
                          sparse_jacobian.outerIndexPtr() + columns + 1);
    analysed_inner.assign(sparse_jacobian.innerIndexPtr(),
                          sparse_jacobian.innerIndexPtr() + sparse_jacobian.nonZeros());
    pattern_analysed = true;
  }

  // --- Newton increments of one attempt, from the prediction ---
  // Convergence, round-off and divergence are judged by detail::NewtonConvergence.
  // full: a fresh matrix in every iteration (full Newton), whatever the options say.
  Attempt iterate(bool fresh_start, StepStatistics& stats, bool full = false) {
    Attempt attempt;
    bool fresh = fresh_start;
    if (fresh) refactorise(stats);
    convergence.restart();
    last_contraction = 0.0;
    for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
      equations.residual(unknowns, residual);
      attempt.residual = residual.lpNorm<Eigen::Infinity>();
      if (!residual.allFinite()) {
        attempt.reason = "the stage equations are not finite (forces or constraints gave NaN/inf)";
        return attempt;
      }
      if (iteration > 1) previous_increment = increment;
      if ((full || full_newton()) && iteration > 1) refactorise(stats);
      if (sparse && singular) {
        attempt.reason = "the Newton matrix is singular (sparse LU)";
        return attempt;
      }
      increment = sparse ? Eigen::VectorXd(-sparse_lu.solve(residual))
                         : Eigen::VectorXd(-lu.solve(residual));
      if (!increment.allFinite()) {  // keep the last finite iterate for the message
        attempt.reason = "the Newton increment is not finite (singular Newton matrix?)";
        return attempt;
      }
      unknowns += increment;
      ++stats.newton_iterations;
      attempt.iterations = iteration;
      attempt.increment = equations.increment_norm(unknowns, increment, options);
      if (!std::isfinite(attempt.increment)) {
        attempt.reason = "the Newton increment is not finite (singular Newton matrix?)";
        return attempt;
      }
      // Whether the iterate the increment started from (the residual's) was at the round-off
      // floor; asked only when the increments stop shrinking, the one case it decides.
      bool at_floor = false;
      if (convergence.floor_matters(attempt.increment)) {
        // The LU solve of the previous increment left rounding of about |J| |dz| in the rows.
        solve_rounding =
            sparse ? Eigen::VectorXd(sparse_jacobian.cwiseAbs() * previous_increment.cwiseAbs())
                   : Eigen::VectorXd(jacobian.cwiseAbs() * previous_increment.cwiseAbs());
        at_floor = equations.residual_at_floor(unknowns - increment, residual, solve_rounding);
      }
      const detail::NewtonVerdict verdict =
          convergence.observe(attempt.increment, attempt.residual, at_floor, fresh);
      if (verdict == detail::NewtonVerdict::ConvergedAtRoundOff) {
        // The last rate measured rounding, not the matrix: it keeps the one measured before.
        attempt.converged = true;
        return attempt;
      }
      last_contraction = convergence.contraction();
      if (verdict == detail::NewtonVerdict::Converged) {
        attempt.converged = true;
        return attempt;
      }
      if (verdict == detail::NewtonVerdict::Diverging) {
        attempt.reason = "the iteration diverges";
        attempt.advice = convergence.advice(options.max_iterations);
        return attempt;
      }
      // A reused matrix is replaced at the current iterate when it contracts slowly, or so slowly
      // that the remaining iterations cannot reach the tolerance (Hairer & Wanner, ODEs II,
      // §IV.8: the error after k more iterations is about theta^k / (1 - theta) |dx|).
      if (iteration > 1 && iteration < options.max_iterations && !fresh) {
        const int remaining = options.max_iterations - iteration;
        const bool slow =
            last_contraction > options.max_contraction || last_contraction >= 1.0 ||
            std::pow(last_contraction, remaining) / (1.0 - last_contraction) * attempt.increment >
                1.0;
        if (slow) {
          refactorise(stats);
          fresh = true;
        }
      }
    }
    equations.residual(unknowns, residual);
    attempt.residual = residual.lpNorm<Eigen::Infinity>();
    attempt.reason = convergence.failure_kind() == detail::NewtonFailureKind::StalledAtRoundOff
                         ? "the increments stalled at round-off above the tolerance"
                         : "no convergence within the iteration limit";
    attempt.advice = convergence.advice(options.max_iterations);
    return attempt;
  }

  // The element a failed attempt points at, for the message: the source of a non-finite value,
  // or else the equation with the largest residual (a stage's rows are n kinematic, n dynamic,
  // then m constraint rows).
  std::string culprit(const State& state, double h) const {
    const ConstrainedSystem& system = *current_system;
    const int n = system.coordinate_count();
    const int block = 2 * n + system.constraint_count();
    if (!residual.allFinite() || !increment.allFinite()) {
      for (int i = 0; i < equations.stages(); ++i) {
        const std::string source =
            system.non_finite_source(state.time + tableau.c(i) * h, equations.position(unknowns, i),
                                     equations.velocity(unknowns, i));
        if (!source.empty()) return "; not finite: " + source;
      }
      return "; every element is finite at the stage values (a singular Newton matrix: "
             "redundant constraints in this configuration?)";
    }
    if (residual.size() == 0 || block == 0) return {};
    Eigen::Index largest = 0;
    residual.cwiseAbs().maxCoeff(&largest);
    const int row = static_cast<int>(largest % block);
    if (row < n)
      return "; largest residual in the kinematics of " + system.coordinate_description(row);
    if (row < 2 * n) {
      return "; largest residual in the equation of motion of " +
             system.coordinate_description(row - n) +
             system.equation_of_motion_note(row - n, state.time, state.q, state.v);
    }
    return "; largest residual in " + system.constraint_description(row - 2 * n);
  }

  // --- accept or reject ---
  void accept_or_reject(const Attempt& attempt, const State& state, double h) {
    if (attempt.converged) return;
    factorised = false;
    char text[512];
    std::snprintf(text, sizeof text,
                  "Newton iterations of %s (%d stages) failed at t = %.9g s with step size "
                  "%.6g s: %s; after %d iterations the scaled increment is %.3g (converged: <= 1) "
                  "and the residual of the scaled stage equations |r|_inf = %.3g",
                  tableau.name.c_str(), equations.stages(), state.time, h, attempt.reason,
                  attempt.iterations, attempt.increment, attempt.residual);
    std::string advice =
        attempt.advice.empty()
            ? "reduce the step size; check that the constraints are consistent with each "
              "other and with the initial state, and that loads and force elements are "
              "finite; or raise the Newton iteration limit"
            : attempt.advice;
    // Lobatto IIIA 3 passes its multiplier error on undamped with index-3 constraints
    // (docs/theory.md, "Integrator orders on the index-3 system"): over a long run the
    // multipliers drift until Newton fails, and a smaller step fails sooner (a user's spin-up:
    // at 10.9, 12.1, 11.9 s for h = 0.005, 0.01, 0.02 s).
    if (tableau.name.rfind("Lobatto", 0) == 0 && equations.stages() == 3 &&
        constraint_form == ConstraintForm::Index3) {
      advice =
          "Lobatto IIIA with 3 stages and index-3 constraints does not damp the error of its "
          "multipliers, which can grow over a long run until Newton fails (a smaller step "
          "fails sooner): use constraint_form = \"index2\", or Radau IIA (docs/theory.md, "
          "\"Integrator orders on the index-3 system\"); else " +
          advice;
    }
    throw Error(text + culprit(state, h), "multibody integration", advice);
  }

  // The step's start and its stages, for the dense output (last_step_stages).
  void record_stages(const State& start, double h) {
    StepStages& r = last_stages;
    r.start_time = start.time;
    r.step_size = h;
    r.nodes.assign(1, 0.0);
    r.positions.assign(1, start.q);
    r.velocities.assign(1, start.v);
    for (int i = 0; i < equations.stages(); ++i) {
      const double c = tableau.c(i);
      if (c == 0.0) continue;  // Lobatto IIIA's first stage is the start
      r.nodes.push_back(c);
      r.positions.push_back(equations.position(unknowns, i));
      r.velocities.push_back(equations.velocity(unknowns, i));
    }
  }

  // The integrand's quadrature over the step: h sum_i b_i g(t0 + c_i h, Q_i, V_i, Lambda_i)
  // (Lobatto IIIA's first stage, c = 0, is the step's start).
  void integrate(const State& start, double h) {
    if (integrand.size == 0) return;
    State stage;
    for (int i = 0; i < equations.stages(); ++i) {
      const double c = tableau.c(i);
      if (c == 0.0) {
        stage = start;
      } else {
        stage.time = start.time + c * h;
        stage.q = equations.position(unknowns, i);
        stage.v = equations.velocity(unknowns, i);
        stage.lambda = equations.multiplier(unknowns, i);
      }
      integrand.evaluate(stage, integrand_values);
      step_integral += (h * tableau.b(i)) * integrand_values;
    }
  }

  // --- finalise: the last stage is the solution (stiffly accurate) ---
  void finalise(State& state, double h, const StepStatistics& stats) {
    record_stages(state, h);
    integrate(state, h);
    const int last = equations.stages() - 1;
    state.q = equations.position(unknowns, last);
    state.v = equations.velocity(unknowns, last);
    state.lambda = equations.multiplier(unknowns, last);
    state.time += h;
    ++steps_with_factorisation;
    if (full_newton() || steps_with_factorisation >= options.max_modified_newton_steps ||
        last_contraction > options.max_contraction) {
      factorised = false;
    }
    statistics.add(stats);
  }
};

RadauIIA::RadauIIA(const RadauOptions& options) {
  validate(options);
  work_ = std::make_unique<Workspace>(options);
}

RadauIIA::RadauIIA(int stages, const NewtonOptions& newton)
    : RadauIIA(RadauOptions{stages, newton}) {}

RadauIIA::~RadauIIA() = default;
RadauIIA::RadauIIA(RadauIIA&&) noexcept = default;
RadauIIA& RadauIIA::operator=(RadauIIA&&) noexcept = default;

StepStatistics RadauIIA::step(const ConstrainedSystem& system, State& state, double step_size) {
  // A release inside the step ends a part of it there: the stages of one part then see one set
  // of rows, and the released row's multiplier drops to zero exactly at its release time (the
  // point loads stay those of the whole step, thesis Fig. 4.10). The parts land on the caller's
  // end time exactly.
  work_->step_integral.setZero(work_->integrand.size);
  const double end = state.time + step_size;
  std::optional<double> release = system.release_within(state.time, end);
  // Without a release the step is taken as given: the same h keeps the Newton matrix.
  if (!release) return step_without_release(system, state, step_size);
  StepStatistics total;
  while (release) {
    const StepStatistics part = step_without_release(system, state, *release - state.time);
    state.time = *release;
    total.newton_iterations += part.newton_iterations;
    total.jacobian_evaluations += part.jacobian_evaluations;
    total.factorisations += part.factorisations;
    total.retries += part.retries;
    release = system.release_within(state.time, end);
  }
  const StepStatistics last = step_without_release(system, state, end - state.time);
  state.time = end;
  total.newton_iterations += last.newton_iterations;
  total.jacobian_evaluations += last.jacobian_evaluations;
  total.factorisations += last.factorisations;
  total.retries += last.retries;
  return total;
}

StepStatistics RadauIIA::step_without_release(const ConstrainedSystem& system, State& state,
                                              double step_size) {
  Workspace& w = *work_;
  StepStatistics stats;
  w.initialise(system, state, step_size);
  // A kept factorisation is tried first; if that attempt fails, the step restarts from the
  // prediction with a fresh matrix, and then in full Newton (a fresh matrix in every iteration)
  // before giving up: a flexible body turning by a large angle in one step (a spinning beam
  // stiff in tension) outruns any matrix held through the step, and its steps were split into
  // substeps that cost more than full Newton (a user's spin-up at h = 0.1 s: 275 of 300 steps
  // substepped, 19.2 s; in full Newton none, 3.8 s). After such a rescue the next steps start
  // in full Newton (kFullNewtonSteps of them), then try the cheaper iteration again.
  if (w.full_newton_steps_left > 0) {
    --w.full_newton_steps_left;
    w.predict();
    Attempt attempt = w.iterate(true, stats, true);
    w.accept_or_reject(attempt, state, step_size);
    w.finalise(state, step_size, stats);
    return stats;
  }
  const bool reuse = w.factorised;
  w.predict();
  Attempt attempt = w.iterate(!reuse, stats);
  if (!attempt.converged && reuse) {
    ++stats.retries;
    w.predict();
    attempt = w.iterate(true, stats);
  }
  if (!attempt.converged && !w.full_newton()) {
    ++stats.retries;
    w.predict();
    attempt = w.iterate(true, stats, true);
    if (attempt.converged) w.full_newton_steps_left = Workspace::kFullNewtonSteps;
  }
  w.accept_or_reject(attempt, state, step_size);
  w.finalise(state, step_size, stats);
  return stats;
}

void RadauIIA::reset() {
  work_->factorised = false;
  work_->full_newton_steps_left = 0;
}

void RadauIIA::set_statistics(const IntegratorStatistics& statistics) {
  work_->statistics = statistics;
}

void RadauIIA::set_integrand(Integrand integrand) {
  detail::check_integrand(integrand, "Radau IIA integrand");
  work_->integrand = std::move(integrand);
  work_->integrand_values.setZero(work_->integrand.size);
  work_->step_integral.setZero(work_->integrand.size);
}

const Eigen::VectorXd& RadauIIA::last_step_integral() const {
  return work_->step_integral;
}

const StepStages& RadauIIA::last_step_stages() const {
  return work_->last_stages;
}
const ButcherTableau& RadauIIA::tableau() const {
  return work_->tableau;
}
const NewtonOptions& RadauIIA::options() const {
  return work_->options;
}
const IntegratorStatistics& RadauIIA::statistics() const {
  return work_->statistics;
}

}  // namespace fsi::mbd
