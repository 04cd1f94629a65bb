// Work against accuracy of the multibody integrators on the two reference problems
// (mbd_server/mbd/tests/reference_problems.hpp): Radau IIA 3 with a fixed step, Radau IIA 3 with
// the step-doubling adaptive step, and SUNDIALS IDA (BDF 1-5, GGL). For each setting: the error
// against the reference, wall time (best of 3), steps, Newton iterations, Jacobian evaluations.
// Prints markdown tables (docs/performance.md). Usage: bench_mbd_integrators
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>

#include "fsi/mbd/adaptive_radau.hpp"
#include "fsi/mbd/ida.hpp"
#include "fsi/mbd/integrator.hpp"
#include "reference_problems.hpp"

namespace {

using namespace fsi::mbd;
namespace car = reference::car_axis;

struct Work {
  double error = 0.0;
  double milliseconds = 0.0;
  std::uint64_t steps = 0, newton = 0, jacobians = 0;
};

// Runs `run` three times and keeps the fastest wall time (the counts are the same every time).
Work best_of_three(const std::function<Work()>& run) {
  Work best;
  best.milliseconds = 1e300;
  for (int k = 0; k < 3; ++k) {
    const auto start = std::chrono::steady_clock::now();
    Work w = run();
    w.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (w.milliseconds < best.milliseconds) best = w;
  }
  return best;
}

// Pendulum after one exact period: back at (L, 0) at rest; error = max |q - (L, 0)| / L.
double pendulum_error(const State& s) {
  return std::max(std::abs(s.q(0) - reference::kPendulumLength), std::abs(s.q(1))) /
         reference::kPendulumLength;
}

// Car axis: largest relative error of q and v (components 1-8) at t = 3.
double car_error(const car::Problem& p, const State& s) {
  const auto y = car::test_set_vector(p, s);
  double worst = 0.0;
  for (int k = 0; k < 8; ++k)
    worst = std::max(worst, std::abs(y[k] - car::kReference[k]) / std::abs(car::kReference[k]));
  return worst;
}

const RadauOptions kRadau{.stages = 3,
                          .newton = {.relative_tolerance = 1e-12, .max_iterations = 20}};

Work radau_fixed(const Model& model, double end, int steps,
                 const std::function<double(const State&)>& error) {
  RadauIIA radau(kRadau);
  State s = model.initial_state();
  for (int i = 0; i < steps; ++i)
    radau.step(model, s, end / steps);
  const auto& st = radau.statistics();
  return {error(s), 0.0, st.steps, st.newton_iterations, st.jacobian_evaluations};
}

Work radau_adaptive(const Model& model, double end, double tolerance,
                    const std::function<double(const State&)>& error) {
  AdaptiveRadau radau(kRadau,
                      {.relative_tolerance = tolerance, .absolute_tolerance = 1e-2 * tolerance});
  State s = model.initial_state();
  radau.advance(model, s, end);
  const auto& st = radau.statistics();
  return {error(s), 0.0, st.radau_steps, st.newton_iterations, st.jacobian_evaluations};
}

Work ida(const Model& model, double end, double tolerance,
         const std::function<double(const State&)>& error) {
  IdaIntegrator integrator(
      {.relative_tolerance = tolerance, .absolute_tolerance = 1e-2 * tolerance});
  State s = model.initial_state();
  integrator.advance(model, s, end);
  const auto st = integrator.statistics();
  return {error(s), 0.0, st.steps, st.newton_iterations, st.jacobian_evaluations};
}

void row(const char* method, const std::string& setting, const Work& w) {
  std::printf("| %s | %s | %.1e | %.1f | %llu | %llu | %llu |\n", method, setting.c_str(), w.error,
              w.milliseconds, static_cast<unsigned long long>(w.steps),
              static_cast<unsigned long long>(w.newton),
              static_cast<unsigned long long>(w.jacobians));
}

void problem(const char* title, const Model& model, double end,
             const std::function<double(const State&)>& error, std::initializer_list<int> fixed,
             std::initializer_list<double> tolerances) {
  std::printf(
      "\n%s\n\n| method | setting | error | wall ms | steps | Newton it. | Jacobians |\n"
      "|---|---|---|---|---|---|---|\n",
      title);
  char text[64];
  for (int n : fixed) {
    std::snprintf(text, sizeof text, "h = %.3g s", end / n);
    row("Radau IIA 3 fixed", text,
        best_of_three([&] { return radau_fixed(model, end, n, error); }));
  }
  for (double tol : tolerances) {
    std::snprintf(text, sizeof text, "rtol %g", tol);
    row("Radau IIA 3 adaptive", text,
        best_of_three([&] { return radau_adaptive(model, end, tol, error); }));
  }
  for (double tol : tolerances) {
    std::snprintf(text, sizeof text, "rtol %g", tol);
    row("IDA (BDF 1-5, GGL)", text, best_of_three([&] { return ida(model, end, tol, error); }));
  }
}

}  // namespace

int main() {
  const Model pendulum = reference::point_mass_pendulum();
  problem("Pendulum, one period (t = 2.3678419476 s), error max|q - q0| / L", pendulum,
          reference::kPendulumPeriod, pendulum_error, {100, 200, 400, 800, 1600},
          {1e-4, 1e-6, 1e-8, 1e-10});
  const car::Problem axis = car::make();
  problem("Car axis, t = 3, error max relative error of q and v", axis.model, car::kEndTime,
          [&](const State& s) { return car_error(axis, s); }, {1500, 3000, 6000, 12000, 24000},
          {1e-4, 1e-6, 1e-8, 1e-10});
  return 0;
}
