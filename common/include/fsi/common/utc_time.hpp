#pragma once
// The wall-clock time in UTC as ISO 8601 ("2026-12-03T11:16:18Z"): when a run started, was
// resumed, or wrote a checkpoint. One place for run.json and the checkpoint manifests.

#include <ctime>
#include <string>

namespace fsi {

inline std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm parts{};
  gmtime_r(&now, &parts);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &parts);
  return text;
}

}  // namespace fsi
