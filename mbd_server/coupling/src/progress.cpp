#include "fsi/coupling/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace fsi::coupling {

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "--:--:--";
  const auto total = static_cast<long long>(std::llround(seconds));
  char text[40];
  std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", total / 3600, total / 60 % 60, total % 60);
  return text;
}

std::string format_progress(const ProgressSample& sample) {
  char text[512];
  const double percent = sample.steps > 0 ? 100.0 * static_cast<double>(sample.step) /
                                                static_cast<double>(sample.steps)
                                          : 100.0;
  const double remaining = static_cast<double>(sample.steps - std::min(sample.step, sample.steps));
  const double eta = sample.steps_per_second > 0.0 ? remaining / sample.steps_per_second
                                                   : std::numeric_limits<double>::quiet_NaN();
  std::snprintf(text, sizeof text, "t = %.4f/%.4f s (%.1f %%), %.0f steps/s, ETA %s", sample.time,
                sample.end_time, percent, sample.steps_per_second, format_duration(eta).c_str());
  std::string line = text;
  if (sample.closest_approach_over_r0 && std::isfinite(*sample.closest_approach_over_r0)) {
    std::snprintf(text, sizeof text, " | closest wall %.2f r0", *sample.closest_approach_over_r0);
    line += text;
  } else {
    line += " | closest wall: no particle in range";
  }
  if (sample.snapshot_time && sample.density_deviation && sample.max_speed) {
    std::snprintf(text, sizeof text,
                  " | snapshot t = %.4f s: max |rho/rho0-1| %.2e, max speed %.3g m/s",
                  *sample.snapshot_time, *sample.density_deviation, *sample.max_speed);
    line += text;
    if (sample.speed_of_sound && *sample.speed_of_sound > 0.0) {
      std::snprintf(text, sizeof text, " = %.3g c", *sample.max_speed / *sample.speed_of_sound);
      line += text;
    }
    if (sample.close_pairs) {
      std::snprintf(text, sizeof text, ", %llu pairs < d/2",
                    static_cast<unsigned long long>(*sample.close_pairs));
      line += text;
      if (sample.closest_pair_over_spacing) {
        std::snprintf(text, sizeof text, " (closest %.2f d)", *sample.closest_pair_over_spacing);
        line += text;
      }
    }
  } else {
    line += " | no particle snapshot yet";
  }
  return line;
}

}  // namespace fsi::coupling
