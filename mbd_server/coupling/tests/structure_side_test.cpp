// The structure side with each integration method of SolverOptions.Timeint.method, on the coarse
// static tank without fluid: the piston is driven down at v0 = 0.05 m/s from y = 0.0725 m and the
// held bottom carries its weight, so every method must land on the output times with the exact
// motion and report the work it did.
#include <gtest/gtest.h>

#include <string>

#include "fsi/coupling/structure_side.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::coupling {
namespace {

constexpr double kStep = 1e-5;
constexpr int kSteps = 100;
constexpr double kWeight = 0.1 * 9.81;  // of each body [N/m]

class StructureSideMethod : public ::testing::TestWithParam<scene::IntegrationMethod> {};

TEST_P(StructureSideMethod, LandsOnEveryOutputStepWithTheDrivenMotion) {
  scene::Scene scene =
      scene::build_scene(FSI_EXAMPLES_DIR "/static_tank/static_tank_coarse.scene",
                         {{"Resolution.end_time", std::to_string(kSteps * kStep)}});
  StructureSide structure(scene, GetParam());
  int piston_sensor = -1, bottom_constraint_sensor = -1;
  for (std::size_t k = 0; k < scene.sensors.size(); ++k) {
    if (scene.sensors[k].name == "piston_position_y") piston_sensor = static_cast<int>(k);
    if (scene.sensors[k].name == "bottom_constraint_force_y")
      bottom_constraint_sensor = static_cast<int>(k);
  }
  ASSERT_GE(piston_sensor, 0);
  ASSERT_GE(bottom_constraint_sensor, 0);

  for (int n = 1; n <= kSteps; ++n) {
    structure.advance(static_cast<std::uint64_t>(n), kStep);
    ASSERT_EQ(structure.time(), n * kStep);
    const auto values = structure.sensor_readout({});
    EXPECT_NEAR(values[static_cast<std::size_t>(piston_sensor)], 0.0725 - 0.05 * n * kStep, 1e-12)
        << "step " << n;
    EXPECT_NEAR(values[static_cast<std::size_t>(bottom_constraint_sensor)], kWeight, 1e-6 * kWeight)
        << "step " << n;
  }
  const mbd::IntegratorStatistics work = structure.statistics();
  EXPECT_GT(work.steps, 0u);
  EXPECT_GE(work.newton_iterations, work.steps);
  EXPECT_GT(work.jacobian_evaluations, 0u);
  EXPECT_GT(work.factorisations, 0u);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, StructureSideMethod,
                         ::testing::Values(scene::IntegrationMethod::FixedStep,
                                           scene::IntegrationMethod::AdaptiveRadau,
                                           scene::IntegrationMethod::Ida));

}  // namespace
}  // namespace fsi::coupling
