// The automatic settling drag (docs/theory.md, "Settling the fluid").
#include "settling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace fsi::client {
namespace {

TEST(SettlingDrag, CriticallyDampsTheColumnsGravityMode) {
  // A 13 cm water column: omega = pi sqrt(9.81 / 0.13) = 27.29 1/s, lambda = 2 omega.
  const SettlingDrag drag = automatic_settling_drag(0.13, 9.81, 2.5e-5);
  EXPECT_NEAR(drag.column_frequency, 27.2905, 1e-4);
  EXPECT_DOUBLE_EQ(drag.critical_rate, 2.0 * drag.column_frequency);
  EXPECT_DOUBLE_EQ(drag.rate, drag.critical_rate);
  EXPECT_DOUBLE_EQ(drag.stability_limit, 0.1 / 2.5e-5);
  EXPECT_FALSE(drag.limited_by_time_step);
  // lambda^2 H / g = 4 pi^2 whatever the column: the same damping ratio for every height.
  for (const double height : {0.001, 0.0308, 0.13, 2.0}) {
    const SettlingDrag any = automatic_settling_drag(height, 9.81, 1e-6);
    EXPECT_NEAR(any.rate * any.rate * height / 9.81, 4.0 * std::numbers::pi * std::numbers::pi,
                1e-9)
        << height;
  }
}

TEST(SettlingDrag, IsBoundedByTheTimeStep) {
  // A 1 mm film under 1000 g with dt = 1e-3 s: 2 pi sqrt(g/H) = 19 676 1/s would remove more than
  // the whole velocity in one step; the drag takes 10 % per step instead.
  const SettlingDrag drag = automatic_settling_drag(1e-3, 9810.0, 1e-3);
  EXPECT_TRUE(drag.limited_by_time_step);
  EXPECT_DOUBLE_EQ(drag.rate, 100.0);
  EXPECT_DOUBLE_EQ(drag.rate * 1e-3, kDragPerStepLimit);
  EXPECT_GT(drag.critical_rate, drag.rate);
}

TEST(SettlingDrag, NothingToSettleWithoutGravityOrHeight) {
  EXPECT_EQ(automatic_settling_drag(0.13, 0.0, 1e-5).rate, 0.0);
  EXPECT_EQ(automatic_settling_drag(0.0, 9.81, 1e-5).rate, 0.0);
  EXPECT_EQ(automatic_settling_drag(std::nan(""), 9.81, 1e-5).rate, 0.0);
}

TEST(EquilibrationChunk, AtMostAboutAHundredChunksOfAtLeastAThousandSteps) {
  EXPECT_EQ(equilibration_chunk(1), 1000u);       // one short run
  EXPECT_EQ(equilibration_chunk(7500), 1000u);    // 8 chunks
  EXPECT_EQ(equilibration_chunk(125000), 1250u);  // 100 chunks
  EXPECT_EQ(equilibration_chunk(125001), 1251u);  // 100 chunks, the last shorter
  EXPECT_EQ(equilibration_chunk(10000000), 100000u);
}

}  // namespace
}  // namespace fsi::client
