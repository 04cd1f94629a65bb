#pragma once
// `fsi-server --mbd-only SCENE`: the scene's multibody part alone, without a fluid client (the
// fluid forces are zero). Integrates up to its end time with SolverOptions.Timeint.method (the
// fixed-step tableau, adaptive Radau IIA or IDA, sensors every step_size) and writes sensors.csv
// (from t = 0) and run.json into the output folder like a coupled run ("mode": "mbd-only").

#include <string>
#include <vector>

#include "fsi/scene/scene.hpp"

namespace fsi::coupling {

struct MbdOnlyOptions {
  std::string output_dir;
  std::string command_line;            // recorded in run.json
  std::vector<std::string> warnings;   // recorded in run.json
  std::vector<std::string> overrides;  // --set KEY=EXPR, recorded in run.json (scene.overrides)
};

// Returns the process exit status (0 success, 1 failure). Never throws for faults of the run
// (Newton failure, non-finite state): they are logged with step and time and recorded in run.json
// with status "failed"; sensors.csv then ends at the last good step and holds no NaN.
int run_mbd_only(scene::Scene& scene, const MbdOnlyOptions& options);

}  // namespace fsi::coupling
