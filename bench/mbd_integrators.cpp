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
#include <utility>
#include <vector>

#include "fsi/mbd/adaptive_radau.hpp"
#include "fsi/mbd/ida.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/mbd/static_analysis.hpp"
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

// Why IDA takes tiny steps on a beam: a steel cantilever (8 elements) released from its static
// deflection under a 10 kN tip load excites its high bending modes (undamped, up to ~1e5 rad/s).
// IDA's error control resolves them; Radau IIA at a fixed step damps them (L-stable). Material
// damping of the bending rate removes them, and IDA's steps drop. Tip deflection after 5 ms.
void released_beam() {
  std::printf(
      "\nReleased steel cantilever (8 elements, 10 kN tip load removed at t = 0), t = 5 ms: IDA "
      "(rtol 1e-8, atol 1e-10) against bending damping; Radau IIA 3 at h = 5e-5 s for "
      "comparison\n\n| method | bending damping [N m^2 s] | tip y [m] | wall ms | steps | "
      "Newton it. | Jacobians |\n|---|---|---|---|---|---|---|\n");
  auto released = [](double damping) {
    Model model;
    AncfBeamSpec b;
    b.name = "beam";
    b.start = {0.0, 0.0};
    b.end = {2.0, 0.0};
    b.element_count = 8;
    b.axial_stiffness = 2.07e11 * 0.01;
    b.bending_stiffness = 2.07e11 * 1e-4 / 12.0;
    b.mass_per_length = 7800.0 * 0.01;
    b.bending_damping = damping;
    b.axial_damping = 600.0 * damping;  // the same relaxation time for the axial modes
    const BodyId beam = model.add_ancf_beam(b);
    model.add_beam_clamp(beam, 0);
    model.add_marker(beam, {2.0, 0.0});
    model.set_point_loads(std::vector<double>{0.0, -1e4});
    State start = solve_static(model, model.initial_state()).state;
    model.set_point_loads(std::vector<double>{0.0, 0.0});
    return std::pair{std::move(model), start};
  };
  for (double damping : {0.0, 1e2, 1e3}) {
    auto [model, start] = released(damping);
    double tip = 0.0;
    const Work w = best_of_three([&, &model = model, &start = start] {
      IdaIntegrator integrator({.relative_tolerance = 1e-8, .absolute_tolerance = 1e-10});
      State s = start;
      integrator.advance(model, s, 0.005);
      tip = marker_position(model, s, 0).y();
      const auto st = integrator.statistics();
      return Work{0.0, 0.0, st.steps, st.newton_iterations, st.jacobian_evaluations};
    });
    std::printf("| IDA (BDF 1-5, GGL) | %g | %.9f | %.1f | %llu | %llu | %llu |\n", damping, tip,
                w.milliseconds, static_cast<unsigned long long>(w.steps),
                static_cast<unsigned long long>(w.newton),
                static_cast<unsigned long long>(w.jacobians));
  }
  auto [model, start] = released(0.0);
  double tip = 0.0;
  const Work w = best_of_three([&, &model = model, &start = start] {
    RadauIIA radau(kRadau);
    State s = start;
    for (int i = 0; i < 100; ++i)
      radau.step(model, s, 5e-5);
    tip = marker_position(model, s, 0).y();
    const auto& st = radau.statistics();
    return Work{0.0, 0.0, st.steps, st.newton_iterations, st.jacobian_evaluations};
  });
  std::printf("| Radau IIA 3 fixed | 0 | %.9f | %.1f | %llu | %llu | %llu |\n", tip, w.milliseconds,
              static_cast<unsigned long long>(w.steps), static_cast<unsigned long long>(w.newton),
              static_cast<unsigned long long>(w.jacobians));
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
  released_beam();
  return 0;
}
