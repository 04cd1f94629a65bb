#include "settling.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fsi::client {

SettlingDrag automatic_settling_drag(double column_height, double gravity, double time_step) {
  SettlingDrag drag;
  drag.stability_limit = kDragPerStepLimit / time_step;
  if (!(column_height > 0.0) || !(gravity > 0.0)) return drag;
  drag.column_frequency = std::numbers::pi * std::sqrt(gravity / column_height);
  drag.critical_rate = 2.0 * drag.column_frequency;
  drag.rate = std::min(drag.critical_rate, drag.stability_limit);
  drag.limited_by_time_step = drag.critical_rate > drag.stability_limit;
  return drag;
}

std::uint64_t equilibration_chunk(std::uint64_t total_steps) {
  constexpr std::uint64_t kSmallest = 1000;
  constexpr std::uint64_t kMostChunks = 100;
  return std::max(kSmallest, (total_steps + kMostChunks - 1) / kMostChunks);
}

}  // namespace fsi::client
