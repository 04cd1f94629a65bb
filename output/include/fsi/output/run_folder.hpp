#pragma once
// The output folder of a run (--output DIR) and what an earlier run left in it. A run never
// replaces another run's results by accident: fsi-server and fsi-run look into the folder before
// they write anything and refuse, naming the earlier run, unless --overwrite is given
// (docs/user-guide.md, "Command line and logs").

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fsi::output {

// What an earlier run left in a folder, read from its run.json where there is one.
struct EarlierRun {
  // Our programs' files and folders found (run.json, sensors.csv, energy.csv, the logs,
  // snapshots/, vtk/, plots/), relative to the folder.
  std::vector<std::string> found;
  bool manifest = false;               // a run.json was found
  std::string manifest_problem;        // why run.json could not be read; empty when it could
  std::string scene;                   // the scene file of the run; empty when unknown
  std::string started;                 // "2026-12-02 11:40:12 UTC", or the file date of run.json
  std::string status;                  // "completed", "failed", "started" (never recorded an end)
  std::optional<std::uint64_t> steps;  // the steps it recorded
  std::uint64_t sensor_rows = 0;       // data rows of sensors.csv
  bool snapshots = false;              // particle snapshots or VTK series are present

  // Something a user may want to keep: every run that did a step or recorded no end, and the
  // sensors and snapshots of a run whose run.json is missing. Only the remains of a run that
  // failed before its first step (a scene mistake, a client that never came) are not results.
  bool has_results() const;
  // "scene S, started D, status X, N steps", as much as is known.
  std::string summary() const;
};

// Nothing of ours in `folder` (absent, empty, or only other files): nullopt.
std::optional<EarlierRun> inspect_run_folder(const std::filesystem::path& folder);

// Called before a run writes anything into `folder`. Throws fsi::Error naming the earlier run when
// the folder holds its results and `overwrite` is false; the folder is not touched then.
// Otherwise returns what is there (nullopt: nothing), which remove_earlier_run then clears.
std::optional<EarlierRun> claim_run_folder(const std::filesystem::path& folder, bool overwrite);

// Removes the files our programs write into a run folder (the names in run_folder.cpp) and the
// subfolders they leave empty; anything else in the folder stays. Returns what it removed.
std::vector<std::filesystem::path> remove_earlier_run(const std::filesystem::path& folder);

}  // namespace fsi::output
