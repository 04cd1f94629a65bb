// Checkpoints and resume of the session loop against the in-process fake fluid side (a fluid
// with a memory, so that its state matters): a run resumed from a checkpoint continues bit for
// bit like the run that never stopped, in sensors.csv, energy.csv and the VTK series; a damaged
// newest checkpoint is passed over; a resume without a checkpoint or with another step is
// refused and changes nothing; a fluid side that cannot write checkpoints is refused when steps
// ask for them. (The refusals' messages are checked by integration_checkpoints.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fake_fluid_side.hpp"
#include "fsi/coupling/session.hpp"
#include "fsi/scene/scene.hpp"
#include "fsi/test_support/folder_per_test.hpp"

namespace fsi::coupling {
namespace {

namespace fs = std::filesystem;
using test_support::file_text;
using testing::FakeFluidSide;

constexpr int kSteps = 200;
constexpr double kStep = 1.25e-4;  // the coarse elastic plate's

// The elastic plate (an ANCF beam clamped under a water column) for kSteps steps, a row every
// 8 steps, snapshots every 40, a checkpoint every 72 (not a multiple of the 20 steps the
// integrator keeps a Newton matrix: a kept matrix would show).
scene::Scene elastic_plate(std::map<std::string, std::string> extra = {}) {
  std::map<std::string, std::string> set{{"Resolution.end_time", std::to_string(kSteps * kStep)},
                                         {"Output.snapshot_every_steps", "40"},
                                         {"Output.checkpoint_every_steps", "72"}};
  for (auto& [key, value] : extra)
    set[key] = value;
  std::vector<scene::Override> overrides;
  for (auto& [key, value] : set)
    overrides.push_back({key, value});
  return scene::build_scene(FSI_EXAMPLES_DIR "/elastic_plate/elastic_plate_coarse.scene",
                            overrides);
}

// Pushes the plate sideways, more where it is displaced, plus the fluid's memory.
FakeFluidSide plate_fluid() {
  FakeFluidSide fluid(2, [](const BoundaryMotion& motion) {
    std::vector<double> forces(motion.positions.size(), 0.0);
    for (std::size_t i = 0; i < forces.size(); i += 2)
      forces[i] = 0.02 + 0.5 * motion.positions[i + 1] * motion.time;
    return forces;
  });
  fluid.memory_coupling = 1e-4;
  return fluid;
}

using SessionCheckpoints = test_support::FolderPerTest;

nlohmann::json manifest(const fs::path& folder) {
  std::ifstream in(folder / "run.json");
  return nlohmann::json::parse(in);
}

TEST_F(SessionCheckpoints, AResumedRunContinuesBitForBit) {
  // The run that never stops.
  ServerOptions whole;
  whole.output_dir = (folder_ / "whole").string();
  {
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    ASSERT_EQ(run_session(scene, whole, fluid), 0);
    EXPECT_EQ(fluid.checkpoint_steps, (std::vector<std::uint64_t>{72, 144}));
  }
  // The same run, killed by a fluid fault at step 130 (after the checkpoint of step 72), then
  // resumed by a fresh process with a fresh fluid.
  ServerOptions broken;
  broken.output_dir = (folder_ / "broken").string();
  {
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    fluid.fail_at_step = 130;
    ASSERT_EQ(run_session(scene, broken, fluid), 1);
  }
  EXPECT_NE(file_text(folder_ / "broken" / "sensors.csv"),
            file_text(folder_ / "whole" / "sensors.csv"));
  EXPECT_TRUE(fs::exists(folder_ / "broken" / "snapshots" / "particles_000000120.csv"));
  ServerOptions resumed = broken;
  resumed.resume = true;
  {
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    ASSERT_EQ(run_session(scene, resumed, fluid), 0);
    EXPECT_EQ(fluid.resume_calls, 1);
    EXPECT_EQ(fluid.set_up_calls, 0);
    EXPECT_EQ(fluid.equilibrate_calls, 0);
    EXPECT_EQ(fluid.resumed_at.first, 72u);
    EXPECT_EQ(fluid.resumed_at.second, 72 * kStep);
    ASSERT_FALSE(fluid.exchanges.empty());
    EXPECT_EQ(fluid.exchanges.front().step, 73u);
    EXPECT_EQ(fluid.checkpoint_steps, (std::vector<std::uint64_t>{144}));
  }
  for (const char* file : {"sensors.csv", "energy.csv", "vtk/fluid.pvd", "vtk/beams.pvd",
                           "vtk/beams_000000160.vtp", "vtk/boundary_000000200.vtu"}) {
    EXPECT_EQ(file_text(folder_ / "broken" / file), file_text(folder_ / "whole" / file)) << file;
  }
  const auto run = manifest(folder_ / "broken");
  EXPECT_EQ(run["status"], "completed");
  EXPECT_EQ(run["steps"], kSteps);
  EXPECT_EQ(run["snapshots"], manifest(folder_ / "whole")["snapshots"]);
  EXPECT_EQ(run["newton"]["steps"], kSteps);
  ASSERT_EQ(run["resumes"].size(), 1u);
  EXPECT_EQ(run["resumes"][0]["step"], 72);
  EXPECT_EQ(run["resumes"][0]["checkpoint"], "step-000000072");
  EXPECT_EQ(run["checkpoints"]["last_step"], 144);
  EXPECT_EQ(run["checkpoints"]["written"], 2);
  EXPECT_EQ(run["energy_audit"]["exchanges"],
            manifest(folder_ / "whole")["energy_audit"]["exchanges"]);
}

// --reconnect-timeout: the fluid lost at step 130 (after the checkpoint of step 72); the session
// goes back to that checkpoint, resumes the fluid side from it and ends like the whole run. Without
// the timeout the same loss ends the run.
TEST_F(SessionCheckpoints, ALostFluidSideIsResumedFromTheNewestCheckpoint) {
  ServerOptions whole;
  whole.output_dir = (folder_ / "whole").string();
  {
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    ASSERT_EQ(run_session(scene, whole, fluid), 0);
  }
  ServerOptions options;
  options.output_dir = (folder_ / "lost").string();
  {
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    fluid.lose_at_step = 130;
    EXPECT_EQ(run_session(scene, options, fluid), 1);
    EXPECT_EQ(fluid.resume_calls, 0);
  }
  fs::remove_all(folder_ / "lost");
  options.reconnect_timeout = std::chrono::seconds(5);
  scene::Scene scene = elastic_plate();
  FakeFluidSide fluid = plate_fluid();
  fluid.lose_at_step = 130;
  ASSERT_EQ(run_session(scene, options, fluid), 0);
  EXPECT_EQ(fluid.resume_calls, 1);
  EXPECT_EQ(fluid.resumed_at.first, 72u);
  for (const char* file : {"sensors.csv", "energy.csv", "vtk/beams.pvd"})
    EXPECT_EQ(file_text(folder_ / "lost" / file), file_text(folder_ / "whole" / file)) << file;
  const auto run = manifest(folder_ / "lost");
  ASSERT_EQ(run["resumes"].size(), 1u);
  EXPECT_EQ(run["resumes"][0]["step"], 72);
}

TEST_F(SessionCheckpoints, ADamagedNewestCheckpointIsPassedOver) {
  ServerOptions options;
  options.output_dir = (folder_ / "run").string();
  ServerOptions whole;
  whole.output_dir = (folder_ / "whole").string();
  {
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    ASSERT_EQ(run_session(scene, whole, fluid), 0);
  }
  {
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    fluid.fail_at_step = 190;
    ASSERT_EQ(run_session(scene, options, fluid), 1);
  }
  // The newest (step 144) loses bytes of its fluid state: the resume takes step 72's.
  fs::resize_file(folder_ / "run" / "checkpoints" / "step-000000144" / "fluid.state", 3);
  options.resume = true;
  scene::Scene scene = elastic_plate();
  FakeFluidSide fluid = plate_fluid();
  ASSERT_EQ(run_session(scene, options, fluid), 0);
  EXPECT_EQ(fluid.resumed_at.first, 72u);
  EXPECT_EQ(file_text(folder_ / "run" / "sensors.csv"),
            file_text(folder_ / "whole" / "sensors.csv"));
}

TEST_F(SessionCheckpoints, AResumeWithoutACheckpointOrWithAnotherStepIsRefused) {
  ServerOptions options;
  options.output_dir = (folder_ / "run").string();
  options.resume = true;
  {
    // No run folder at all.
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    ASSERT_EQ(run_session(scene, options, fluid), 1);
    EXPECT_FALSE(fs::exists(folder_ / "run"));
  }
  options.resume = false;
  {
    // A run that failed before its first checkpoint (step 72).
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    fluid.fail_at_step = 50;
    ASSERT_EQ(run_session(scene, options, fluid), 1);
  }
  options.resume = true;
  {
    // Refused; the earlier run's record stays as it was.
    const std::string record_before = file_text(folder_ / "run" / "run.json");
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    ASSERT_EQ(run_session(scene, options, fluid), 1);
    EXPECT_EQ(fluid.resume_calls, 0);
    EXPECT_EQ(file_text(folder_ / "run" / "run.json"), record_before);
  }
  options.resume = false;
  fs::remove_all(folder_ / "run");
  {
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    fluid.fail_at_step = 100;
    ASSERT_EQ(run_session(scene, options, fluid), 1);
  }
  const std::string sensors_before = file_text(folder_ / "run" / "sensors.csv");
  const std::string record_before = file_text(folder_ / "run" / "run.json");
  options.resume = true;
  scene::Scene scene =
      elastic_plate({{"SolverOptions.Timeint.step_size", "1e-4"}, {"Resolution.end_time", "0.02"}});
  FakeFluidSide fluid = plate_fluid();
  ASSERT_EQ(run_session(scene, options, fluid), 1);
  EXPECT_EQ(fluid.resume_calls, 0);
  EXPECT_EQ(file_text(folder_ / "run" / "sensors.csv"), sensors_before);
  EXPECT_EQ(file_text(folder_ / "run" / "run.json"), record_before);
}

TEST_F(SessionCheckpoints, AFluidSideWithoutCheckpointsIsRefusedWhenStepsAskForThem) {
  ServerOptions options;
  options.output_dir = (folder_ / "run").string();
  {
    scene::Scene scene = elastic_plate();
    FakeFluidSide fluid = plate_fluid();
    fluid.checkpoints_supported = false;
    ASSERT_EQ(run_session(scene, options, fluid), 1);
    EXPECT_TRUE(fluid.exchanges.empty());
    EXPECT_NE(manifest(folder_ / "run")["reason"].get<std::string>().find(
                  "the fluid side cannot write checkpoints"),
              std::string::npos);
  }
  // By time only (the default): the run goes on without them.
  scene::Scene scene = elastic_plate(
      {{"Output.checkpoint_every_steps", "0"}, {"Output.checkpoint_every_seconds", "1e-9"}});
  FakeFluidSide fluid = plate_fluid();
  fluid.checkpoints_supported = false;
  fs::remove_all(folder_ / "run");
  ASSERT_EQ(run_session(scene, options, fluid), 0);
  EXPECT_TRUE(fluid.checkpoint_steps.empty());
}

}  // namespace
}  // namespace fsi::coupling
