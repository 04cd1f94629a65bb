// The multi-rate force predictor: exact for forces linear in time, the identity for k = 1.
#include "fsi/coupling/force_predictor.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace fsi::coupling {
namespace {

// The average over fluid steps first+1 .. first+k of f(m) = a + b m (one value per step m).
double window_average(double a, double b, int first, int k) {
  double sum = 0.0;
  for (int m = first + 1; m <= first + k; ++m)
    sum += a + b * m;
  return sum / k;
}

TEST(ForcePredictor, ALinearForceIsPredictedAsTheSingleRateSchemeWouldApplyIt) {
  // Two components with different slopes. After the exchange at fluid step n the k = 1 scheme
  // would apply f(n), ..., f(n+k-1) over the next structure step: their average is the target.
  const double a0 = 3.0, b0 = 0.25, a1 = -1.0, b1 = -0.5;
  for (int k : {2, 5, 20}) {
    ForcePredictor predictor(k);
    for (int n = k; n <= 6 * k; n += k) {
      const std::vector<double> average{window_average(a0, b0, n - k, k),
                                        window_average(a1, b1, n - k, k)};
      const std::span<const double> applied = predictor.apply(average);
      const double target0 = window_average(a0, b0, n - 1, k);
      const double target1 = window_average(a1, b1, n - 1, k);
      if (n == k) {  // the first average: no slope yet
        EXPECT_EQ(applied[0], average[0]);
        continue;
      }
      EXPECT_NEAR(applied[0], target0, 1e-12) << "k = " << k << ", n = " << n;
      EXPECT_NEAR(applied[1], target1, 1e-12) << "k = " << k << ", n = " << n;
      // Without the predictor the held average misses by the lag of k - 1 steps.
      EXPECT_NEAR(target0 - average[0], b0 * (k - 1), 1e-12);
    }
  }
}

TEST(ForcePredictor, WithOneSubstepItIsTheIdentity) {
  ForcePredictor predictor(1);
  for (double f : {1.0, 4.0, -2.0}) {
    const std::vector<double> average{f, 2.0 * f};
    const std::span<const double> applied = predictor.apply(average);
    EXPECT_EQ(applied[0], f);
    EXPECT_EQ(applied[1], 2.0 * f);
  }
}

}  // namespace
}  // namespace fsi::coupling
