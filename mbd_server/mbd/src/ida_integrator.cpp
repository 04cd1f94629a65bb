// SUNDIALS IDA driver: builds the IDA memory, the serial vectors and the dense linear solver,
// passes the GGL residual and its analytic Jacobian (ggl_equations.hpp), and restarts whenever
// the caller's state is not the one IDA returned last.

#include "fsi/mbd/ida.hpp"

#include <idas/idas.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fsi/common/error.hpp"
#include "ggl_equations.hpp"
#include "integrand_check.hpp"

namespace fsi::mbd {
namespace {

void validate(const IdaOptions& o) {
  std::string problems;
  if (!(o.relative_tolerance > 0.0 && o.relative_tolerance < 1.0)) {
    problems += " relative_tolerance must be in (0, 1);";
  }
  if (!(o.absolute_tolerance > 0.0 && std::isfinite(o.absolute_tolerance))) {
    problems += " absolute_tolerance must be positive;";
  }
  if (o.max_order < 1 || o.max_order > 5) problems += " max_order must be 1 ... 5;";
  if (o.max_steps < 1) problems += " max_steps must be >= 1;";
  if (!(o.max_step >= 0.0 && std::isfinite(o.max_step))) problems += " max_step must be >= 0;";
  if (!(o.initial_step >= 0.0 && std::isfinite(o.initial_step))) {
    problems += " initial_step must be >= 0;";
  }
  if (!problems.empty()) {
    problems.pop_back();
    throw Error("invalid IDA options:" + problems, "IDA integrator options",
                "use e.g. relative_tolerance = 1e-8, absolute_tolerance = 1e-10, max_order = 5");
  }
}

Eigen::Map<Eigen::VectorXd> view(N_Vector x) {
  return {N_VGetArrayPointer(x), static_cast<Eigen::Index>(N_VGetLength(x))};
}

}  // namespace

struct IdaIntegrator::Impl {
  IdaOptions options;
  SUNContext context = nullptr;
  void* ida = nullptr;
  N_Vector y = nullptr, yp = nullptr, id = nullptr;
  N_Vector quad = nullptr;  // the integrand's integral since start() (IDAS' quadrature)
  SUNMatrix matrix = nullptr;
  SUNLinearSolver solver = nullptr;
  detail::GglEquations equations;
  IdaStatistics totals;
  // Counters of the current IDA memory, already added to totals.
  long counted_steps = 0, counted_newton = 0, counted_jacobians = 0, counted_residuals = 0,
       counted_error_fails = 0, counted_convergence_fails = 0;
  // What IDA's history belongs to.
  const ConstrainedSystem* system = nullptr;
  State last;
  std::vector<double> last_loads;
  bool running = false;
  double mass_scale = 1.0;  // largest diagonal entry of M
  double first_step = 0.0;  // the step IDA starts with (error_weights' h before it has one)
  std::string last_message;
  std::string bad_residual;  // set by residual() when it returns a failure
  Integrand integrand;
  Eigen::VectorXd quad_before;       // the quadrature at the end of the last advance
  Eigen::VectorXd advance_integral;  // the integral over the current / last advance()
  State quad_state_;
  Eigen::VectorXd quad_values_;
  // Scratch for the callbacks (the vectors are copied: N_Vector data is not an Eigen::VectorXd).
  Eigen::VectorXd y_, yp_, r_;

