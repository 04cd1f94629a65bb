// The session loop against the in-process fake fluid side (no LIGGGHTS, no TCP): set-up,
// equilibration, the t = 0 row and snapshot, 100 coupled steps, snapshots, and a fault that ends
// the run failed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "fake_fluid_side.hpp"
#include "fsi/coupling/output.hpp"
#include "fsi/coupling/session.hpp"
#include "fsi/scene/scene.hpp"
#include "fsi/test_support/thrown.hpp"

namespace fsi::coupling {
namespace {

namespace fs = std::filesystem;
using testing::FakeFluidSide;

constexpr double kStep = 1e-5;  // the coarse static tank's
constexpr int kSteps = 100;
constexpr int kSnapshotEvery = 50;

scene::Scene static_tank() {
  return scene::build_scene(FSI_EXAMPLES_DIR "/static_tank/static_tank_coarse.scene",
                            {{"Resolution.end_time", std::to_string(kSteps * kStep)},
                             {"Resolution.snapshot_every_steps", std::to_string(kSnapshotEvery)}});
}

class SessionLoop : public ::testing::Test {
 protected:
  void SetUp() override {
    output_ = fs::temp_directory_path() /
              ("fsi_session_test_" +
               std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(output_);
    options_.output_dir = output_.string();
  }
  void TearDown() override { fs::remove_all(output_); }

  nlohmann::json manifest() const {
    std::ifstream in(output_ / "run.json");
    return nlohmann::json::parse(in);
  }

  // sensors.csv (or another of the run's CSV files) as columns by name.
  std::map<std::string, std::vector<double>> sensors(const char* file = "sensors.csv") const {
    std::ifstream in(output_ / file);
    std::string line;
    std::vector<std::string> header;
    std::map<std::string, std::vector<double>> columns;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::stringstream fields(line);
      std::string field;
      if (header.empty()) {
        while (std::getline(fields, field, ','))
          header.push_back(field);
        continue;
      }
      for (std::size_t i = 0; std::getline(fields, field, ','); ++i)
        columns[header.at(i)].push_back(std::stod(field));
    }
    return columns;
  }

