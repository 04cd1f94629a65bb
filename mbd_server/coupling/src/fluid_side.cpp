#include "fsi/coupling/fluid_side.hpp"

#include "fsi/common/error.hpp"

namespace fsi::coupling {

std::string FluidSide::checkpoint(std::uint64_t step) {
  throw Error("this fluid side keeps no checkpoints", "checkpoint of step " + std::to_string(step),
              "set Output.checkpoint_every_steps = 0 and checkpoint_every_seconds = 0");
}

FluidReady FluidSide::resume(const scene::Scene&, const std::vector<double>&,
                             const std::vector<double>&, std::uint64_t step, double,
                             std::string_view) {
  throw Error("this fluid side cannot resume from a checkpoint",
              "resume from step " + std::to_string(step), "start the run afresh (--overwrite)");
}

}  // namespace fsi::coupling
