// Error-controlled adaptive Radau IIA (step doubling) on the car axis problem: the requested
// tolerance is met at t = 3, and a fixed step doing the same number of Radau steps is less
// accurate (so a fixed step of equal accuracy needs more steps). Numbers in docs/validation.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "error_message.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/adaptive_radau.hpp"
#include "reference_problems.hpp"

namespace fsi::mbd {
namespace {

namespace car = reference::car_axis;

// Largest relative error of the positions and velocities (components 1-8) at t = 3.
double state_error(const car::Problem& problem, const State& state) {
  const auto computed = car::test_set_vector(problem, state);
  double worst = 0.0;
  for (int k = 0; k < 8; ++k) {
    worst =
        std::max(worst, std::abs(computed[k] - car::kReference[k]) / std::abs(car::kReference[k]));
  }
  return worst;
}

const RadauOptions kRadau{.stages = 3,
                          .newton = {.relative_tolerance = 1e-12, .max_iterations = 20}};

TEST(MbdAdaptiveRadau, CarAxisMeetsTheToleranceWithFewerStepsThanAFixedStep) {
  const car::Problem problem = car::make();
  const double tolerance = 1e-6;
  AdaptiveRadau adaptive(kRadau, {.relative_tolerance = tolerance,
                                  .absolute_tolerance = 1e-2 * tolerance,
                                  .initial_step = 1e-3});
  State state = problem.model.initial_state();
  adaptive.advance(problem.model, state, car::kEndTime);
  ASSERT_EQ(state.time, car::kEndTime);
  const AdaptiveStatistics& stats = adaptive.statistics();
  const double adaptive_error = state_error(problem, state);

  // The same number of Radau IIA steps (whole and halves, accepted and rejected) at a fixed step.
  const auto steps = static_cast<int>(stats.radau_steps);
  RadauIIA fixed(kRadau);
  State fixed_state = problem.model.initial_state();
  for (int i = 0; i < steps; ++i)
    fixed.step(problem.model, fixed_state, car::kEndTime / steps);
  const double fixed_error = state_error(problem, fixed_state);

  std::printf(
      "car axis, adaptive Radau IIA 3, rtol %g: relative error of q, v at t = 3: %.2e; "
      "%llu accepted, %llu rejected, %d Radau steps in all, %llu Newton iterations; "
      "fixed step 3/%d: %.2e\n",
      tolerance, adaptive_error, static_cast<unsigned long long>(stats.accepted),
      static_cast<unsigned long long>(stats.rejected), steps,
      static_cast<unsigned long long>(stats.newton_iterations), steps, fixed_error);
  EXPECT_LT(adaptive_error, tolerance);
  EXPECT_GT(fixed_error, adaptive_error);
}

TEST(MbdAdaptiveRadau, TighterToleranceGivesSmallerErrorAndMoreSteps) {
  const car::Problem problem = car::make();
  double previous_error = 1.0;
  std::uint64_t previous_steps = 0;
  for (double tolerance : {1e-3, 1e-5, 1e-7}) {
    AdaptiveRadau adaptive(
        kRadau, {.relative_tolerance = tolerance, .absolute_tolerance = 1e-2 * tolerance});
    State state = problem.model.initial_state();
    adaptive.advance(problem.model, state, car::kEndTime);
    const double error = state_error(problem, state);
    std::printf("rtol %g: error %.2e, %llu accepted steps\n", tolerance, error,
                static_cast<unsigned long long>(adaptive.statistics().accepted));
    EXPECT_LT(error, previous_error);
    EXPECT_GT(adaptive.statistics().accepted, previous_steps);
    previous_error = error;
    previous_steps = adaptive.statistics().accepted;
  }
}

TEST(MbdAdaptiveRadau, InvalidOptionsNameTheOption) {
  const std::string text = testing::error_message(
      [] { AdaptiveRadau adaptive(kRadau, {.relative_tolerance = -1.0, .initial_step = 0.0}); });
  EXPECT_NE(text.find("relative_tolerance"), std::string::npos) << text;
  EXPECT_NE(text.find("initial_step"), std::string::npos) << text;
}

}  // namespace
}  // namespace fsi::mbd
