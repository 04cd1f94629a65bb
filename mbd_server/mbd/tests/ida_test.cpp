// SUNDIALS IDA on the GGL (stabilised index-2) form: its Jacobian against differences of the
// residual, consistent starts, and the acceptance problems of issue 4 (pendulum period, car axis
// at t = 3) reached at IDA's tolerances (numbers in docs/validation.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "element_checks.hpp"
#include "error_message.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/ida.hpp"
#include "fsi/mbd/readouts.hpp"
#include "ggl_equations.hpp"
#include "reference_problems.hpp"

namespace fsi::mbd {
namespace {

namespace car = reference::car_axis;

// A state off the solution (mu != 0, constraints violated) so that every term of the Jacobian
// counts.
void perturbed_vectors(detail::GglEquations& equations, const State& start, Eigen::VectorXd& y,
                       Eigen::VectorXd& yp) {
  ASSERT_TRUE(equations.consistent_vectors(start, y, yp));
  for (int i = 0; i < y.size(); ++i) {
    y(i) += 0.01 * std::sin(1.7 * i + 0.3);
    yp(i) += 0.02 * std::cos(0.9 * i + 0.1);
  }
}

TEST(MbdIda, GglJacobianMatchesDifferencesOfTheResidual) {
  car::Problem problem = car::make();
  State start = problem.model.initial_state();
  start.time = 0.37;  // the moving anchor makes C_t and dG/dt non-zero
  detail::GglEquations equations;
  equations.bind(problem.model);
  ASSERT_EQ(equations.size(), 2 * 6 + 2 + 2);
  Eigen::VectorXd y, yp;
  perturbed_vectors(equations, start, y, yp);
  const double cj = 3.7e2;
  Eigen::MatrixXd analytic(equations.size(), equations.size());
  equations.jacobian(start.time, cj, y, analytic);

  Eigen::MatrixXd differences(equations.size(), equations.size());
  Eigen::VectorXd plus, minus;
  const double step = 1e-6;
  for (int j = 0; j < y.size(); ++j) {
    Eigen::VectorXd y1 = y, y2 = y, yp1 = yp, yp2 = yp;
    y1(j) += step;
    y2(j) -= step;
    yp1(j) += cj * step;  // dr/dy + cj dr/dy' is the derivative along (e_j, cj e_j)
    yp2(j) -= cj * step;
    equations.residual(start.time, y1, yp1, plus);
    equations.residual(start.time, y2, yp2, minus);
    differences.col(j) = (plus - minus) / (2.0 * step);
  }
  const double error = (analytic - differences).lpNorm<Eigen::Infinity>();
  std::printf(
      "GGL Jacobian (car axis, 16 x 16, cj = %g): max |analytic - differences| = %.2e of "
      "max entry %.2e\n",
      cj, error, analytic.lpNorm<Eigen::Infinity>());
  EXPECT_LT(error, 1e-7 * analytic.lpNorm<Eigen::Infinity>());
}

TEST(MbdIda, ConsistentStartSatisfiesTheResidual) {
  car::Problem problem = car::make();
  const State start = problem.model.initial_state();
  detail::GglEquations equations;
  equations.bind(problem.model);
  Eigen::VectorXd y, yp, r;
  ASSERT_TRUE(equations.consistent_vectors(start, y, yp));
  equations.residual(start.time, y, yp, r);
  EXPECT_LT(r.lpNorm<Eigen::Infinity>(), 1e-13);
  // The same multipliers as the model's own consistent start.
  EXPECT_LT((y.segment(equations.lambda_offset(), 2) - start.lambda).lpNorm<Eigen::Infinity>(),
            1e-14);
}

TEST(MbdIdaAcceptance, PendulumPeriodAtTolerance1e10) {
  const Model model = reference::point_mass_pendulum();
  const IdaOptions options{.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12};
  IdaIntegrator ida(options);
  State state = model.initial_state();
  // Output every 1e-3 s; the crossings of x = 0 (T/4, 3T/4, 5T/4, 7T/4) by Hermite interpolation
  // between outputs, as for Radau IIA (pendulum_test.cpp).
  const double output = 1e-3;
  std::vector<double> crossings;
  double position_drift = 0.0, velocity_drift = 0.0, energy_drift = 0.0;
  const double energy0 = kinetic_energy(model, state) + potential_energy(model, state);
  const int outputs = static_cast<int>(std::ceil(2.0 * reference::kPendulumPeriod / output)) + 2;
  for (int i = 1; i <= outputs; ++i) {
    const State before = state;
    ida.advance(model, state, i * output);
    if ((before.q(0) > 0) != (state.q(0) > 0)) {
      crossings.push_back(reference::hermite_root(before.time, output, before.q(0), before.v(0),
                                                  state.q(0), state.v(0)));
    }
    position_drift = std::max(position_drift, position_constraint_drift(model, state));
    velocity_drift = std::max(velocity_drift, velocity_constraint_drift(model, state));
    energy_drift = std::max(energy_drift, std::abs(kinetic_energy(model, state) +
                                                   potential_energy(model, state) - energy0));
  }
  ASSERT_EQ(crossings.size(), 4u);
  const double period = (crossings[3] - crossings[0]) / 1.5;
  const double relative =
      std::abs(period - reference::kPendulumPeriod) / reference::kPendulumPeriod;
  const IdaStatistics stats = ida.statistics();
  std::printf(
      "pendulum, IDA rtol %g atol %g: period %.12f s (exact %.10f), relative error %.2e; "
      "energy drift %.2e J, |C| <= %.2e m, |G v| <= %.2e m/s; %llu steps, %llu Newton "
      "iterations, %llu Jacobians\n",
      options.relative_tolerance, options.absolute_tolerance, period, reference::kPendulumPeriod,
      relative, energy_drift, position_drift, velocity_drift,
      static_cast<unsigned long long>(stats.steps),
      static_cast<unsigned long long>(stats.newton_iterations),
      static_cast<unsigned long long>(stats.jacobian_evaluations));
  EXPECT_EQ(stats.initialisations, 1u);  // one history over all outputs
  EXPECT_LT(relative, 1e-8);
  // GGL holds both constraint levels at every step (to Newton's tolerance).
  EXPECT_LT(position_drift, 1e-9);
  EXPECT_LT(velocity_drift, 1e-8);
}

TEST(MbdIdaAcceptance, CarAxisMatchesTheReferenceToSixDigitsAtTolerance1e10) {
  const car::Problem problem = car::make();
  const IdaOptions options{.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12};
  IdaIntegrator ida(options);
  State state = problem.model.initial_state();
  ida.advance(problem.model, state, car::kEndTime);
  EXPECT_EQ(state.time, car::kEndTime);
  const auto digits = car::significant_digits(problem, state);
  const IdaStatistics stats = ida.statistics();
  std::printf("car axis, IDA rtol %g atol %g: significant digits", options.relative_tolerance,
              options.absolute_tolerance);
  for (double d : digits)
    std::printf(" %.1f", d);
  std::printf("; %llu steps, %llu Newton iterations, %llu Jacobians, %llu error-test failures\n",
              static_cast<unsigned long long>(stats.steps),
              static_cast<unsigned long long>(stats.newton_iterations),
              static_cast<unsigned long long>(stats.jacobian_evaluations),
              static_cast<unsigned long long>(stats.error_test_failures));
  for (int k = 0; k < 10; ++k)
    EXPECT_GE(digits[k], 6.0) << "component " << k + 1;
}

TEST(MbdIda, ChangedPointLoadsRestartFromAConsistentState) {
  Model model = reference::point_mass_pendulum();
  const int marker = model.add_marker(0, {0.0, 0.0});
  ASSERT_EQ(marker, 0);
  IdaIntegrator ida({.relative_tolerance = 1e-8, .absolute_tolerance = 1e-10});
  State state = model.initial_state();
  ida.advance(model, state, 0.1);
  ida.advance(model, state, 0.2);
  EXPECT_EQ(ida.statistics().initialisations, 1u);
  const double load[2] = {0.0, -5.0};
  model.set_point_loads(load);
  ida.advance(model, state, 0.3);
  EXPECT_EQ(ida.statistics().initialisations, 2u);
  ida.advance(model, state, 0.4);  // the state IDA returned: continues
  EXPECT_EQ(ida.statistics().initialisations, 2u);
  State changed = state;
  changed.v(2) += 1e-3;  // a state changed by the caller (the bob's free spin): restarts
  ida.advance(model, changed, 0.5);
  EXPECT_EQ(ida.statistics().initialisations, 3u);
  model.set_point_loads(std::vector<double>{0.0, 0.0});
  ida.advance(model, changed, 0.6);
  EXPECT_EQ(ida.statistics().initialisations, 4u);
}

// A force that turns non-finite after t = 0.05 s.
class BreaksAfter final : public ForceElement {
 public:
  void add_force(double time, const Eigen::VectorXd&, const Eigen::VectorXd&,
                 Eigen::VectorXd& force) const override {
    if (time > 0.05) force(0) += std::numeric_limits<double>::quiet_NaN();
  }
  bool add_jacobians(double, const Eigen::VectorXd&, const Eigen::VectorXd&, Eigen::MatrixXd&,
                     Eigen::MatrixXd&) const override {
    return true;
  }
};

TEST(MbdIda, NonFiniteForceIsReportedWithTheTimeAndLeavesTheStateUnchanged) {
  Model model = reference::point_mass_pendulum();
  model.add_force_element(std::make_unique<BreaksAfter>());
  IdaIntegrator ida;
  State state = model.initial_state();
  const State before = state;
  const std::string text = testing::error_message([&] { ida.advance(model, state, 0.1); });
  std::printf("IDA, a force that turns NaN: %s\n", text.c_str());
  EXPECT_NE(text.find("IDA failed between t = 0 s and 0.1 s"), std::string::npos) << text;
  EXPECT_NE(text.find("non-finite residual at t = 0.05"), std::string::npos) << text;
  EXPECT_NE(text.find("equation of motion of body 'bob' coordinate"), std::string::npos) << text;
  EXPECT_EQ(state.time, before.time);
  EXPECT_EQ(state.q, before.q);
  EXPECT_TRUE(state.q.allFinite() && state.v.allFinite() && state.lambda.allFinite());
}

// A law that jumps (a preload dropped inside a seat) stops IDA as it stops Radau IIA's Newton: the
// message names the variable whose correction IDA could not bring under its tolerance and the
// user's law on its equation, not the smooth law on another body.
TEST(MbdIda, ALawThatJumpsIsNamedWhereIdaFails) {
  Model model;
  testing::slider_on_a_jumping_seat(model);
  IdaIntegrator ida({.max_steps = 20000});
  State state = model.initial_state();
  const std::string text = testing::error_message([&] { ida.advance(model, state, 1.0); });
  std::printf("IDA, a law that jumps: %s\n", text.c_str());
  EXPECT_NE(text.find("body 'slider' coordinate x"), std::string::npos) << text;
  EXPECT_NE(text.find("a user's law acts on it (nonlinear spring-damper 'seat')"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("'smooth'"), std::string::npos) << text;
  EXPECT_NE(text.find("look first at the user's law named above"), std::string::npos) << text;
}

TEST(MbdIda, InvalidOptionsNameTheOption) {
  const std::string text = testing::error_message(
      [] { IdaIntegrator ida({.relative_tolerance = 0.0, .max_order = 7}); });
  EXPECT_NE(text.find("relative_tolerance"), std::string::npos) << text;
  EXPECT_NE(text.find("max_order"), std::string::npos) << text;
}

}  // namespace
}  // namespace fsi::mbd
