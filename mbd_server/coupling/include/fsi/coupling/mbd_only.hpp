#pragma once
// `fsi-server --mbd-only SCENE`: the scene's multibody part alone, without a fluid client (the
// fluid forces are zero). Integrates with Radau IIA at the scene's fixed step, stages and Newton
// settings up to its end time and writes sensors.csv and run.json into the output folder like a
// coupled run (run.json's "mode" is "mbd-only").

#include <string>
#include <vector>

#include "fsi/scene/scene.hpp"

namespace fsi::coupling {

struct MbdOnlyOptions {
  std::string output_dir;
  std::string command_line;           // recorded in run.json
  std::vector<std::string> warnings;  // recorded in run.json
};

// Returns the process exit status (0 success, 1 failure). Never throws for faults of the run
// (Newton failure, non-finite state): they are logged with step and time and recorded in run.json
// with status "failed"; sensors.csv then ends at the last good step and holds no NaN.
int run_mbd_only(scene::Scene& scene, const MbdOnlyOptions& options);

}  // namespace fsi::coupling
