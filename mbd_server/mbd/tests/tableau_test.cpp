#include <gtest/gtest.h>

#include <cmath>

#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"

namespace fsi::mbd {
namespace {

TEST(RadauTableau, SatisfiesSimplifyingAssumptions) {
  for (int s = 1; s <= 3; ++s) {
    const ButcherTableau t = radau_iia(s);
    EXPECT_EQ(t.order, 2 * s - 1);
    EXPECT_DOUBLE_EQ(t.c(s - 1), 1.0);
    for (int j = 0; j < s; ++j)
      EXPECT_DOUBLE_EQ(t.a(s - 1, j), t.b(j));
    // B(2s-1): sum_i b_i c_i^(k-1) = 1/k.
    for (int k = 1; k <= 2 * s - 1; ++k) {
      double sum = 0.0;
      for (int i = 0; i < s; ++i)
        sum += t.b(i) * std::pow(t.c(i), k - 1);
      EXPECT_NEAR(sum, 1.0 / k, 1e-15) << "s = " << s << ", B(" << k << ")";
    }
    // The order is not higher: B(2s) fails.
    double sum = 0.0;
    for (int i = 0; i < s; ++i)
      sum += t.b(i) * std::pow(t.c(i), 2 * s - 1);
    EXPECT_GT(std::abs(sum - 1.0 / (2 * s)), 1e-6);
    // C(s): sum_j a_ij c_j^(k-1) = c_i^k / k.
    for (int i = 0; i < s; ++i) {
      for (int k = 1; k <= s; ++k) {
        double row = 0.0;
        for (int j = 0; j < s; ++j)
          row += t.a(i, j) * std::pow(t.c(j), k - 1);
        EXPECT_NEAR(row, std::pow(t.c(i), k) / k, 1e-15) << "s = " << s << ", C(" << k << ")";
      }
    }
  }
}

TEST(RadauTableau, UnavailableStageCountIsAUserError) {
  EXPECT_THROW(radau_iia(4), fsi::Error);
  EXPECT_THROW(radau_iia(0), fsi::Error);
}

}  // namespace
}  // namespace fsi::mbd
