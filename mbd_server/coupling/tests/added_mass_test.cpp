// Artificial added mass (scene block AddedMass; docs/theory.md, "Artificial added mass") on the
// model problem of the added-mass instability: a plate of mass m_s falls under gravity through a
// "fluid" that answers each exchange with the force of an added mass m_f = 3 m_s on the wall's
// acceleration over the last step, -m_f (v(n) - v(n-1)) / dt, the staggered scheme of the coupled
// runs (StructureSide, forces held over the next step). Exactly, the plate falls at
// g m_s / (m_s + m_f). Staggered, the acceleration is multiplied by -m_f / m_s = -3 each step
// without the added mass, and by (ratio m_s - m_f) / ((1 + ratio) m_s) with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/coupling/structure_side.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/output/state_archive.hpp"
#include "fsi/scene/scene.hpp"
#include "fsi/test_support/folder_per_test.hpp"

namespace fsi::coupling {
namespace {

constexpr double kStep = 1e-3;
constexpr double kGravity = 9.81;
constexpr double kPlateMass = 1.0;
constexpr double kFluidAddedMass = 3.0 * kPlateMass;

class AddedMassCoupling : public test_support::FolderPerTest {
 protected:
  std::string scene_path(const std::string& added_mass) const {
    write("s.in", "# script\n");
    const std::string path =
        write("a.scene",
              "scene_language = 1\n"
              "SolverOptions { end_time = 1; Timeint { step_size = 0.001 } }\n"
              "Gravity { acceleration = [0, -9.81] }\n"
              "RigidBody2D { name = \"plate\"; mass = 1; inertia = 0.1; position = [0, 1]\n"
              "  Mesh { points = [[-0.5, 0], [0.5, 0]] } }\n"
              "CoordinateConstraint { body = \"plate\"; coordinate = \"x\" }\n"
              "CoordinateConstraint { body = \"plate\"; coordinate = \"angle\" }\n" +
                  added_mass +
                  "LIGGGHTS { script1 = \"s.in\"; script2 = \"s.in\" }\n"
                  "Coupling { refinement_resolution = 0.002 }\n");
    return path;
  }

  // Exchanges first..last: the structure steps, the "fluid" answers the wall's acceleration over
  // the step (from `previous`, the wall's velocity before it) with the added mass' force, half
  // on each of the two vertices. Appends the accelerations to `result`.
  static void exchange(StructureSide& structure, int first, int last, double& previous,
                       std::vector<double>& result) {
    std::vector<double> positions, velocities;
    for (int n = first; n <= last; ++n) {
      structure.advance(static_cast<std::uint64_t>(n), kStep);
      structure.boundary_state(positions, velocities);
      const double acceleration = (velocities[1] - previous) / kStep;
      previous = velocities[1];
      result.push_back(acceleration);
      const double force = -kFluidAddedMass * acceleration / 2.0;
      structure.apply_vertex_forces(std::vector<double>{0.0, force, 0.0, force},
                                    static_cast<std::uint64_t>(n));
    }
  }

