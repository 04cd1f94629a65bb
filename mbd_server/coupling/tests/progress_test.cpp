#include "fsi/coupling/progress.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace fsi::coupling {
namespace {

ProgressSample third_of_the_tank() {
  ProgressSample sample;
  sample.time = 0.05;
  sample.end_time = 0.15;
  sample.step = 5000;
  sample.steps = 15000;
  sample.steps_per_second = 500.0;
  sample.closest_approach_over_r0 = 0.6125;
  sample.snapshot_time = 0.05;
  sample.density_deviation = 1.31e-3;
  sample.max_speed = 0.032;
  sample.speed_of_sound = 20.0;
  return sample;
}

TEST(CouplingProgress, LineHasTimePercentRateEtaAndHealth) {
  EXPECT_EQ(format_progress(third_of_the_tank()),
            "t = 0.0500/0.1500 s (33.3 %), 500 steps/s, ETA 0:00:20 | closest wall 0.61 r0 | "
            "snapshot t = 0.0500 s: max |rho/rho0-1| 1.31e-03, max speed 0.032 m/s = 0.0016 c");
}

TEST(CouplingProgress, TheSnapshotsParticlePairsFollowItsHealth) {
  ProgressSample sample = third_of_the_tank();
  sample.close_pairs = 0;
  EXPECT_TRUE(format_progress(sample).ends_with("= 0.0016 c, 0 pairs < d/2"))
      << format_progress(sample);
  sample.close_pairs = 2;
  sample.closest_pair_over_spacing = 0.1349;
  EXPECT_TRUE(format_progress(sample).ends_with("= 0.0016 c, 2 pairs < d/2 (closest 0.13 d)"))
      << format_progress(sample);
}

TEST(CouplingProgress, MissingNumbersAreSaidNotInvented) {
  ProgressSample sample = third_of_the_tank();
  sample.speed_of_sound.reset();
  const std::string without_c = format_progress(sample);
  EXPECT_TRUE(without_c.ends_with("max speed 0.032 m/s")) << without_c;
  sample.snapshot_time.reset();
  sample.closest_approach_over_r0 = std::numeric_limits<double>::infinity();
  sample.steps_per_second = 0.0;
  EXPECT_EQ(format_progress(sample),
            "t = 0.0500/0.1500 s (33.3 %), 0 steps/s, ETA --:--:-- | closest wall: no particle in "
            "range | no particle snapshot yet");
}

TEST(CouplingProgress, DurationsInHoursMinutesSeconds) {
  EXPECT_EQ(format_duration(3723.4), "1:02:03");
  EXPECT_EQ(format_duration(59.6), "0:01:00");
  EXPECT_EQ(format_duration(std::numeric_limits<double>::quiet_NaN()), "--:--:--");
  EXPECT_EQ(format_duration(-1.0), "--:--:--");
}

}  // namespace
}  // namespace fsi::coupling
