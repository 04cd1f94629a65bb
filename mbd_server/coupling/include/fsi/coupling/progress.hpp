#pragma once
// The server's progress report while the coupled steps run: simulated time, percent done, steps per
// second, ETA, and the fluid's health (max |rho/rho0 - 1| and max particle speed against the speed
// of sound from the latest particle snapshot, the closest particle-wall approach over r0 since the
// previous report). format_progress is pure; the session decides when and where to show it (a
// live line on a terminal, periodic log lines otherwise).

#include <cstdint>
#include <optional>
#include <string>

namespace fsi::coupling {

struct ProgressSample {
  double time = 0.0;      // simulated time now [s]
  double end_time = 0.0;  // [s]
  std::uint64_t step = 0;
  std::uint64_t steps = 0;        // of the coupled phase
  double steps_per_second = 0.0;  // since the last log line (>= 1 s ago), else the phase's start
  std::optional<double> snapshot_time;              // of the latest particle snapshot [s]
  std::optional<double> density_deviation;          // max |rho/rho0 - 1| in that snapshot
  std::optional<double> max_speed;                  // max |v| in that snapshot [m/s]
  std::optional<std::uint64_t> close_pairs;         // particle pairs closer than d/2 in it
  std::optional<double> closest_pair_over_spacing;  // the closest of them / d
  std::optional<double> speed_of_sound;             // c [m/s] of the scene, if it declares one
  std::optional<double> closest_approach_over_r0;   // min since the previous report
};

// One line, e.g. "t = 0.0500/0.1500 s (33.3 %), 512 steps/s, ETA 0:00:19 | closest wall 0.61 r0 |
// snapshot t = 0.0500 s: max |rho/rho0-1| 1.31e-03, max speed 0.032 m/s = 0.0016 c, 2 pairs
// < d/2 (closest 0.13 d)".
std::string format_progress(const ProgressSample& sample);

// "1:02:03" for 3723 s; "--:--:--" when unknown (no rate yet, not finite).
std::string format_duration(double seconds);

}  // namespace fsi::coupling
