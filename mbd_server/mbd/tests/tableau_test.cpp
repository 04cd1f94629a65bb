#include <gtest/gtest.h>

#include <cmath>

#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"

namespace fsi::mbd {
namespace {

double sum_b_c_power(const ButcherTableau& t, int power) {
  double sum = 0.0;
  for (int i = 0; i < t.c.size(); ++i)
    sum += t.b(i) * std::pow(t.c(i), power);
  return sum;
}

// C(s): sum_j a_ij c_j^(k-1) = c_i^k / k, k = 1..s.
void expect_stage_order(const ButcherTableau& t) {
  const auto s = static_cast<int>(t.c.size());
  for (int i = 0; i < s; ++i) {
    for (int k = 1; k <= s; ++k) {
      double row = 0.0;
      for (int j = 0; j < s; ++j)
        row += t.a(i, j) * std::pow(t.c(j), k - 1);
      EXPECT_NEAR(row, std::pow(t.c(i), k) / k, 2e-16) << "s = " << s << ", C(" << k << ")";
    }
  }
}

TEST(MbdRadauTableau, SatisfiesTheSimplifyingAssumptionsOfOrder2sMinus1) {
  for (int s = 1; s <= 3; ++s) {
    const ButcherTableau t = radau_iia(s);
    ASSERT_EQ(t.a.rows(), s);
    ASSERT_EQ(t.a.cols(), s);
    EXPECT_EQ(t.order, 2 * s - 1);
    EXPECT_EQ(t.c(s - 1), 1.0) << "c_s = 1";
    for (int j = 0; j < s; ++j)
      EXPECT_EQ(t.a(s - 1, j), t.b(j)) << "stiffly accurate: a_sj = b_j";
    // B(2s-1): sum_i b_i c_i^(k-1) = 1/k, k = 1..2s-1.
    for (int k = 1; k <= 2 * s - 1; ++k)
      EXPECT_NEAR(sum_b_c_power(t, k - 1), 1.0 / k, 2e-16) << "s = " << s << ", B(" << k << ")";
    // The quadrature is not better than that: B(2s) fails, so the order is exactly 2s-1.
    EXPECT_GT(std::abs(sum_b_c_power(t, 2 * s - 1) - 1.0 / (2 * s)), 1e-4);
    expect_stage_order(t);
    // Nodes distinct and inside (0, 1].
    for (int i = 0; i < s; ++i) {
      EXPECT_GT(t.c(i), 0.0);
      if (i > 0) {
        EXPECT_GT(t.c(i), t.c(i - 1));
      }
    }
  }
}

TEST(MbdLobattoTableau, SatisfiesTheSimplifyingAssumptionsOfOrder2sMinus2) {
  for (int s = 2; s <= 3; ++s) {
    const ButcherTableau t = lobatto_iiia(s);
    EXPECT_EQ(t.order, 2 * s - 2);
    EXPECT_EQ(t.name, "Lobatto IIIA");
    EXPECT_EQ(t.c(0), 0.0);
    EXPECT_EQ(t.c(s - 1), 1.0);
    EXPECT_TRUE(t.a.row(0).isZero(0.0)) << "the first stage is the step start";
    for (int j = 0; j < s; ++j)
      EXPECT_EQ(t.a(s - 1, j), t.b(j));
    for (int k = 1; k <= 2 * s - 2; ++k)
      EXPECT_NEAR(sum_b_c_power(t, k - 1), 1.0 / k, 2e-16) << "s = " << s << ", B(" << k << ")";
    EXPECT_GT(std::abs(sum_b_c_power(t, 2 * s - 2) - 1.0 / (2 * s - 1)), 1e-4);
    expect_stage_order(t);
  }
  EXPECT_THROW(lobatto_iiia(1), fsi::Error);
  EXPECT_THROW(lobatto_iiia(4), fsi::Error);
}

TEST(MbdRadauTableau, UnavailableStageCountIsAUserError) {
  for (int s : {0, 4, -1}) {
    try {
      radau_iia(s);
      FAIL() << s << " stages accepted";
    } catch (const fsi::Error& error) {
      EXPECT_NE(std::string(error.what()).find("choose 1, 2 or 3 stages"), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace fsi::mbd
