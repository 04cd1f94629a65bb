// Acceptance test of issue 4: the car axis problem of the IVP Test Set (Mazzia & Magherini),
// an index-3 DAE with 4 coordinates and 2 multipliers, against its reference y(3). The model and
// the reference values: reference_problems.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fsi/mbd/integrator.hpp"
#include "reference_problems.hpp"

namespace fsi::mbd {
namespace {

namespace car = reference::car_axis;

TEST(MbdCarAxisAcceptance, RadauIIA3MatchesTheReferenceAtTEquals3ToSixDigits) {
  const car::Problem problem = car::make();
  const double h = 1e-4;
  RadauIIA integrator(3, {.relative_tolerance = 1e-12, .max_iterations = 20});
  State state = problem.model.initial_state();
  for (int i = 0; i < 30000; ++i)
    integrator.step(problem.model, state, h);
  ASSERT_NEAR(state.time, car::kEndTime, 1e-10);  // 30000 additions of h

  const auto computed = car::test_set_vector(problem, state);
  const auto digits = car::significant_digits(problem, state);
  for (int k = 0; k < 10; ++k) {
    std::printf("car axis y%-2d = %+.12e  reference %+.12e  relative error %.1e\n", k + 1,
                computed[k], car::kReference[k], std::pow(10.0, -digits[k]));
    EXPECT_GE(digits[k], 6.0) << "component " << k + 1;
  }
  std::printf(
      "car axis, Radau IIA 3, h = %g: at least %.1f significant digits in every component\n", h,
      *std::min_element(digits.begin(), digits.end()));
}

}  // namespace
}  // namespace fsi::mbd