  explicit Impl(const IdaOptions& o) : options(o) {
    if (SUNContext_Create(nullptr, &context) != 0) {
      throw Error("cannot create a SUNDIALS context", "IDA integrator", "check the installation");
    }
  }
  ~Impl() {
    free_solver();
    SUNContext_Free(&context);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  void free_solver() {
    if (ida != nullptr) IDAFree(&ida);
    if (solver != nullptr) SUNLinSolFree(solver);
    if (matrix != nullptr) SUNMatDestroy(matrix);
    for (N_Vector* x : {&y, &yp, &id, &quad}) {
      if (*x != nullptr) N_VDestroy(*x);
      *x = nullptr;
    }
    solver = nullptr;
    matrix = nullptr;
    running = false;
  }

  static int residual(realtype t, N_Vector yy, N_Vector ypp, N_Vector rr, void* data) {
    auto& self = *static_cast<Impl*>(data);
    self.y_ = view(yy);
    self.yp_ = view(ypp);
    self.equations.residual(t, self.y_, self.yp_, self.r_);
    view(rr) = self.r_;
    if (self.r_.allFinite()) return 0;
    // Non-finite forces or constraints: unrecoverable (a recoverable failure lets IDA creep up to
    // the offending time with ever smaller steps until max_steps). The first such row is named.
    int row = 0;
    while (std::isfinite(self.r_(row)))
      ++row;
    char text[96];
    std::snprintf(text, sizeof text, "non-finite residual at t = %.9g s in the ", t);
    self.bad_residual = text + self.equations.describe_row(row);
    const std::string source = self.equations.non_finite_source(t, self.y_);
    if (!source.empty()) self.bad_residual += "; not finite: " + source;
    return -1;
  }

  // IDAS' quadrature right-hand side: the integrand at (t, q, v, lambda) of y.
  static int quadrature(realtype t, N_Vector yy, N_Vector, N_Vector rq, void* data) {
    auto& self = *static_cast<Impl*>(data);
    self.y_ = view(yy);
    self.equations.to_state(self.y_, t, self.quad_state_);
    self.integrand.evaluate(self.quad_state_, self.quad_values_);
    view(rq) = self.quad_values_;
    if (self.quad_values_.allFinite()) return 0;
    char text[96];
    std::snprintf(text, sizeof text, "a non-finite integrand (a work sensor's power) at t = %.9g s",
                  t);
    self.bad_residual = text;
    return -1;
  }

  static int jacobian(realtype t, realtype cj, N_Vector yy, N_Vector, N_Vector, SUNMatrix jac,
                      void* data, N_Vector, N_Vector, N_Vector) {
    auto& self = *static_cast<Impl*>(data);
    self.y_ = view(yy);
    const auto size = static_cast<Eigen::Index>(SUNDenseMatrix_Rows(jac));
    Eigen::Map<Eigen::MatrixXd> matrix(SUNDenseMatrix_Data(jac), size, size);
    self.equations.jacobian(t, cj, self.y_, matrix);
    return matrix.allFinite() ? 0 : 1;
  }

  // Error weights (1 / tolerance per component). q and v: relative_tolerance |y_i| +
  // absolute_tolerance. The algebraic lambda and mu are out of the error test, but Newton's
  // convergence test measures them too; there they are weighed by their effect on the differential
  // variables within one step h: a change d lambda moves v by h M^-1 G^T d lambda and a change
  // d mu moves q by h G_p^T d mu, so lambda gets (largest mass) x (velocity tolerance) / h and mu
  // (position tolerance) / h (the h-scaling of index-2 variables, Hairer & Wanner II, §VII.3).
  // With weights fixed in absolute terms, the rounding of lambda, ~eps M |v| / h, outgrows them
  // at small steps and Newton fails for ever smaller steps.
  static int error_weights(N_Vector yy, N_Vector weights, void* data) {
    auto& self = *static_cast<Impl*>(data);
    const auto y_ = view(yy);
    auto w = view(weights);
    const int n = self.equations.coordinates();
    const double rtol = self.options.relative_tolerance, atol = self.options.absolute_tolerance;
    for (int i = 0; i < 2 * n; ++i)
      w(i) = 1.0 / (rtol * std::abs(y_(i)) + atol);
    // Before its first step IDA has no current step, and the weights it takes then hold for
    // every try of that step: they are the first step's. (With h = 1 there, the rounding of the
    // constraint rows, carried into mu as ~ |g| / h, failed every try down to hmin: Andrews'
    // squeezer at the default tolerances.)
    realtype h = 0.0;
    IDAGetCurrentStep(self.ida, &h);
    if (!(h > 0.0)) h = self.first_step > 0.0 ? self.first_step : 1.0;
    const double position = rtol * y_.head(n).lpNorm<Eigen::Infinity>() + atol;
    const double velocity = rtol * y_.segment(n, n).lpNorm<Eigen::Infinity>() + atol;
    w.segment(self.equations.lambda_offset(), self.equations.constraints())
        .setConstant(h / (self.mass_scale * velocity));
    w.segment(self.equations.mu_offset(), self.equations.position_rows()).setConstant(h / position);
    return w.allFinite() ? 0 : -1;
  }

  static void error_handler(int, const char* module, const char* function, char* message,
                            void* data) {
    auto& self = *static_cast<Impl*>(data);
    self.last_message = std::string(module) + "/" + function + ": " + message;
  }

  // The variable that stopped IDA, for its failure message: the largest weighted component of the
  // last attempted step's correction (IDAGetEstLocalErrors: the corrector's change of the
  // predicted y, which the error test measures). A failed corrector (IDA_CONV_FAIL) is judged on
  // every variable, the error test and a step count run out (IDA_ERR_FAIL, IDA_TOO_MUCH_WORK) on
  // the differential ones it tests. A coordinate's variable also names the user's laws acting on
  // its equation of motion (ConstrainedSystem::equation_of_motion_note): a law that jumps, across
  // which IDA chatters with ever smaller steps, is the usual cause.
  struct Limiting {
    std::string text;       // "; the largest weighted local error is in the ..."
    bool user_law = false;  // the text names a user's law on that variable's equation
  };
  Limiting limiting_variable(int flag, double time) {
    if (ida == nullptr || system == nullptr) return {};
    N_Vector scratch = N_VClone(y);
    if (scratch == nullptr) return {};
    Eigen::VectorXd weighted;
    if (IDAGetEstLocalErrors(ida, scratch) == IDA_SUCCESS) {
      weighted = view(scratch);
      if (IDAGetErrWeights(ida, scratch) == IDA_SUCCESS)
        weighted.array() *= view(scratch).array();
      else
        weighted.resize(0);
    }
    N_VDestroy(scratch);
    const int n = equations.coordinates();
    const Eigen::Index tested =
        flag == IDA_CONV_FAIL ? weighted.size() : std::min<Eigen::Index>(2 * n, weighted.size());
    if (tested == 0 || !weighted.head(tested).allFinite()) return {};
    Eigen::Index largest = 0;
    if (!(weighted.head(tested).cwiseAbs().maxCoeff(&largest) > 0.0)) return {};
    const int index = static_cast<int>(largest);
    Limiting found;
    found.text = (flag == IDA_CONV_FAIL ? "; the largest weighted correction is in the "
                                        : "; the largest weighted local error is in the ") +
                 equations.describe_variable(index);
    if (index < 2 * n) {
      const Eigen::VectorXd at = view(y);
      const std::string note =
          system->equation_of_motion_note(index % n, time, at.head(n), at.segment(n, n));
      found.text += note;
      found.user_law = !note.empty();
    }
    return found;
  }

  void check(int flag, const char* call) {
    if (flag >= 0) return;
    throw Error(std::string("SUNDIALS call ") + call + " failed with flag " + std::to_string(flag) +
                    (last_message.empty() ? "" : " (" + last_message + ")"),
                "IDA integrator", "check the options and the model");
  }

  // Builds IDA from a consistent restart at `state`, with the rows released over the interval
  // to be integrated.
  // The step IDA starts with: the options' initial_step, or IDA's own rule (SUNDIALS' IDA guide,
  // "initial step size"): 0.001 of the interval, shortened so that it moves the differential
  // variables by at most half their tolerance's weight at their initial rates.
  double initial_step(const Eigen::VectorXd& y0, const Eigen::VectorXd& yp0,
                      double interval) const {
    if (options.initial_step > 0.0) return options.initial_step;
    const int differential = 2 * equations.coordinates();
    double sum = 0.0;
    for (int i = 0; i < differential; ++i) {
      const double weighted =
          yp0(i) / (options.relative_tolerance * std::abs(y0(i)) + options.absolute_tolerance);
      sum += weighted * weighted;
    }
    const double rate = differential > 0 ? std::sqrt(sum / differential) : 0.0;
    double h = 0.001 * interval;
    if (rate * h > 0.5) h = 0.5 / rate;
    return h;
  }

  void start(const ConstrainedSystem& candidate, const State& state, std::vector<bool> released,
             double end_time) {
    free_solver();
    equations.bind(candidate, std::move(released));
    const sunindextype size = equations.size();
    y = N_VNew_Serial(size, context);
    yp = N_VNew_Serial(size, context);
    id = N_VNew_Serial(size, context);
    if (y == nullptr || yp == nullptr || id == nullptr) {
      throw Error("cannot allocate SUNDIALS vectors", "IDA integrator", "free memory");
    }
    Eigen::VectorXd y0, yp0;
    if (!equations.consistent_vectors(state, y0, yp0)) {
      char text[160];
      std::snprintf(text, sizeof text,
                    "no consistent multipliers at t = %.9g s: the constraint rows are redundant "
                    "or contradictory, or a force is not finite",
                    state.time);
      throw Error(text, "IDA integrator",
                  "constrain each coordinate once; Model::check_consistency lists the rows");
    }
    view(y) = y0;
    mass_scale = equations.coordinates() > 0 ? candidate.mass_matrix().diagonal().maxCoeff() : 1.0;
    view(yp) = yp0;
    auto ids = view(id);
    ids.setZero();
    ids.head(2 * equations.coordinates()).setOnes();  // q, v differential; lambda, mu algebraic

    ida = IDACreate(context);
    if (ida == nullptr) throw Error("IDACreate failed", "IDA integrator", "free memory");
    check(IDASetErrHandlerFn(ida, &Impl::error_handler, this), "IDASetErrHandlerFn");
    check(IDAInit(ida, &Impl::residual, state.time, y, yp), "IDAInit");
    check(IDAWFtolerances(ida, &Impl::error_weights), "IDAWFtolerances");
    check(IDASetUserData(ida, this), "IDASetUserData");
    check(IDASetId(ida, id), "IDASetId");
    check(IDASetSuppressAlg(ida, SUNTRUE), "IDASetSuppressAlg");
    check(IDASetMaxOrd(ida, options.max_order), "IDASetMaxOrd");
    check(IDASetMaxNumSteps(ida, static_cast<long>(options.max_steps)), "IDASetMaxNumSteps");
    if (options.max_step > 0.0) check(IDASetMaxStep(ida, options.max_step), "IDASetMaxStep");
    first_step = initial_step(y0, yp0, end_time - state.time);
    if (options.max_step > 0.0) first_step = std::min(first_step, options.max_step);
    check(IDASetInitStep(ida, first_step), "IDASetInitStep");
    matrix = SUNDenseMatrix(size, size, context);
    solver = SUNLinSol_Dense(y, matrix, context);
    if (matrix == nullptr || solver == nullptr) {
      throw Error("cannot allocate the dense Newton matrix", "IDA integrator", "free memory");
    }
    check(IDASetLinearSolver(ida, solver, matrix), "IDASetLinearSolver");
    check(IDASetJacFn(ida, &Impl::jacobian), "IDASetJacFn");
    if (integrand.size > 0) {
      quad = N_VNew_Serial(integrand.size, context);
      if (quad == nullptr)
        throw Error("cannot allocate SUNDIALS vectors", "IDA integrator", "free memory");
      view(quad).setZero();
      quad_values_.setZero(integrand.size);
      // Not error-tested (IDASetQuadErrCon's default): the integrand does not change the steps.
      check(IDAQuadInit(ida, &Impl::quadrature, quad), "IDAQuadInit");
    }
    quad_before.setZero(integrand.size);
    counted_steps = counted_newton = counted_jacobians = counted_residuals = 0;
    counted_error_fails = counted_convergence_fails = 0;
    system = &candidate;
    running = true;
    ++totals.initialisations;
  }

  bool continues(const ConstrainedSystem& candidate, const State& state) const {
    if (!running || system != &candidate || state.time != last.time) return false;
    if (state.q.size() != last.q.size() || state.v.size() != last.v.size()) return false;
    if (state.q != last.q || state.v != last.v) return false;
    const auto loads = candidate.point_loads();
    return std::equal(loads.begin(), loads.end(), last_loads.begin(), last_loads.end());
  }

  void count() {
    long steps = 0, newton = 0, jacobians = 0, residuals = 0, error_fails = 0,
         convergence_fails = 0;
    IDAGetNumSteps(ida, &steps);
    IDAGetNumNonlinSolvIters(ida, &newton);
    IDAGetNumJacEvals(ida, &jacobians);
    IDAGetNumResEvals(ida, &residuals);
    IDAGetNumErrTestFails(ida, &error_fails);
    IDAGetNumNonlinSolvConvFails(ida, &convergence_fails);
    totals.steps += static_cast<std::uint64_t>(steps - counted_steps);
    totals.newton_iterations += static_cast<std::uint64_t>(newton - counted_newton);
    totals.jacobian_evaluations += static_cast<std::uint64_t>(jacobians - counted_jacobians);
    totals.residual_evaluations += static_cast<std::uint64_t>(residuals - counted_residuals);
    totals.error_test_failures += static_cast<std::uint64_t>(error_fails - counted_error_fails);
    totals.convergence_failures +=
        static_cast<std::uint64_t>(convergence_fails - counted_convergence_fails);
    counted_steps = steps;
    counted_newton = newton;
    counted_jacobians = jacobians;
    counted_residuals = residuals;
    counted_error_fails = error_fails;
    counted_convergence_fails = convergence_fails;
  }
};

IdaIntegrator::IdaIntegrator(const IdaOptions& options) {
  validate(options);
  impl_ = std::make_unique<Impl>(options);
}

IdaIntegrator::~IdaIntegrator() = default;
IdaIntegrator::IdaIntegrator(IdaIntegrator&&) noexcept = default;
IdaIntegrator& IdaIntegrator::operator=(IdaIntegrator&&) noexcept = default;

void IdaIntegrator::advance(const ConstrainedSystem& system, State& state, double end_time) {
  if (!(end_time > state.time) || !std::isfinite(end_time)) {
    char text[128];
    std::snprintf(text, sizeof text, "end time %.9g s is not after the state's time %.9g s",
                  end_time, state.time);
    throw Error(text, "IDA integrator", "advance to a later time");
  }
  if (state.q.size() != system.coordinate_count() || state.v.size() != system.coordinate_count() ||
      state.lambda.size() != system.constraint_count()) {
    throw Error("the state does not match the model", "IDA integrator",
                "start from Model::initial_state() of this model");
  }
  // BDF's history does not survive a multiplier that drops to zero: IDA stops at every release
  // and restarts there with the row's equation lambda = 0.
  const State before = state;
  impl_->advance_integral.setZero(impl_->integrand.size);
  try {
    while (const std::optional<double> release = system.release_within(state.time, end_time))
      advance_without_release(system, state, *release);
    advance_without_release(system, state, end_time);
  } catch (const Error&) {
    state = before;
    throw;
  }
}

void IdaIntegrator::advance_without_release(const ConstrainedSystem& system, State& state,
                                            double end_time) {
  Impl& w = *impl_;
  std::vector<bool> released = system.released_rows(state.time, end_time);
  if (!w.continues(system, state) || w.equations.released() != released)
    w.start(system, state, std::move(released), end_time);
  w.last_message.clear();
  w.bad_residual.clear();
  w.check(IDASetStopTime(w.ida, end_time), "IDASetStopTime");
  realtype reached = state.time;
  const int flag = IDASolve(w.ida, end_time, &reached, w.y, w.yp, IDA_NORMAL);
  w.count();
  if (flag < 0 || !view(w.y).allFinite()) {
    w.running = false;
    char* flag_name = IDAGetReturnFlagName(flag);  // allocated by SUNDIALS
    const std::string reason = flag_name != nullptr ? flag_name : "unknown";
    std::free(flag_name);
    char text[256];
    std::snprintf(text, sizeof text,
                  "IDA failed between t = %.9g s and %.9g s, at t = %.9g s: %s (flag %d)",
                  state.time, end_time, reached, reason.c_str(), flag);
    std::string detail = w.bad_residual.empty() ? w.last_message : w.bad_residual;
    while (!detail.empty() && (detail.back() == '.' || detail.back() == ' '))
      detail.pop_back();
    std::string message = text + (detail.empty() ? "" : ": " + detail);
    Impl::Limiting limiting;
    if (w.bad_residual.empty()) {
      realtype last_step = 0.0;
      if (IDAGetLastStep(w.ida, &last_step) == IDA_SUCCESS && last_step > 0.0) {
        std::snprintf(text, sizeof text, "; its last step was %.3g s", last_step);
        message += text;
      }
      limiting = w.limiting_variable(flag, reached);
      message += limiting.text;
    }
    // The scene's names (SolverOptions): IDA's options have no other way to the user.
    const std::string tolerances =
        "loosen SolverOptions.ErrorControl.absolute_tolerance (a corrector that fails at ever "
        "smaller steps, at the start in particular, is held by it) and relative_tolerance, or "
        "integrate with Radau IIA (Timeint.method = \"fixed\" or \"adaptive\")";
    throw Error(message, "multibody integration (IDA)",
                !w.bad_residual.empty()
                    ? "find why that row is not finite at that time (a force or constraint "
                      "expression, a body that left its range)"
                : limiting.user_law
                    ? "look first at the user's law named above: a jump in it stops every "
                      "integrator, no tolerance helps; if it is continuous, " +
                          tolerances
                    : tolerances);
  }
  w.equations.to_state(view(w.y), end_time, state);
  if (w.integrand.size > 0) {
    w.check(IDAGetQuad(w.ida, &reached, w.quad), "IDAGetQuad");
    const auto now = view(w.quad);
    w.advance_integral += now - w.quad_before;
    w.quad_before = now;
  }
  w.last = state;
  const auto loads = system.point_loads();
  w.last_loads.assign(loads.begin(), loads.end());
}

void IdaIntegrator::set_integrand(Integrand integrand) {
  detail::check_integrand(integrand, "IDA integrand");
  impl_->integrand = std::move(integrand);
  impl_->advance_integral.setZero(impl_->integrand.size);
  impl_->running = false;  // the next advance() starts the quadrature with it
}

const Eigen::VectorXd& IdaIntegrator::last_advance_integral() const {
  return impl_->advance_integral;
}

void IdaIntegrator::reset() {
  impl_->running = false;
}

const IdaOptions& IdaIntegrator::options() const {
  return impl_->options;
}

IdaStatistics IdaIntegrator::statistics() const {
  return impl_->totals;
}

}  // namespace fsi::mbd