  fs::path output_;
  ServerOptions options_;
};

TEST_F(SessionLoop, SetsUpEquilibratesAndCouplesOneHundredSteps) {
  scene::Scene scene = static_tank();
  // Every dynamic vertex feels a force that grows with the time of the boundary state it is
  // computed for, so that the rows show which exchange's forces acted in which step.
  auto per_vertex_y = [](double time) { return -0.25 * (1.0 + time / (kSteps * kStep)); };
  FakeFluidSide fluid(2, [&](const BoundaryMotion& motion) {
    std::vector<double> forces(motion.positions.size(), 0.0);
    for (std::size_t i = 1; i < forces.size(); i += 2)
      forces[i] = per_vertex_y(motion.time);
    return forces;
  });

  ASSERT_EQ(run_session(scene, options_, fluid), 0);

  EXPECT_EQ(fluid.set_up_calls, 1);
  EXPECT_EQ(fluid.set_up_vertex_values, 2 * scene.boundary.vertex_count);  // static ones too
  EXPECT_EQ(fluid.equilibrate_calls, 1);
  ASSERT_EQ(fluid.exchanges.size(), static_cast<std::size_t>(kSteps));
  for (std::size_t k = 0; k < fluid.exchanges.size(); ++k) {
    const BoundaryMotion& motion = fluid.exchanges[k];
    EXPECT_EQ(motion.step, k + 1);
    EXPECT_EQ(motion.time, static_cast<double>(k + 1) * kStep);
    EXPECT_EQ(motion.time_step, kStep);
    EXPECT_EQ(motion.positions.size(), 2 * scene.boundary.dynamic_vertex_count);
  }
  // The first snapshot is the fluid as equilibrated, before the first step.
  EXPECT_EQ(fluid.snapshot_steps, (std::vector<std::uint64_t>{0, 50, 100}));
  EXPECT_EQ(fluid.finish_calls, 1);
  EXPECT_TRUE(fluid.reported_faults.empty());

  // The piston moves down at its prescribed speed, and the boundary the fluid sees with it.
  double largest_descent = 0.0;
  for (std::size_t i = 1; i < fluid.exchanges.front().positions.size(); i += 2) {
    largest_descent = std::max(largest_descent, fluid.exchanges.front().positions[i] -
                                                    fluid.exchanges.back().positions[i]);
  }
  EXPECT_GT(largest_descent, 0.0);

  // Every dynamic vertex's fake force reaches the bodies' fluid-force sensors, and the fluid's
  // own total reaches total_fluid_force_y. The row of t(n) holds f(t(n-1)), the forces held over
  // step n (thesis Fig. 4.10); the row of t = 0 the forces on the initial configuration.
  const auto columns = sensors();
  const auto vertices = static_cast<double>(scene.boundary.dynamic_vertex_count);
  // A row at t = 0 (the forces on the initial configuration), then one per step.
  ASSERT_EQ(columns.at("time").size(), static_cast<std::size_t>(kSteps) + 1);
  EXPECT_EQ(columns.at("time").front(), 0.0);
  EXPECT_EQ(columns.at("time")[1], kStep);
  EXPECT_EQ(columns.at("time").back(), kSteps * kStep);
  for (std::size_t row = 0; row < columns.at("time").size(); ++row) {
    const double acting_since = row == 0 ? 0.0 : static_cast<double>(row - 1) * kStep;
    const double expected_total = per_vertex_y(acting_since) * vertices;
    EXPECT_NEAR(columns.at("bottom_fluid_force_y")[row] + columns.at("piston_fluid_force_y")[row],
                expected_total, 1e-12)
        << "row " << row;
    EXPECT_NEAR(columns.at("total_fluid_force_y")[row], expected_total, 1e-12) << "row " << row;
  }

  const auto run = manifest();
  EXPECT_EQ(run["mode"], "coupled");
  EXPECT_EQ(run["status"], "completed");
  EXPECT_EQ(run["steps"], kSteps);
  EXPECT_EQ(run["snapshots"], 3);
  EXPECT_EQ(run["newton"]["steps"], kSteps);
  EXPECT_EQ(run["fluid"]["particle_count"], fluid.particle_count);
  EXPECT_TRUE(run["client"].is_null());  // an in-process fluid has no client
  EXPECT_TRUE(fs::exists(output_ / "snapshots" / "particles_000000000.csv"));
  EXPECT_TRUE(fs::exists(output_ / "snapshots" / "particles_000000050.csv"));
  EXPECT_TRUE(fs::exists(output_ / "vtk" / "boundary.pvd"));
}

// energy.csv holds the whole's books and, with several bodies, each body's: the static tank's
// bottom and piston. The fake pushes every dynamic vertex down; the piston moves down under it
// (the fluid works on it), the bottom is held (no work), and the bodies' works add up to the
// whole's at every row.
TEST_F(SessionLoop, EnergyCsvKeepsEachBodysBooks) {
  scene::Scene scene = static_tank();
  FakeFluidSide fluid(2, [&](const BoundaryMotion& motion) {
    std::vector<double> forces(motion.positions.size(), 0.0);
    for (std::size_t i = 1; i < forces.size(); i += 2)
      forces[i] = -0.25;
    return forces;
  });
  ASSERT_EQ(run_session(scene, options_, fluid), 0);
  const auto columns = sensors("energy.csv");
  for (const char* name : {"work_fluid_on_structure", "work_structure_on_fluid", "coupling_energy",
                           "work_fluid_on_bottom", "coupling_energy_bottom", "work_fluid_on_piston",
                           "coupling_energy_piston"})
    ASSERT_TRUE(columns.contains(name)) << name;
  const auto rows = columns.at("time").size();
  ASSERT_EQ(rows, static_cast<std::size_t>(kSteps) + 1);
  for (std::size_t row = 0; row < rows; ++row) {
    const double whole = columns.at("work_fluid_on_structure")[row];
    EXPECT_NEAR(columns.at("work_fluid_on_bottom")[row] + columns.at("work_fluid_on_piston")[row],
                whole, 1e-12 * std::max(1.0, std::abs(whole)))
        << "row " << row;
    EXPECT_NEAR(
        columns.at("coupling_energy_bottom")[row] + columns.at("coupling_energy_piston")[row],
        columns.at("coupling_energy")[row], 1e-15)
        << "row " << row;
  }
  EXPECT_GT(columns.at("work_fluid_on_piston").back(), 0.0);
  EXPECT_EQ(columns.at("work_fluid_on_bottom").back(), 0.0);
}

// run.json follows a run at the progress log's pace, so that a script reading it mid-run finds
// the steps done and the time spent so far, not the zeros of its start.
TEST_F(SessionLoop, RunJsonFollowsTheRunAtTheProgressLogsPace) {
  scene::Scene scene = static_tank();
  options_.progress_interval = std::chrono::milliseconds(0);  // a log line at every step
  nlohmann::json mid_run;
  FakeFluidSide fluid(2, [&](const BoundaryMotion& motion) {
    if (motion.step == 51) mid_run = manifest();
    return std::vector<double>(motion.positions.size(), 0.0);
  });
  ASSERT_EQ(run_session(scene, options_, fluid), 0);
  ASSERT_TRUE(mid_run.is_object());
  EXPECT_EQ(mid_run["status"], "started");  // no end recorded yet
  EXPECT_EQ(mid_run["steps"], 50);
  EXPECT_GT(mid_run["timings_seconds"]["total"].get<double>(), 0.0);
  EXPECT_GT(mid_run["timings_seconds"]["coupled_phase"].get<double>(), 0.0);
  EXPECT_EQ(manifest()["steps"], kSteps);
}

// Multi-rate coupling: one structure step and one exchange per 4 fluid steps; each exchange
// carries the structure step's start and stages, whose last block is the end the fluid sees.
TEST_F(SessionLoop, MultiRateStepsTheStructureOncePerSubstepsAndSendsItsStages) {
  scene::Scene scene = static_tank();
  constexpr int k = 4;
  scene.solver.substeps = k;
  scene.output.sensor_every_steps = k;
  scene.output.snapshot_every_steps = 20;
  FakeFluidSide fluid(2, FakeFluidSide::constant({0.0, -0.25}));

  ASSERT_EQ(run_session(scene, options_, fluid), 0);

  ASSERT_EQ(fluid.exchanges.size(), static_cast<std::size_t>(kSteps / k));
  const std::vector<double> radau_nodes = {0.0, (4.0 - std::sqrt(6.0)) / 10.0,
                                           (4.0 + std::sqrt(6.0)) / 10.0, 1.0};
  std::vector<double> previous_end;
  for (std::size_t e = 0; e < fluid.exchanges.size(); ++e) {
    const BoundaryMotion& motion = fluid.exchanges[e];
    const std::size_t values = motion.positions.size();
    EXPECT_EQ(motion.step, k * (e + 1));
    EXPECT_EQ(motion.time_step, kStep);
    EXPECT_EQ(motion.substeps, static_cast<std::uint32_t>(k));
    ASSERT_EQ(motion.nodes.size(), radau_nodes.size());
    for (std::size_t i = 0; i < radau_nodes.size(); ++i)
      EXPECT_NEAR(motion.nodes[i], radau_nodes[i], 1e-15);
    ASSERT_EQ(motion.node_positions.size(), radau_nodes.size() * values);
    ASSERT_EQ(motion.node_velocities.size(), radau_nodes.size() * values);
    // The last node is the end of the step, the first the previous step's end, bit for bit.
    const std::vector<double> last(motion.node_positions.end() - static_cast<long>(values),
                                   motion.node_positions.end());
    EXPECT_EQ(last, motion.positions);
    if (!previous_end.empty()) {
      const std::vector<double> first(motion.node_positions.begin(),
                                      motion.node_positions.begin() + static_cast<long>(values));
      EXPECT_EQ(first, previous_end);
    }
    previous_end = motion.positions;
  }
  // The piston descends at its prescribed constant speed: its stages lie on that line.
  const BoundaryMotion& some = fluid.exchanges[10];
  const std::size_t values = some.positions.size();
  for (std::size_t v = 1; v < values; v += 2) {
    const double start = some.node_positions[v], end = some.positions[v];
    for (std::size_t i = 1; i + 1 < some.nodes.size(); ++i) {
      EXPECT_NEAR(some.node_positions[i * values + v], start + some.nodes[i] * (end - start), 1e-12)
          << "value " << v << ", node " << i;
    }
  }
  EXPECT_EQ(fluid.snapshot_steps, (std::vector<std::uint64_t>{0, 20, 40, 60, 80, 100}));
  const auto run = manifest();
  EXPECT_EQ(run["status"], "completed");
  EXPECT_EQ(run["steps"], kSteps);
  EXPECT_EQ(run["newton"]["steps"], kSteps / k);  // one structure step per k fluid steps
  EXPECT_EQ(run["energy_audit"]["exchanges"], kSteps / k);
  EXPECT_EQ(run["model"]["integrator"], "Radau IIA, 3 stages, 4 fluid steps per structure step");
  const auto columns = sensors();
  ASSERT_EQ(columns.at("time").size(), static_cast<std::size_t>(kSteps / k) + 1);
  EXPECT_NEAR(columns.at("time")[1], k * kStep, 1e-18);
}

TEST_F(SessionLoop, KeepsTheFixedCoupledStepWhateverMethodTheSceneChooses) {
  scene::Scene scene = static_tank();
  scene.solver.method = scene::IntegrationMethod::Ida;
  FakeFluidSide fluid(2, FakeFluidSide::constant({0.0, 0.0}));

  ASSERT_EQ(run_session(scene, options_, fluid), 0);

  const auto run = manifest();
  EXPECT_EQ(run["model"]["integrator"], "Radau IIA, 3 stages");
  EXPECT_EQ(run["newton"]["steps"], kSteps);  // one Radau IIA step per coupled step
}

TEST_F(SessionLoop, AFluidFaultEndsTheRunFailedWithTheFaultRecorded) {
  scene::Scene scene = static_tank();
  FakeFluidSide fluid(2, FakeFluidSide::constant({0.0, -0.25}));
  fluid.fail_at_step = 37;

  EXPECT_EQ(run_session(scene, options_, fluid), 1);

  EXPECT_EQ(fluid.exchanges.size(), 37u);
  EXPECT_EQ(fluid.finish_calls, 0);
  ASSERT_EQ(fluid.reported_faults.size(), 1u);
  EXPECT_NE(fluid.reported_faults[0].find("fails at step 37"), std::string::npos);
  EXPECT_TRUE(fluid.faults_during_coupled_steps[0]);
  const auto run = manifest();
  EXPECT_EQ(run["status"], "failed");
  EXPECT_NE(run["reason"].get<std::string>().find("fails at step 37"), std::string::npos);
  EXPECT_EQ(run["steps"], 36);
  // The structure had done step 37 when the fluid failed: its Newton work is recorded.
  EXPECT_EQ(run["newton"]["steps"], 37);
  EXPECT_GE(run["newton"]["iterations"].get<int>(), 37);
  EXPECT_EQ(sensors().at("time").back(), 37 * kStep);
}

TEST_F(SessionLoop, AFaultBeforeTheCoupledStepsIsReportedAsSuch) {
  scene::Scene scene = static_tank();
  FakeFluidSide fluid(2, FakeFluidSide::constant({0.0, 0.0}));
  fluid.fail_in_equilibration = true;

  EXPECT_EQ(run_session(scene, options_, fluid), 1);

  EXPECT_TRUE(fluid.exchanges.empty());
  ASSERT_EQ(fluid.reported_faults.size(), 1u);
  EXPECT_FALSE(fluid.faults_during_coupled_steps[0]);
  EXPECT_EQ(manifest()["status"], "failed");
  EXPECT_EQ(manifest()["steps"], 0);
}

TEST_F(SessionLoop, NonFiniteFluidForcesStopTheRunAtTheirStep) {
  scene::Scene scene = static_tank();
  FakeFluidSide fluid(2, [](const BoundaryMotion& motion) {
    std::vector<double> forces(motion.positions.size(), 0.0);
    if (motion.step == 5) forces[1] = std::nan("");
    return forces;
  });

  EXPECT_EQ(run_session(scene, options_, fluid), 1);

  EXPECT_EQ(fluid.exchanges.size(), 5u);
  const auto run = manifest();
  EXPECT_EQ(run["status"], "failed");
  EXPECT_NE(run["reason"].get<std::string>().find("fluid forces of step 5 are not finite"),
            std::string::npos);
}

TEST_F(SessionLoop, AFailingHealthCheckStopsTheRunBeforeItsStepIsWritten) {
  scene::Scene scene = static_tank();
  FakeFluidSide fluid(2, FakeFluidSide::constant({0.0, -0.01}));
  fluid.report_health = true;
  fluid.nan_at_step = 7;
  fluid.non_finite_particles = 4;

  EXPECT_EQ(run_session(scene, options_, fluid), 1);

  EXPECT_EQ(fluid.exchanges.size(), 7u);
  const auto run = manifest();
  EXPECT_EQ(run["status"], "failed");
  EXPECT_EQ(run["steps"], 6);
  EXPECT_EQ(run["health"]["failed_check"], "non_finite");
  EXPECT_EQ(run["health"]["steps_checked"], 8);  // step 0 and 1 to 7
  EXPECT_NE(run["reason"].get<std::string>().find(
                "fluid health check 'non_finite' failed: 4 of 1980 particles have a NaN"),
            std::string::npos)
      << run["reason"];
  // The sensors stop at the last good step: rows for t = 0 and steps 1 to 7 (step 7's row holds
  // the forces of step 6, written before its exchange).
  EXPECT_EQ(sensors().at("time").size(), 8u);
  ASSERT_EQ(fluid.reported_faults.size(), 1u);
  EXPECT_TRUE(fluid.faults_during_coupled_steps[0]);
}

TEST_F(SessionLoop, AHealthyFluidIsRecordedInRunJson) {
  scene::Scene scene = static_tank();
  FakeFluidSide fluid(2, FakeFluidSide::constant({0.0, -0.01}));
  fluid.report_health = true;

  EXPECT_EQ(run_session(scene, options_, fluid), 0);

  const auto health = manifest()["health"];
  EXPECT_EQ(health["steps_checked"], kSteps + 1);
  EXPECT_EQ(health["max_density_deviation"], 0.0);
  EXPECT_TRUE(health["failed_check"].is_null());
  EXPECT_EQ(health["limits"]["max_density_deviation"], 0.03);
  EXPECT_EQ(health["limits"]["allowed_lost_particles"], 0);
}

// Both run kinds (coupled and --mbd-only) create their folder this way: a folder that cannot be
// made (here: below a regular file) is an error naming it and the option.
TEST_F(SessionLoop, ARunFolderThatCannotBeCreatedIsAnErrorNamingIt) {
  fs::create_directories(output_);
  std::ofstream(output_ / "a_file") << "not a folder\n";
  const std::string folder = (output_ / "a_file" / "run").string();
  const std::string text = test_support::message_thrown([&] { create_run_folder(folder); });
  EXPECT_NE(text.find("cannot create output folder " + folder), std::string::npos) << text;
  EXPECT_NE(text.find("--output"), std::string::npos) << text;
  EXPECT_NE(text.find("choose a writable folder"), std::string::npos) << text;
}

}  // namespace
}  // namespace fsi::coupling