  // The plate's acceleration over each of `steps` exchanges, with `added_mass` scene text.
  std::vector<double> accelerations(const std::string& added_mass, int steps) const {
    scene::Scene scene = scene::build_scene(scene_path(added_mass));
    StructureSide structure(scene, scene::IntegrationMethod::FixedStep);
    double previous = 0.0;
    std::vector<double> result;
    exchange(structure, 1, steps, previous, result);
    return result;
  }
};

TEST_F(AddedMassCoupling, WithoutItTheStaggeredSchemeTriplesTheErrorEveryStep) {
  const std::vector<double> a = accelerations("", 12);
  // 3^11 times the first step's error of 3 g / 4.
  EXPECT_GT(std::abs(a.back()), 1e4 * kGravity);
  EXPECT_NEAR(a[2] / a[1], -3.0, 0.5);  // the error dominates from the start
}

TEST_F(AddedMassCoupling, WithItThePlateFallsAtTheRateOfItsMassAndTheWatersTogether) {
  const double exact = -kGravity * kPlateMass / (kPlateMass + kFluidAddedMass);
  // ratio 2: the error shrinks by (2 - 3) / 3 = -1/3 every step.
  const std::vector<double> a = accelerations("AddedMass { body = \"plate\"; ratio = 2 }\n", 40);
  EXPECT_NEAR(a.back(), exact, 1e-9 * kGravity);
  EXPECT_NEAR((a[11] - exact) / (a[10] - exact), -1.0 / 3.0, 1e-3);
  // ratio 3 = m_f / m_s: exact from the second step on.
  const std::vector<double> b = accelerations("AddedMass { body = \"plate\"; ratio = 3 }\n", 5);
  EXPECT_NEAR(b[1], exact, 1e-9 * kGravity);
  EXPECT_NEAR(b.back(), exact, 1e-9 * kGravity);
}

TEST_F(AddedMassCoupling, ACheckpointCarriesTheLoadHeldOverTheNextStep) {
  const std::string path = scene_path("AddedMass { body = \"plate\"; ratio = 2 }\n");
  scene::Scene whole_scene = scene::build_scene(path);
  StructureSide whole(whole_scene, scene::IntegrationMethod::FixedStep);
  double previous = 0.0;
  std::vector<double> straight;
  exchange(whole, 1, 5, previous, straight);
  output::StateWriter checkpoint;
  whole.save_state(checkpoint);
  const double previous_at_checkpoint = previous;
  exchange(whole, 6, 10, previous, straight);

  scene::Scene resumed_scene = scene::build_scene(path);
  StructureSide resumed(resumed_scene, scene::IntegrationMethod::FixedStep);
  output::StateReader in(checkpoint.bytes(), "test checkpoint");
  resumed.restore_state(in);
  in.finish();
  previous = previous_at_checkpoint;
  std::vector<double> continued;
  exchange(resumed, 6, 10, previous, continued);
  ASSERT_EQ(continued.size(), 5u);
  for (std::size_t k = 0; k < continued.size(); ++k)
    EXPECT_EQ(continued[k], straight[5 + k]) << "exchange " << 6 + k;  // bit for bit
}

// The lag's price (docs/theory.md, "Artificial added mass"): the compensation acts one step late,
// which feeds every stiffness k acting on the body (omega dt = 0.045 here: a plate of 1 kg/m on a
// spring of 1e4 N/m, no fluid, ratio 4, dt = 1e-3 s): undamped the heave grows 2e6 times in one
// second; a damper of ratio dt k pays for the lag.
double heave_after_one_second(const std::string& folder_scene_path) {
  scene::Scene scene = scene::build_scene(folder_scene_path);
  StructureSide structure(scene, scene::IntegrationMethod::FixedStep);
  std::vector<double> positions, velocities;
  double largest = 0.0;
  for (int n = 1; n <= 1000; ++n) {
    structure.advance(static_cast<std::uint64_t>(n), kStep);
    structure.boundary_state(positions, velocities);
    if (n > 850) largest = std::max(largest, std::abs(positions[1] - 0.9));
  }
  return largest;
}

TEST_F(AddedMassCoupling, ItsLagUndampsTheStiffnessesOnTheBodyByRatioTimesTheStep) {
  auto scene_with_damping = [&](const std::string& damping) {
    write("s.in", "# script\n");
    return write("k" + damping + ".scene",
                 "scene_language = 1\n"
                 "SolverOptions { end_time = 1; Timeint { step_size = 0.001 } }\n"
                 "RigidBody2D { name = \"plate\"; mass = 1; inertia = 0.1; position = [0, 1]\n"
                 "  Mesh { points = [[-0.5, 0], [0.5, 0]] } }\n"
                 "CoordinateConstraint { body = \"plate\"; coordinate = \"x\" }\n"
                 "CoordinateConstraint { body = \"plate\"; coordinate = \"angle\" }\n"
                 "SpringDamper { body_a = \"plate\"; point_b = [0, 0]; rest_length = 0.9\n"
                 "  stiffness = 1e4; damping = " +
                     damping +
                     " }\n"
                     "AddedMass { body = \"plate\"; ratio = 4 }\n"
                     "LIGGGHTS { script1 = \"s.in\"; script2 = \"s.in\" }\n"
                     "Coupling { refinement_resolution = 0.002 }\n");
  };
  const double initial = 0.1;
  const double undamped = heave_after_one_second(scene_with_damping("0"));
  EXPECT_GT(undamped, 1e3 * initial);
  const double paid = heave_after_one_second(scene_with_damping("40"));  // 4 * 1e-3 * 1e4
  EXPECT_LT(paid, initial);
}

TEST_F(AddedMassCoupling, ABeamWithoutTheDampingItsLagNeedsIsRefusedWithTheValues) {
  auto outcome = [&](const std::string& damping) -> std::string {
    write("s.in", "# script\n");
    const std::string path =
        write("b.scene",
              "scene_language = 1\n"
              "SolverOptions { end_time = 1; Timeint { step_size = 0.001 } }\n"
              "AncfBeam2D { name = \"strip\"; start = [0, 0]; end = [0, -0.04]; elements = 2\n"
              "  axial_stiffness = 1.5e4; bending_stiffness = 0.03; mass_per_length = 5.5\n"
              "  thickness = 0.005 " +
                  damping +
                  " }\n"
                  "BeamClamp { beam = \"strip\"; node = 0 }\n"
                  "AddedMass { body = \"strip\"; ratio = 4 }\n"
                  "LIGGGHTS { script1 = \"s.in\"; script2 = \"s.in\" }\n"
                  "Coupling { refinement_resolution = 0.002 }\n");
    try {
      scene::build_scene(path);
    } catch (const Error& error) {
      return error.what();
    }
    return "(accepted)";
  };
  const std::string refused = outcome("");
  EXPECT_NE(refused.find("b.scene:7:29:"), std::string::npos) << refused;
  EXPECT_NE(refused.find("needs axial_damping >= ratio dt EA = 60 and bending_damping >= ratio dt "
                         "EI = 0.00012 (dt = 0.001 s"),
            std::string::npos)
      << refused;
  EXPECT_EQ(outcome("; axial_damping = 60; bending_damping = 1.2e-4"), "(accepted)");
  EXPECT_NE(outcome("; axial_damping = 60; bending_damping = 1e-4").find("needs axial_damping"),
            std::string::npos);
}

TEST_F(AddedMassCoupling, AnMbdOnlyRunIntegratesTheBodysOwnMass) {
  write("s.in", "# script\n");
  const std::string path = write("m.scene",
                                 "scene_language = 1\n"
                                 "SolverOptions { end_time = 1; Timeint { step_size = 0.001 } }\n"
                                 "RigidBody2D { name = \"plate\"; mass = 2; inertia = 0.1 }\n"
                                 "AddedMass { body = \"plate\"; ratio = 4 }\n");
  const scene::Scene mbd_only = scene::build_scene(path, {}, scene::SceneMode::MbdOnly);
  EXPECT_FALSE(mbd_only.model.has_added_mass());
  EXPECT_DOUBLE_EQ(mbd_only.model.mass_matrix()(0, 0), 2.0);
}

}  // namespace
}  // namespace fsi::coupling
