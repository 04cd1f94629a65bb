#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fsi/scene/physics_checks.hpp"
#include "fsi/scene/scene.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

using testing::listing;

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

const std::string kCoarseTank = FSI_EXAMPLES_DIR "/static_tank/static_tank_coarse.scene";
const std::string kThesisTank = FSI_EXAMPLES_DIR "/static_tank/static_tank.scene";

std::vector<Diagnostic> of(const std::vector<Diagnostic>& diagnostics, std::string_view check,
                           Severity severity = Severity::Warning) {
  std::vector<Diagnostic> found;
  for (const Diagnostic& diagnostic : diagnostics) {
    if (diagnostic.check == check && diagnostic.severity == severity) found.push_back(diagnostic);
  }
  return found;
}

// The one warning of `check` on the coarse tank with `overrides`.
Diagnostic coarse_warning(std::string_view check, const std::vector<Override>& overrides) {
  const std::vector<Diagnostic> found =
      of(physics_checks(build_scene(kCoarseTank, overrides)), check);
  EXPECT_EQ(found.size(), 1u) << check << "\n" << listing(found);
  return found.empty() ? Diagnostic{} : found.front();
}

std::vector<Diagnostic> coarse_diagnostics(const std::vector<Override>& overrides) {
  return physics_checks(build_scene(kCoarseTank, overrides));
}

// Script 1 of the small scene: the fluid's gravity and the coupling fix with the wall law of the
// LIGGGHTS_SPH_parameters.
const std::string kSetUp =
    "# set-up\n"
    "fix gravity all gravity 9.81 vector 0.0 -1.0 0.0\n"
    "fix fsi all fsi/sph k ${SPH_wall_rep} t ${SPH_wall_visc} r0 ${SPH_wall_equilibriumdist} &\n"
    "    cutoff ${SPH_wall_cutoff}\n";

// Script 2 of the small scene: the fluid's artificial viscosity, alpha = 0.8 with c = 20 m/s and
// h = 0.001 m, is nu = alpha c h / 16 = 1e-3 m^2/s, the `viscosity` of kGoodSph.
const std::string kAfter =
    "# after the equilibration\n"
    "fix m1 all property/global speedOfSound peratomtype 20\n"
    "fix m2 all property/global sl peratomtype 0.001\n"
    "fix m3 all property/global artViscAlpha peratomtype 0.8\n"
    "pair_style sph/artVisc/tensCorr spiky2d 0.001 artVisc\n";

class SmallScene : public testing::FolderPerTest {
 protected:
  void SetUp() override {
    testing::FolderPerTest::SetUp();
    set_up_script(kSetUp);
    std::ofstream(folder_ / "after.in") << kAfter;
  }

  void set_up_script(const std::string& text) { std::ofstream(folder_ / "setup.in") << text; }

  Scene build(const std::string& sph, const std::string& extra) {
    std::ofstream(folder_ / "small.scene")
        << "scene_language = 1\n"
           "SolverOptions { end_time = 0.1; Timeint { step_size = 5e-6 } }\n"
           "Gravity { acceleration = [0, -9.81] }\n"
           "Ground { Mesh { points = [[0, 0], [0.1, 0]] } }\n"
           "LIGGGHTS { script1 = \"setup.in\"; script2 = \"after.in\" }\n"
           "Coupling { refinement_resolution = 0.002 }\n"
           "LIGGGHTS_SPH_parameters {\n"
        << sph << "\n}\n"
        << extra << "\n";
    return build_scene((folder_ / "small.scene").string());
  }
};

// A small scene of our own in a temporary folder: a floor from x = 0 to 0.1 at y = 0, gravity
// (0, -9.81) for the structure (Gravity block) and the fluid (script 1's fix gravity), a fluid
// box above it, the LIGGGHTS variables `sph` and any `extra` blocks.
// h = 0.001 m, d = h/1.9, c = 20 m/s, a fluid box 0.02 m high starting h above the floor.
const std::string kGoodSph =
    "smoothinglength = 0.001; cAB = 20; viscosity = 1e-3\n"
    "SPH_wall_rep = 2000; SPH_wall_visc = 1000; SPH_wall_equilibriumdist = 0.002\n"
    "SPH_wall_cutoff = 0.002";
const std::string kGoodFluid =
    "FluidRegion { shape = \"box\"; lower = [0.01, 0.001]; upper = [0.09, 0.021]; "
    "spacing = 0.001/1.9; density = 1000 }";

TEST(PhysicsChecks, TheStaticTanksGetOnlyTheExplainedRepulsionWarning) {
  // k = 17500 N/m^2 is the thesis' own value (§5.6), 58 rho0 g h_max: explained in the README.
  for (const std::string& file : {kCoarseTank, kThesisTank}) {
    const std::vector<Diagnostic> diagnostics = physics_checks(build_scene(file));
    ASSERT_EQ(diagnostics.size(), 1u) << file << ":\n" << listing(diagnostics);
    EXPECT_EQ(diagnostics.front().check, "wall_repulsion");
    EXPECT_CONTAINS(diagnostics.front().message, "k = 17500 N/m^2 is 57.9 rho0 g h_max, above");
    EXPECT_CONTAINS(diagnostics.front().text(), "static_tank_model.inc:");
  }
}

TEST(PhysicsChecks, ImplicitEulerIsWarnedWithTheDampingItAdds) {
  // Radau IIA with 1 stage at h = 0.005 s (the Turek-Hron CSM3 beam, 1.1 Hz, measured by a user:
  // the amplitude halved over 10 s): per period T the factor (1 + (2 pi h / T)^2)^(-T / 2h).
  const auto warnings = [](const std::vector<Override>& overrides) {
    return integrator_check(build_scene(kCoarseTank, overrides));
  };
  const std::vector<Diagnostic> found =
      warnings({{"SolverOptions.Timeint.stages", "1"}, {"Resolution.time_step", "0.005"}});
  ASSERT_EQ(found.size(), 1u) << listing(found);
  const Diagnostic& warning = found.front();
  EXPECT_EQ(warning.check, "integrator_damping");
  EXPECT_CONTAINS(warning.message, "implicit Euler (first order): at the structure step 0.005 s");
  EXPECT_CONTAINS(warning.message,
                  "loses 0.982 % per period of 10 s, 9.39 % per period of 1 s, 61 % per "
                  "period of 0.1 s");
  EXPECT_CONTAINS(warning.fix, "use stages = 2 or 3");
  EXPECT_CONTAINS(warning.location.text(), "--set SolverOptions.Timeint.stages=1");  // its source
  // A short step names the short periods it damps too (a user's connecting rod rang at 5 ms and
  // the warning spoke of 0.1 s only), down to 4 steps.
  const std::vector<Diagnostic> short_step =
      warnings({{"SolverOptions.Timeint.stages", "1"}, {"Resolution.time_step", "1e-4"}});
  ASSERT_EQ(short_step.size(), 1u) << listing(short_step);
  EXPECT_CONTAINS(short_step.front().message, "per period of 0.01 s, ");
  EXPECT_CONTAINS(short_step.front().message, "per period of 0.001 s of its amplitude");
  // Orders 3 and 5, and an error-controlled method, are not warned; nor is it a fluid rule.
  EXPECT_TRUE(warnings({{"SolverOptions.Timeint.stages", "2"}}).empty());
  EXPECT_TRUE(warnings({{"SolverOptions.Timeint.stages", "1"},
                        {"SolverOptions.Timeint.method", "\"adaptive\""}})
                  .empty());
  EXPECT_TRUE(of(coarse_diagnostics({{"SolverOptions.Timeint.stages", "1"}}), "integrator_damping")
                  .empty());
}

TEST(PhysicsChecks, AcousticTimeStepAboveTheMeasuredLimit) {
  const Diagnostic warning =
      coarse_warning("acoustic_time_step", {{"Resolution.time_step", "1.5e-5"}});
  EXPECT_CONTAINS(warning.message, "dt c/h = 0.188 (h = 0.0016 m, c = 20 m/s)");
  EXPECT_CONTAINS(warning.message, "within the acoustic CFL limit 0.25 h/c of thesis §6.2");
  EXPECT_CONTAINS(warning.message, "above 0.125 h/c = 1e-05 s");
  EXPECT_CONTAINS(warning.message, "blew up at dt c/h = 0.163");
  EXPECT_EQ(warning.fix, "use SolverOptions.Timeint.step_size <= 1e-05 s");
  EXPECT_CONTAINS(warning.location.text(), "static_tank_model.inc:");
}

TEST(PhysicsChecks, AcousticTimeStepAtTheLimitToThePrintedDigitsIsNotWarned) {
  // 1.0000005e-5 s against 0.125 h/c = 1e-05 s: beyond it only past the three digits printed
  // ("above 1e-05 s ... use <= 1e-05 s"); 1.01e-5 s is warned.
  EXPECT_TRUE(
      of(coarse_diagnostics({{"Resolution.time_step", "1.0000005e-5"}}), "acoustic_time_step")
          .empty());
  EXPECT_EQ(
      of(coarse_diagnostics({{"Resolution.time_step", "1.01e-5"}}), "acoustic_time_step").size(),
      1u);
}

TEST(PhysicsChecks, AcousticTimeStepAboveTheThesisLimit) {
  const Diagnostic warning =
      coarse_warning("acoustic_time_step", {{"Resolution.time_step", "3e-5"}});
  EXPECT_CONTAINS(warning.message, "dt c/h = 0.375");
  EXPECT_CONTAINS(warning.message, "above the acoustic CFL limit dt <= 0.25 h/c = 2e-05 s");
}

TEST(PhysicsChecks, TheBlownUpThesisRunIsFlaggedTwice) {
  // docs/validation.md: dt = 5e-6 s at h = 0.000614 m blew up at t = 0.636 s.
  const std::vector<Diagnostic> diagnostics =
      physics_checks(build_scene(kThesisTank, {{"Resolution.time_step", "5e-6"}}));
  ASSERT_EQ(of(diagnostics, "acoustic_time_step").size(), 1u);
  EXPECT_CONTAINS(of(diagnostics, "acoustic_time_step")[0].message, "dt c/h = 0.163");
  ASSERT_EQ(of(diagnostics, "contact_time_step").size(), 1u);
  const std::string contact = of(diagnostics, "contact_time_step")[0].message;
  // m = 1000 (0.000614/1.9)^2 = 1.04e-4 kg/m, k_eff = 4k = 7e4 N/m^2: sqrt(m/k_eff) = 3.86e-5 s.
  EXPECT_CONTAINS(contact, "sqrt(m/k_eff) = 3.86e-05 s");
  EXPECT_CONTAINS(contact, "= 70000 N/m^2 with k = 17500 N/m^2");
  EXPECT_CONTAINS(contact, "is 0.129 sqrt(m/k_eff)");
  EXPECT_CONTAINS(of(diagnostics, "contact_time_step")[0].fix, "<= 3.86e-06 s");
}

TEST(PhysicsChecks, ContactTimeStepWithAStifferWall) {
  // k = 70000: k_eff = 2.8e5 N/m^2, m = 7.09e-4 kg/m, sqrt(m/k_eff) = 5.03e-5 s; dt = 1e-5 s.
  const Diagnostic warning =
      coarse_warning("contact_time_step", {{"LIGGGHTS_SPH_parameters.SPH_wall_rep", "70000"}});
  EXPECT_CONTAINS(warning.message, "time step dt = 1e-05 s is 0.199 sqrt(m/k_eff)");
  EXPECT_CONTAINS(warning.message, "particle mass m = 0.000709 kg/m");
  EXPECT_CONTAINS(warning.message, "k_eff = r_c max|df/dd|");
  EXPECT_EQ(warning.fix,
            "use SolverOptions.Timeint.step_size <= 5.03e-06 s, or a smaller SPH_wall_rep if the "
            "walls hold with it");
}

TEST(PhysicsChecks, ContactStiffnessFollowsTheEquilibriumDistance) {
  // r0 = r_c / 2: k_eff = k (4 r_c^2 - 2 (r_c/2)^2) / (r_c/2 * 3 r_c/2) = 14 k / 3.
  const Diagnostic warning = coarse_warning(
      "contact_time_step", {{"LIGGGHTS_SPH_parameters.SPH_wall_rep", "70000"},
                            {"LIGGGHTS_SPH_parameters.SPH_wall_equilibriumdist", "0.0016"}});
  EXPECT_CONTAINS(warning.message, "= 327000 N/m^2 with k = 70000");
}

TEST_F(SmallScene, ContactCheckSkippedForTheLennardJonesLaw) {
  std::ofstream(folder_ / "setup.in")
      << "fix fsi all fsi/sph k 2000 t 1 r0 0.002 &\n    cutoff 0.002 law lj p1 12 p2 6\n";
  const std::vector<Diagnostic> diagnostics = physics_checks(build(kGoodSph, kGoodFluid));
  const auto infos = of(diagnostics, "contact_time_step", Severity::Info);
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_EQ(infos[0].message,
            "fix fsi/sph uses law lj, the estimate covers the thesis law only: contact time-step "
            "check skipped");
}

TEST(PhysicsChecks, SpeedOfSoundAgainstFreeFall) {
  // U = sqrt(2 * 9.81 * 0.0308) = 0.777 m/s.
  const Diagnostic warning =
      coarse_warning("speed_of_sound", {{"LIGGGHTS_SPH_parameters.cAB", "5"}});
  EXPECT_CONTAINS(warning.message, "c = 5 m/s is below 10x the expected flow speed U = 0.777 m/s");
  EXPECT_CONTAINS(warning.message, "sqrt(2 g H) with g = 9.81 m/s^2, H = 0.0308 m");
  EXPECT_CONTAINS(warning.message, "(U/c)^2 = 2.42 %");
  EXPECT_CONTAINS(warning.fix, "raise cAB to >= 7.77 m/s");
}

TEST(PhysicsChecks, SpeedOfSoundAgainstAPrescribedVelocity) {
  const Diagnostic warning = coarse_warning("speed_of_sound", {{"Geometry.piston_v0", "3"}});
  EXPECT_CONTAINS(warning.message, "U = 3 m/s (VelocityConstraint on piston.y)");
  EXPECT_CONTAINS(warning.fix, ">= 30 m/s");
}

TEST_F(SmallScene, SpeedOfSoundAgainstARotationUsesTheBodyRadius) {
  // 2 rad/s on a body whose mesh reaches 0.05 m from its centre: 0.1 m/s; gravity off.
  const Scene scene =
      build("cAB = 0.5",
            "RigidBody2D { name = \"paddle\"; mass = 1; inertia = 1; position = [0.05, 0.5]; "
            "angular_velocity = 2\n"
            "  Mesh { points = [[-0.05, 0], [0.05, 0]] } }\n"
            "VelocityConstraint { body = \"paddle\"; coordinate = \"angle\"; velocity = 2 }\n"
            "Gravity.acceleration = [0, 0]");
  const auto warnings = of(physics_checks(scene), "speed_of_sound");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_CONTAINS(warnings[0].message, "U = 0.1 m/s (VelocityConstraint on paddle.angle)");
}

TEST(PhysicsChecks, WallRepulsionBelowTheThesisRange) {
  // rho0 g h_max = 1000 * 9.81 * 0.0308 = 302 N/m^2.
  const Diagnostic warning =
      coarse_warning("wall_repulsion", {{"LIGGGHTS_SPH_parameters.SPH_wall_rep", "300"}});
  EXPECT_CONTAINS(warning.message,
                  "k = 300 N/m^2 is 0.993 rho0 g h_max, below the thesis' 2-20 "
                  "rho0 g h_max = 604-6040 N/m^2");
  EXPECT_CONTAINS(warning.message, "particles may pass through the walls");
  EXPECT_CONTAINS(warning.fix, "between 604 and 6040 N/m^2");
}

TEST(PhysicsChecks, WallRepulsionInsideTheThesisRangeIsSilent) {
  EXPECT_TRUE(
      of(coarse_diagnostics({{"LIGGGHTS_SPH_parameters.SPH_wall_rep", "3000"}}), "wall_repulsion")
          .empty());
}

TEST(PhysicsChecks, KernelNeighboursTooFewAndTooMany) {
  // d = h: pi (2h)^2 / h^2 = 4 pi = 12.6; d = h/3: 36 pi = 113.
  Diagnostic warning = coarse_warning(
      "kernel_neighbours", {{"LIGGGHTS_SPH_parameters.particlespacing", "smoothinglength"}});
  EXPECT_CONTAINS(warning.message,
                  "pi (2h)^2 / d^2 = 12.6 particles lie within the kernel support");
  EXPECT_CONTAINS(warning.message, "outside the thesis' 30-100");
  // d = 2h sqrt(pi/N): 0.000567 m for N = 100, 0.00104 m for N = 30.
  EXPECT_EQ(warning.fix, "choose the spacing between 0.000567 and 0.00104 m");
  warning = coarse_warning("kernel_neighbours",
                           {{"LIGGGHTS_SPH_parameters.particlespacing", "smoothinglength/3"}});
  EXPECT_CONTAINS(warning.message, "= 113 particles");
}

// The 3D example: the checks that hold in 3D run with 3D geometry (fluid height along z, the
// 3D neighbour count); the 2D-only ones are skipped with an info, not mis-reported.
TEST(PhysicsChecks, TheThreeDimensionalBoxGetsThreeDimensionalChecks) {
  const std::string box3d = FSI_EXAMPLES_DIR "/hydrostatic_box_3d/hydrostatic_box_3d.scene";
  const auto checks = physics_checks(build_scene(box3d));
  // Only the example's deliberate wall friction (its README), against the declared nu and the
  // fluid's alpha (3D: nu = alpha c h / 20).
  ASSERT_EQ(of(checks, "wall_viscosity").size(), 1u) << listing(checks);
  ASSERT_EQ(of(checks, "viscosity_match").size(), 1u) << listing(checks);
  EXPECT_CONTAINS(of(checks, "viscosity_match")[0].message, "nu = alpha c h / 20 = 5e-05 m^2/s");
  EXPECT_EQ(std::count_if(checks.begin(), checks.end(),
                          [](const Diagnostic& d) { return d.severity == Severity::Warning; }),
            2)
      << listing(checks);
  for (const char* skipped : {"contact_time_step", "fluid_overlap"}) {
    const auto infos = of(checks, skipped, Severity::Info);
    ASSERT_EQ(infos.size(), 1u) << skipped << "\n" << listing(checks);
    EXPECT_CONTAINS(infos[0].message, "a 3D scene");
  }
  // k = 100 N/m^2 against rho0 g H with H = 0.008 m along z (78.5 N/m^2): below 2-20.
  const auto soft =
      physics_checks(build_scene(box3d, {{"LIGGGHTS_SPH_parameters.SPH_wall_rep", "100"}}));
  ASSERT_EQ(of(soft, "wall_repulsion").size(), 1u) << listing(soft);
  EXPECT_CONTAINS(of(soft, "wall_repulsion")[0].message, "fluid height h_max = 0.008 m");
  // d = h: 4/3 pi (2h)^3 / d^3 = 33.5 is fine in 3D; d = 1.5 h gives 9.93, too few.
  const auto sparse = physics_checks(
      build_scene(box3d, {{"LIGGGHTS_SPH_parameters.particlespacing", "1.5*smoothinglength"}}));
  ASSERT_EQ(of(sparse, "kernel_neighbours").size(), 1u) << listing(sparse);
  EXPECT_CONTAINS(of(sparse, "kernel_neighbours")[0].message, "4/3 pi (2h)^3 / d^3 = 9.93");
}

TEST(PhysicsChecks, WallViscosityMoreThanAFactorThreeOff) {
  // rho0 nu / r_v = 1000 * 1e-3 / 0.0032 = 312.5 N s/m^3 (r_v = the fix's cutoff 2h).
  const Diagnostic warning =
      coarse_warning("wall_viscosity", {{"LIGGGHTS_SPH_parameters.SPH_wall_visc", "5000"}});
  EXPECT_CONTAINS(warning.message,
                  "t = 5000 N s/m^3 is 16x the no-slip value t = rho0 nu / r_v = 312 N s/m^3");
  EXPECT_CONTAINS(warning.message, "r_v = 0.0032 m, the fix's cutoff_visc");
  EXPECT_EQ(warning.fix, "set SPH_wall_visc = 312 (SPHdensity*viscosity/r_v)");
  EXPECT_EQ(coarse_warning("wall_viscosity", {{"LIGGGHTS_SPH_parameters.SPH_wall_visc", "80"}})
                .message.substr(0, 40),
            "wall viscosity t = 80 N s/m^3 is 0.256x ");
  EXPECT_TRUE(
      of(coarse_diagnostics({{"LIGGGHTS_SPH_parameters.SPH_wall_visc", "900"}}), "wall_viscosity")
          .empty());
}

TEST(PhysicsChecks, FluidBoxTooCloseToAWall) {
  const Diagnostic warning =
      coarse_warning("fluid_overlap", {{"FluidRegion.lower", "[0.0005, 0.0041]"}});
  EXPECT_CONTAINS(warning.message, "comes within 0.0005 m of the mesh of the ground");
  EXPECT_CONTAINS(warning.message, "closer than r0/2 = 0.0016 m");
  EXPECT_EQ(warning.fix, "leave at least 0.0016 m between the fluid box and the mesh");
}

TEST(PhysicsChecks, FluidBoxOverlappingThePiston) {
  // Fill height 0.08 m: the box reaches y = 0.0841 m, the piston's lower face is at 0.07 m.
  const Diagnostic warning = coarse_warning("fluid_overlap", {{"Geometry.fill_height", "0.08"}});
  EXPECT_CONTAINS(warning.message,
                  "overlaps the mesh of body 'piston' (segment (0, 0.07)-(0.05, "
                  "0.07)): particles start on or inside the structure");
}

TEST_F(SmallScene, FluidBoxNearARotatedBody) {
  // A square of half-width 0.01 m at (0.05, 0.05): turned by 45 degrees its corner reaches
  // x = 0.0359 m, 0.0009 m from the box (r0/2 = 0.001 m); unturned it stays 0.005 m away.
  const std::string fluid =
      "FluidRegion { shape = \"box\"; lower = [0.01, 0.001]; upper = [0.035, 0.08]; "
      "spacing = 0.001/1.9; density = 1000 }\n";
  const std::string body =
      "RigidBody2D { name = \"block\"; mass = 1; inertia = 1; position = [0.05, 0.05]; angle = "
      "ANGLE\n  Mesh { points = [[-0.01, -0.01], [0.01, -0.01], [0.01, 0.01], [-0.01, 0.01]]; "
      "closed = 1 } }\n";
  auto with_angle = [&](const std::string& angle) {
    std::string text = body;
    text.replace(text.find("ANGLE"), 5, angle);
    return text;
  };
  EXPECT_TRUE(
      of(physics_checks(build(kGoodSph, fluid + with_angle("0"))), "fluid_overlap").empty());
  const auto warnings =
      of(physics_checks(build(kGoodSph, fluid + with_angle("pi/4"))), "fluid_overlap");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_CONTAINS(warnings[0].message, "comes within 0.000858 m of the mesh of body 'block'");
}

// An elastic baffle drawn through the water (a user's trial, 2026-12-06: the check read the
// RigidBody2D and Ground blocks only and said nothing): a beam's outline is checked like any mesh.
TEST_F(SmallScene, FluidBoxThroughABeam) {
  const std::string fluid =
      "FluidRegion { shape = \"box\"; lower = [0.01, 0.001]; upper = [0.035, 0.02]; "
      "spacing = 0.001/1.9; density = 1000 }\n";
  auto baffle = [](const std::string& x) {
    return "AncfBeam2D { name = \"baffle\"; start = [" + x + ", 0]; end = [" + x +
           ", 0.03]; elements = 3; thickness = 0.002; axial_stiffness = 1e6; "
           "bending_stiffness = 0.1; mass_per_length = 2 }\n"
           "BeamClamp { beam = \"baffle\"; node = 0 }\n";
  };
  const auto through = of(physics_checks(build(kGoodSph, fluid + baffle("0.02"))), "fluid_overlap");
  ASSERT_EQ(through.size(), 1u);
  EXPECT_CONTAINS(through[0].message,
                  "the fluid box (0.01, 0.001)-(0.035, 0.02) overlaps the "
                  "mesh of body 'baffle'");
  const auto clear = physics_checks(build(kGoodSph, fluid + baffle("0.05")));
  EXPECT_TRUE(of(clear, "fluid_overlap").empty()) << listing(clear);
}

// Water on both sides of a gate: each FluidRegion is checked against the meshes, and the one
// that reaches into the gate is named.
TEST_F(SmallScene, EachOfSeveralFluidRegionsAgainstTheMeshes) {
  const std::string gate =
      "AncfBeam2D { name = \"gate\"; start = [0.04, 0]; end = [0.04, 0.03]; elements = 3; "
      "thickness = 0.002; axial_stiffness = 1e6; bending_stiffness = 0.1; mass_per_length = 2 }\n"
      "BeamClamp { beam = \"gate\"; node = 0 }\n";
  auto regions = [](const std::string& downstream_lower) {
    return "FluidRegion { shape = \"box\"; lower = [0.01, 0.001]; upper = [0.035, 0.02]; "
           "spacing = 0.001/1.9; density = 1000 }\n"
           "FluidRegion { shape = \"box\"; lower = [" +
           downstream_lower +
           ", 0.001]; upper = [0.07, 0.01]; spacing = 0.001/1.9; density = 1000 }\n";
  };
  const auto clear = physics_checks(build(kGoodSph, regions("0.045") + gate));
  EXPECT_TRUE(of(clear, "fluid_overlap").empty()) << listing(clear);
  const auto through =
      of(physics_checks(build(kGoodSph, regions("0.039") + gate)), "fluid_overlap");
  ASSERT_EQ(through.size(), 1u);
  EXPECT_CONTAINS(through[0].message,
                  "the fluid box (0.039, 0.001)-(0.07, 0.01) overlaps the mesh of body 'gate'");
  EXPECT_CONTAINS(through[0].fix, "FluidRegion[1].lower/upper");
}

TEST_F(SmallScene, FluidPolygonAroundABodyInItsHole) {
  // The square of half-width 0.01 m at (0.05, 0.05) sits in a square hole of the fluid polygon:
  // a hole of half-width 0.015 m leaves 0.005 m, one of 0.0105 m only 0.0005 m (r0/2 = 0.001 m),
  // and one of 0.005 m puts fluid inside the body.
  const std::string body =
      "RigidBody2D { name = \"block\"; mass = 1; inertia = 1; position = [0.05, 0.05]\n"
      "  Mesh { points = [[-0.01, -0.01], [0.01, -0.01], [0.01, 0.01], [-0.01, 0.01]]; "
      "closed = 1 } }\n";
  auto with_hole = [&](const std::string& low, const std::string& high) {
    return "FluidRegion { shape = \"polygon\"; spacing = 0.001/1.9; density = 1000\n"
           "  points = [[0.01, 0.001], [0.09, 0.001], [0.09, 0.08], [0.01, 0.08]]\n"
           "  Hole { points = [[" +
           low + ", " + low + "], [" + high + ", " + low + "], [" + high + ", " + high + "], [" +
           low + ", " + high + "]] } }\n" + body;
  };
  const auto clear = physics_checks(build(kGoodSph, with_hole("0.035", "0.065")));
  EXPECT_TRUE(of(clear, "fluid_overlap").empty()) << listing(clear);
  EXPECT_TRUE(of(clear, "fluid_overlap", Severity::Info).empty()) << listing(clear);
  const auto close =
      of(physics_checks(build(kGoodSph, with_hole("0.0395", "0.0605"))), "fluid_overlap");
  ASSERT_EQ(close.size(), 1u);
  EXPECT_CONTAINS(close[0].message,
                  "the fluid polygon comes within 0.0005 m of the mesh of body 'block'");
  EXPECT_EQ(close[0].location.line, 13);  // FluidRegion.points
  const auto inside =
      of(physics_checks(build(kGoodSph, with_hole("0.045", "0.055"))), "fluid_overlap");
  ASSERT_EQ(inside.size(), 1u);
  EXPECT_CONTAINS(inside[0].message,
                  "the fluid polygon overlaps the mesh of body 'block' (segment (0.04, "
                  "0.04)-(0.06, 0.04)): particles start on or inside the structure");
}

TEST_F(SmallScene, AGoodSceneIsSilent) {
  const std::vector<Diagnostic> diagnostics = physics_checks(build(kGoodSph, kGoodFluid));
  for (const Diagnostic& diagnostic : diagnostics)
    ADD_FAILURE() << diagnostic.text();
}

TEST_F(SmallScene, MissingInputsSkipChecksWithOneInfoEach) {
  // No cAB, no SPH_wall_* values, no FluidRegion (so no spacing, density or fluid height); the
  // fix line gives its numbers itself.
  set_up_script(
      "fix gravity all gravity 9.81 vector 0.0 -1.0 0.0\n"
      "fix fsi all fsi/sph k 2000 t 1000 r0 0.002 cutoff 0.002\n");
  const std::vector<Diagnostic> diagnostics =
      physics_checks(build("smoothinglength = 0.001; viscosity = 1e-3", ""));
  for (const Diagnostic& diagnostic : diagnostics)
    EXPECT_EQ(diagnostic.severity, Severity::Info) << diagnostic.text();
  // Every check but gravity and liggghts_scripts, whose inputs (the Gravity block, the scripts)
  // are all there.
  ASSERT_EQ(diagnostics.size(), std::size(kPhysicsCheckNames) - 2) << listing(diagnostics);
  EXPECT_TRUE(of(diagnostics, "gravity", Severity::Info).empty()) << listing(diagnostics);
  EXPECT_EQ(of(diagnostics, "acoustic_time_step", Severity::Info)[0].message,
            "no 'cAB' in LIGGGHTS_SPH_parameters: acoustic time-step check skipped");
  EXPECT_EQ(of(diagnostics, "speed_of_sound", Severity::Info)[0].message,
            "no 'cAB' in LIGGGHTS_SPH_parameters: speed-of-sound check skipped");
  EXPECT_CONTAINS(of(diagnostics, "wall_viscosity", Severity::Info)[0].message,
                  "no 'SPHdensity' in LIGGGHTS_SPH_parameters");
  EXPECT_CONTAINS(of(diagnostics, "kernel_neighbours", Severity::Info)[0].message,
                  "no 'particlespacing' in LIGGGHTS_SPH_parameters");
  EXPECT_CONTAINS(of(diagnostics, "fluid_overlap", Severity::Info)[0].message, "no FluidRegion");
  EXPECT_EQ(of(diagnostics, "fluid_overlap", Severity::Info)[0].location.text(),
            (folder_ / "small.scene").string());
}

TEST_F(SmallScene, AnUnsetWallViscosityGetsTheSuggestedValue) {
  // Without a fix line the checks read the wall law from LIGGGHTS_SPH_parameters (and say that
  // script 1 lacks the fix).
  set_up_script("fix gravity all gravity 9.81 vector 0.0 -1.0 0.0\n");
  std::vector<Diagnostic> diagnostics = physics_checks(
      build("smoothinglength = 0.001; cAB = 20; viscosity = 1e-3; SPH_wall_rep = 2000\n"
            "SPH_wall_equilibriumdist = 0.002; SPH_wall_cutoff = 0.002",
            kGoodFluid));
  ASSERT_EQ(of(diagnostics, "liggghts_scripts").size(), 1u) << listing(diagnostics);
  diagnostics = of(diagnostics, "wall_viscosity", Severity::Info);
  ASSERT_EQ(diagnostics.size(), 1u) << listing(diagnostics);
  EXPECT_EQ(diagnostics[0].message,
            "no 'SPH_wall_visc' in LIGGGHTS_SPH_parameters (no slip at the wall needs t = rho0 nu "
            "/ r_v = 500 N s/m^3, docs/theory.md \"Viscosity\"): wall-viscosity check skipped");
}

TEST(PhysicsChecks, SeveralProblemsAreAllListed) {
  const std::vector<Diagnostic> diagnostics = coarse_diagnostics({
      {"Resolution.time_step", "3e-5"},                                // acoustic, contact
      {"LIGGGHTS_SPH_parameters.cAB", "7"},                            // speed of sound
      {"LIGGGHTS_SPH_parameters.particlespacing", "smoothinglength"},  // neighbours
      {"LIGGGHTS_SPH_parameters.SPH_wall_visc", "10"},                 // wall viscosity
      {"FluidRegion.lower", "[0.0005, 0.0041]"},                       // overlap
      {"Gravity.acceleration", "[0, -9.8]"},                           // gravity
      {"LIGGGHTS.script1", "\"static_tank.in2\""},  // liggghts_scripts: twice (below)
  });
  // Script 2 run as script 1 lacks the fix and uses ${alpha}, which script 1 defines. Without
  // the fix there is no wall friction to match against the fluid: viscosity_match is skipped.
  for (std::string_view check : kPhysicsCheckNames) {
    const std::size_t expected = check == "liggghts_scripts"  ? 2u
                                 : check == "viscosity_match" ? 0u
                                                              : 1u;
    EXPECT_EQ(of(diagnostics, check).size(), expected) << check;
  }
  EXPECT_EQ(of(diagnostics, "viscosity_match", Severity::Info).size(), 1u) << listing(diagnostics);
  EXPECT_EQ(diagnostics.size(), std::size(kPhysicsCheckNames) + 1) << listing(diagnostics);
}

TEST(PhysicsChecks, FluidGravityOtherThanTheStructuresIsFlaggedAtTheScriptLine) {
  // static_tank.in1 line 43: fix gravity all gravity ${gravity} vector 0.0 -1.0 0.0
  const Diagnostic found = coarse_warning("gravity", {{"LIGGGHTS_SPH_parameters.gravity", "9.80"}});
  EXPECT_CONTAINS(found.location.text(), "static_tank.in1:43:1");
  EXPECT_CONTAINS(found.message, "fix gravity gives the fluid g = (0, -9.8, 0) m/s^2");
  EXPECT_CONTAINS(found.message, "the Gravity block gives the structure g = (0, -9.81, 0) m/s^2");
  EXPECT_CONTAINS(found.message, "static_tank_model.inc:");
  EXPECT_EQ(found.fix, "make Gravity.acceleration and the script's fix gravity the same vector");
  // The same magnitude along another direction is just as wrong.
  const Diagnostic tilted = coarse_warning("gravity", {{"Gravity.acceleration", "[-9.81, 0]"}});
  EXPECT_CONTAINS(tilted.message, "the structure g = (-9.81, 0, 0)");
}

TEST_F(SmallScene, FluidGravityAlongAnotherDirectionIsFlagged) {
  set_up_script("fix down all gravity 9.81 &\n  vector 2.0 0 0   # sideways, not a unit vector\n");
  const std::vector<Diagnostic> found = of(physics_checks(build(kGoodSph, kGoodFluid)), "gravity");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].location.line, 1);
  EXPECT_CONTAINS(found[0].message, "fix down gives the fluid g = (9.81, 0, 0) m/s^2");
}

TEST_F(SmallScene, OnlyTheCoupledRunsGravityCounts) {
  // An equilibration under a tilted gravity (examples/u_tube) that script 2 turns upright is no
  // mismatch; a tilted fix left in place, or one script 2 defines, is.
  set_up_script("fix gravity all gravity 9.81 vector 0.0871 -0.9962 0.0\n");
  std::ofstream(folder_ / "after.in")
      << "unfix gravity\nfix gravity all gravity 9.81 vector 0 -1 0\n";
  EXPECT_TRUE(of(physics_checks(build(kGoodSph, kGoodFluid)), "gravity").empty());
  std::ofstream(folder_ / "after.in") << "fix gravity all gravity 9.81 vector 0 -1 0  # replaces\n";
  EXPECT_TRUE(of(physics_checks(build(kGoodSph, kGoodFluid)), "gravity").empty());
  std::ofstream(folder_ / "after.in") << "# gravity stays tilted\n";
  std::vector<Diagnostic> found = of(physics_checks(build(kGoodSph, kGoodFluid)), "gravity");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_CONTAINS(found[0].location.text(), "setup.in:1:1");
  EXPECT_CONTAINS(found[0].message, "in the coupled run");
  std::ofstream(folder_ / "after.in")
      << "unfix gravity\n\nfix tilt all gravity 9.81 vector 1 -1 0\n";
  found = of(physics_checks(build(kGoodSph, kGoodFluid)), "gravity");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_CONTAINS(found[0].location.text(), "after.in:3:1");
  EXPECT_CONTAINS(found[0].message, "fix tilt gives the fluid g = (6.94, -6.94, 0) m/s^2");
}

TEST_F(SmallScene, AFluidWithoutGravityUnderAFallingStructureIsFlagged) {
  set_up_script("# no gravity for the fluid\n");
  const std::vector<Diagnostic> found = of(physics_checks(build(kGoodSph, kGoodFluid)), "gravity");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_CONTAINS(found[0].message, "neither LIGGGHTS script has a 'fix ... gravity'");
  EXPECT_CONTAINS(found[0].fix, "fix gravity all gravity 9.81 vector X Y 0");
}

TEST_F(SmallScene, ASceneWithoutFluidIsNotAskedForFluidGravity) {
  // --mbd-only scenes name two placeholder scripts and no FluidRegion.
  set_up_script("# placeholder: no LIGGGHTS here\n");
  std::ofstream(folder_ / "after.in") << "# placeholder\n";
  const std::vector<Diagnostic> diagnostics = physics_checks(build(kGoodSph, ""));
  EXPECT_TRUE(of(diagnostics, "gravity").empty()) << listing(diagnostics);
  ASSERT_EQ(of(diagnostics, "gravity", Severity::Info).size(), 1u) << listing(diagnostics);
  EXPECT_CONTAINS(of(diagnostics, "gravity", Severity::Info)[0].message, "a scene without fluid");
}

TEST_F(SmallScene, AGravityTheCheckCannotReadIsSaid) {
  set_up_script("variable g equal 9.81\nfix gravity all gravity v_g vector 0 -1 0\n");
  const std::vector<Diagnostic> diagnostics = physics_checks(build(kGoodSph, kGoodFluid));
  EXPECT_TRUE(of(diagnostics, "gravity").empty()) << listing(diagnostics);
  const std::vector<Diagnostic> found = of(diagnostics, "gravity", Severity::Info);
  ASSERT_EQ(found.size(), 1u) << listing(diagnostics);
  EXPECT_CONTAINS(found[0].message, "setup.in:2:1");
}

TEST_F(SmallScene, WallValuesAreReadFromTheFixLineTheScriptRuns) {
  // LIGGGHTS_SPH_parameters say k = 2000 (within 2-20 rho0 g h_max), but the fix line the client
  // runs says 200000: the check must judge the value that is used, at the script line.
  set_up_script(
      "fix gravity all gravity 9.81 vector 0.0 -1.0 0.0\n"
      "fix fsi all fsi/sph k 200000 t ${SPH_wall_visc} &\n"
      "    r0 ${SPH_wall_equilibriumdist} cutoff ${SPH_wall_cutoff}\n");
  const std::vector<Diagnostic> diagnostics = physics_checks(build(kGoodSph, kGoodFluid));
  const std::vector<Diagnostic> found = of(diagnostics, "wall_repulsion");
  ASSERT_EQ(found.size(), 1u) << listing(diagnostics);
  EXPECT_EQ(found[0].location.text(), "setup.in:2:1");  // the script as the scene names it
  EXPECT_CONTAINS(found[0].message, "k = 200000 N/m^2");
  // A value given as ${name} alone is located at that parameter, where the user changes it.
  const std::vector<Diagnostic> viscosity =
      of(physics_checks(
             build("smoothinglength = 0.001; cAB = 20; viscosity = 1e-3\n"
                   "SPH_wall_rep = 2000; SPH_wall_visc = 50; SPH_wall_equilibriumdist = 0.002\n"
                   "SPH_wall_cutoff = 0.002",
                   kGoodFluid)),
         "wall_viscosity");
  ASSERT_EQ(viscosity.size(), 1u);
  EXPECT_EQ(viscosity[0].location.file, (folder_ / "small.scene").string());
}

TEST_F(SmallScene, AFixValueTheChecksCannotReadSkipsThemWithTheReason) {
  set_up_script(
      "fix gravity all gravity 9.81 vector 0.0 -1.0 0.0\n"
      "fix fsi all fsi/sph k v_k t 1000 r0 0.002 cutoff 0.002\n");
  const std::vector<Diagnostic> found =
      of(physics_checks(build(kGoodSph, kGoodFluid)), "wall_repulsion", Severity::Info);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_CONTAINS(
      found[0].message,
      "fix fsi/sph k 'v_k' at setup.in:2:1 is not a number or a LIGGGHTS_SPH_parameters value");
}

// The checks read the fix line with the parser fsi-client uses (fsi::contact): a line the fix
// refuses is judged as refused, not as a set of numbers that look right.
TEST_F(SmallScene, AFixLineTheFixRefusesIsNotJudged) {
  set_up_script(
      "fix gravity all gravity 9.81 vector 0.0 -1.0 0.0\n"
      "fix fsi all fsi/sph k 200000 t 1000 r0 0.002 cutoff 0.002 speed 3\n");
  const std::vector<Diagnostic> diagnostics = physics_checks(build(kGoodSph, kGoodFluid));
  EXPECT_TRUE(of(diagnostics, "wall_repulsion").empty()) << listing(diagnostics);
  const std::vector<Diagnostic> found = of(diagnostics, "wall_repulsion", Severity::Info);
  ASSERT_EQ(found.size(), 1u) << listing(diagnostics);
  EXPECT_CONTAINS(found[0].message,
                  "fix fsi/sph at setup.in:2:1 is refused: unknown keyword 'speed': wall-repulsion "
                  "check skipped");
}

TEST_F(SmallScene, AnUndefinedScriptVariableIsNamedAtItsLine) {
  set_up_script(std::string(kSetUp) +
                "variable skin equal 0.25*${smoothinglength}\n"
                "neighbor ${skin} bin   # defined just above\n"
                "pair_style sph/artVisc/tensCorr spiky2d ${smoothing_length} artVisc\n"
                "region r block 0 1 0 1 0 1 units box # ${in_a_comment} is not read\n");
  std::ofstream(folder_ / "after.in")
      << "fix m3 all property/global artViscAlpha peratomtype ${alpha}\n";
  const std::vector<Diagnostic> found =
      of(physics_checks(build(kGoodSph, kGoodFluid)), "liggghts_scripts");
  ASSERT_EQ(found.size(), 2u) << listing(found);
  EXPECT_EQ(found[0].location.text(), "setup.in:7:1");
  EXPECT_CONTAINS(found[0].message, "LIGGGHTS variable 'smoothing_length' is not defined");
  EXPECT_CONTAINS(found[0].fix, "add 'smoothing_length = ...' to LIGGGHTS_SPH_parameters");
  EXPECT_EQ(found[1].location.text(), "after.in:1:1");
  EXPECT_CONTAINS(found[1].message, "'alpha'");
}

TEST_F(SmallScene, AScriptWithoutTheCouplingFixIsNamed) {
  set_up_script("fix gravity all gravity 9.81 vector 0.0 -1.0 0.0\n");
  // In script 2 it comes too late: fsi-client needs it before the equilibration.
  std::ofstream(folder_ / "after.in")
      << "fix fsi all fsi/sph k 2000 t 1000 r0 0.002 cutoff 0.002\n";
  const std::vector<Diagnostic> found =
      of(physics_checks(build(kGoodSph, kGoodFluid)), "liggghts_scripts");
  ASSERT_EQ(found.size(), 1u) << listing(found);
  EXPECT_EQ(found[0].location.text(), "setup.in:1:1");
  EXPECT_CONTAINS(found[0].message, "script 1 has no 'fix ID group fsi/sph ...'");
}

TEST_F(SmallScene, ScriptsWithIncludeAreNotFollowedAndSaySo) {
  set_up_script(std::string(kSetUp) + "include more.in\nneighbor ${skin} bin\n");
  const std::vector<Diagnostic> diagnostics = physics_checks(build(kGoodSph, kGoodFluid));
  EXPECT_TRUE(of(diagnostics, "liggghts_scripts").empty()) << listing(diagnostics);
  const std::vector<Diagnostic> found = of(diagnostics, "liggghts_scripts", Severity::Info);
  ASSERT_EQ(found.size(), 1u) << listing(diagnostics);
  EXPECT_CONTAINS(found[0].message, "(setup.in:5:1), which the check does not follow");
}

TEST_F(SmallScene, SpeedOfSoundIsCabOrUnknown) {
  EXPECT_EQ(speed_of_sound(build(kGoodSph, kGoodFluid)), 20.0);
  EXPECT_EQ(speed_of_sound(build_scene(kCoarseTank, {{"LIGGGHTS_SPH_parameters.cAB", "35"}})),
            35.0);
  EXPECT_FALSE(speed_of_sound(build("smoothinglength = 0.001", kGoodFluid)).has_value());
  EXPECT_FALSE(speed_of_sound(build("cAB = -3", kGoodFluid)).has_value());
}

}  // namespace
}  // namespace fsi::scene

namespace fsi::scene {
namespace {

// A DampingZone acts on the fluid in its box: one that starts dry absorbs nothing there, one over
// a moving body takes part of the body's fluid force. The small scene's fluid box spans
// x = 0.01..0.09; a body 6 mm wide at x = 0.05; d = 0.526 mm, so 2 d = 1.05 mm.
TEST_F(SmallScene, DampingZonesThatStartDryOrReachABodyAreWarned) {
  const std::string body =
      "RigidBody2D { name = \"float\"; mass = 0.01; inertia = 1e-6; position = [0.05, 0.01]\n"
      "  Mesh { points = [[-0.003, -0.003], [0.003, -0.003], [0.003, 0.003], [-0.003, 0.003], "
      "[-0.003, -0.003]] } }\n";
  // One long segment through the third zone: its ends and its middle lie outside it.
  const std::string plate =
      "RigidBody2D { name = \"plate\"; mass = 0.01; inertia = 1e-6; position = [0.35, 0.02]\n"
      "  Mesh { points = [[-0.2, 0], [0.2, 0]] } }\n";
  auto zone = [](const std::string& lower, const std::string& upper) {
    return "DampingZone { lower = " + lower + "; upper = " + upper +
           "; rate = 10; grows_toward = \"x+\" }\n";
  };
  const Scene scene =
      build(kGoodSph, kGoodFluid + "\n" + body + plate + zone("[0.06, 0]", "[0.1, 0.03]") +
                          zone("[0.0535, 0]", "[0.1, 0.03]") + zone("[0.2, 0]", "[0.3, 0.03]"));
  ASSERT_EQ(scene.damping_zones.size(), 3u);
  const std::vector<Diagnostic> found = of(physics_checks(scene), "damping_zones");
  ASSERT_EQ(found.size(), 3u) << listing(found);
  // Where the float's bottom edge enters the zone grown by 2 d (d = 0.001/1.9 m).
  EXPECT_CONTAINS(found[0].message,
                  "this DampingZone reaches the mesh of body 'float' (at (0.0524, 0.007)");
  EXPECT_EQ(found[0].location.line, scene.damping_zones[1].location.line);
  EXPECT_CONTAINS(found[1].message, "no particle of the FluidRegions starts in this DampingZone");
  EXPECT_EQ(found[1].location.line, scene.damping_zones[2].location.line);
  EXPECT_CONTAINS(found[2].message,
                  "this DampingZone reaches the mesh of body 'plate' (at (0.199, 0.02)");
  EXPECT_EQ(found[2].location.line, scene.damping_zones[2].location.line);
}

// A PistonWavemaker's wave is noted with its height in particle spacings (SPH damps a wave the
// more the fewer span it); the wave flume's sponge stands over water and away from the paddle.
TEST(PhysicsChecks, TheWaveHeightInSpacingsIsNoted) {
  const std::string flume = FSI_EXAMPLES_DIR "/wave_flume/wave_flume.scene";
  const auto notes = [&](const std::vector<Override>& overrides) {
    return of(physics_checks(build_scene(flume, overrides)), "wave_resolution", Severity::Info);
  };
  const std::vector<Diagnostic> coarse = notes({});
  ASSERT_EQ(coarse.size(), 1u) << listing(coarse);
  EXPECT_CONTAINS(coarse[0].message, "the wave is H/d = 2.47 particle spacings high");
  EXPECT_CONTAINS(coarse[0].message, "a structure 2.39 m (a wavelength) down the flume");
  EXPECT_CONTAINS(coarse[0].location.text(), "piston_paddle.inc:");
  const std::vector<Diagnostic> fine = notes({{"Resolution.spacing", "0.0125"}});
  ASSERT_EQ(fine.size(), 1u) << listing(fine);
  EXPECT_CONTAINS(fine[0].message, "H/d = 4.94");
  EXPECT_TRUE(of(physics_checks(build_scene(flume, {})), "damping_zones").empty());
}

const std::string kTrueShapeBlock = FSI_EXAMPLES_DIR "/immersed_block/immersed_block_coarse.scene";
const std::string kTrueShapeTank =
    FSI_EXAMPLES_DIR "/static_tank/static_tank_true_shape_coarse.scene";

TEST(PhysicsChecks, TrueShapeExamplesPassEveryCheck) {
  for (const std::string& path : {kTrueShapeBlock, kTrueShapeTank}) {
    const std::vector<Diagnostic> diagnostics = physics_checks(build_scene(path, {}));
    EXPECT_TRUE(of(diagnostics, "wall_repulsion").empty()) << path << listing(diagnostics);
    EXPECT_TRUE(of(diagnostics, "contact_time_step").empty()) << path << listing(diagnostics);
    EXPECT_TRUE(of(diagnostics, "fluid_overlap").empty()) << path << listing(diagnostics);
    // The derived k, r0 and cutoff are read: no check is skipped for want of them.
    EXPECT_TRUE(of(diagnostics, "contact_time_step", Severity::Info).empty())
        << listing(diagnostics);
  }
}

// A wall off the lattice's cell edges leaves a gap the water falls into during the settling (a
// user's flap 0.9 d off its first columns: troughs either side, 2026-12-06, said nowhere): a
// note names it. The block's bottom at y = 0.025 m lies half a spacing (d = 2 mm) off the cell
// edges, so the row below stands 1 d off; at 0.024 m it is on one.
TEST(PhysicsChecks, ATrueShapeWallOffTheLatticeIsNoted) {
  const auto notes = [](const std::vector<Override>& overrides) {
    return of(physics_checks(build_scene(kTrueShapeBlock, overrides)), "fluid_overlap",
              Severity::Info);
  };
  const std::vector<Diagnostic> off = notes({});
  ASSERT_EQ(off.size(), 1u) << listing(off);
  EXPECT_CONTAINS(off[0].message, "the water starts 1 d from the mesh of body 'block' at");
  EXPECT_CONTAINS(off[0].message, "the gap of 0.001 m fills during the settling");
  EXPECT_TRUE(notes({{"Geometry.centre_depth", "0.036"}}).empty())
      << listing(notes({{"Geometry.centre_depth", "0.036"}}));
  // The block turned by 45 degrees meets the lattice at every distance: not noted.
  EXPECT_TRUE(notes({{"RigidBody2D.angle", "pi/4"}}).empty())
      << listing(notes({{"RigidBody2D.angle", "pi/4"}}));
}

TEST(PhysicsChecks, TheTrueShapeReferencePressureIsReadForTheHealthAdvice) {
  // The fix's `pressure ${SPH_wall_pressure}`, expanded; the thesis' law has none.
  const std::optional<double> pressure = true_shape_pressure(
      build_scene(kTrueShapeBlock, {{"LIGGGHTS_SPH_parameters.SPH_wall_pressure", "1234"}}));
  ASSERT_TRUE(pressure);
  EXPECT_DOUBLE_EQ(*pressure, 1234.0);
  EXPECT_FALSE(wall_cutoff(build_scene(kTrueShapeBlock, {})));
  const Scene thesis_law =
      build_scene(FSI_EXAMPLES_DIR "/static_tank/static_tank_coarse.scene", {});
  EXPECT_FALSE(true_shape_pressure(thesis_law));
  EXPECT_TRUE(wall_cutoff(thesis_law));
}

TEST(PhysicsChecks, TrueShapeReferencePressureAboveTheColumnIsNamed) {
  // rho0 g H = 1000 * 9.81 * 0.07 = 687 Pa: a reference of 5000 Pa is 7.3 rho0 g H.
  const std::vector<Diagnostic> found =
      of(physics_checks(
             build_scene(kTrueShapeBlock, {{"LIGGGHTS_SPH_parameters.SPH_wall_pressure", "5000"}})),
         "wall_repulsion");
  ASSERT_EQ(found.size(), 1u) << listing(found);
  EXPECT_CONTAINS(found[0].message, "reference pressure 5000 Pa is 7.28 rho0 g H");
  EXPECT_CONTAINS(found[0].message, "the first particle layer rests at");
  EXPECT_CONTAINS(found[0].location.text(), "immersed_block.in1:");
  EXPECT_CONTAINS(found[0].fix, "rho0 g H / 2 = 343 Pa");
}

TEST(PhysicsChecks, TrueShapeParticlesStartingInsideABodyAreNamed) {
  // A hole 2 mm smaller than the block all round: the lattice reaches into the block.
  const std::vector<Diagnostic> found =
      of(physics_checks(build_scene(kTrueShapeBlock, {{"Geometry.side", "0.024"},
                                                      {"FluidRegion.Hole[0].points",
                                                       "[[0.02, 0.027], [0.04, 0.027], [0.04, "
                                                       "0.043], [0.02, 0.043]]"}})),
         "fluid_overlap");
  ASSERT_FALSE(found.empty());
  EXPECT_CONTAINS(found[0].message, "d from the mesh of body 'block'");
  EXPECT_CONTAINS(found[0].fix, "along the water's true outline");
}

// A rounded corner drawn with the same radius in the walls and the water (docs/user-guide.md,
// "Rounded corners"): the lattice meets the arcs at every distance (a particle 0.16 d from one
// here), and those particles start in the water, not in the wall. With the water's corners
// rounded by half the walls' radius the water reaches past the walls' arcs, into the wall.
TEST(PhysicsChecks, ParticlesBesideAWallTheWaterFollowsStartInTheWater) {
  const std::string tank = FSI_EXAMPLES_DIR "/wave_flume/corner_tank_rounded.scene";
  const std::vector<Diagnostic> followed =
      of(physics_checks(build_scene(tank, {})), "fluid_overlap");
  EXPECT_TRUE(followed.empty()) << listing(followed);
  const std::vector<Diagnostic> past = of(
      physics_checks(build_scene(
          tank, {{"FluidRegion.points", "[[0, 0, 0.05], [0.5, 0, 0.05], [0.5, 0.4], [0, 0.4]]"}})),
      "fluid_overlap");
  ASSERT_EQ(past.size(), 1u) << listing(past);
  EXPECT_CONTAINS(past[0].message, "d from the mesh of the ground");
  EXPECT_CONTAINS(past[0].message, "it starts inside the structure or its wall");
}

TEST(PhysicsChecks, TrueShapeContactTimeStepUsesTheStiffnessAtRest) {
  const std::vector<Diagnostic> found =
      of(physics_checks(build_scene(kTrueShapeBlock, {{"SolverOptions.Timeint.step_size", "2e-4"},
                                                      {"SolverOptions.end_time", "0.4"}})),
         "contact_time_step");
  ASSERT_EQ(found.size(), 1u) << listing(found);
  EXPECT_CONTAINS(found[0].message, "of the true-shape wall at the first layer's rest distance");
}

// --- viscosity_match: the wall's t against the fluid's alpha (docs/theory.md, "Viscosity") ---

const std::string kChannel = FSI_EXAMPLES_DIR "/channel_flows/poiseuille_coarse.scene";

// The channel example sets both from nu: t = rho0 nu / r_v and alpha = 16 nu / (c h).
TEST(ViscosityMatch, TheChannelFlowsWallAndFluidAgree) {
  const auto diagnostics = physics_checks(build_scene(kChannel));
  EXPECT_TRUE(of(diagnostics, "viscosity_match").empty()) << listing(diagnostics);
  EXPECT_TRUE(of(diagnostics, "viscosity_match", Severity::Info).empty()) << listing(diagnostics);
}

// The thesis' t = rho0 nu / h with the user guide's old nu = alpha c h / 8 (issue 13): the wall
// holds a fluid 4x as viscous as the fluid is.
TEST(ViscosityMatch, TheOldMappingsAreFlaggedWithBothValues) {
  const auto diagnostics = physics_checks(build_scene(
      kChannel, {{"LIGGGHTS_SPH_parameters.SPH_wall_visc", "SPHdensity*viscosity/smoothinglength"},
                 {"LIGGGHTS_SPH_parameters.artvisc_alpha", "8*viscosity/(cAB*smoothinglength)"}}));
  const auto found = of(diagnostics, "viscosity_match");
  ASSERT_EQ(found.size(), 1u) << listing(diagnostics);
  // t = 1e-3/9.5e-5 = 10.5; nu_wall = t 2h / rho0 = 2e-6; alpha = 0.842 -> nu = 5e-7.
  EXPECT_CONTAINS(found[0].message,
                  "the wall friction t = 10.5 N s/m^3 holds without slip a fluid "
                  "of nu = t r_v / rho0 = 2e-06 m^2/s");
  EXPECT_CONTAINS(found[0].message,
                  "alpha = 0.842 (channel.in1:24:1) gives nu = alpha c h / 16 = "
                  "5e-07 m^2/s (c = 0.1 m/s, h = 9.5e-05 m): 4x");
  EXPECT_CONTAINS(found[0].location.text(), "channel.in1:33:1");  // the fix fsi/sph line
  EXPECT_EQ(found[0].fix,
            "set t = 2.63 (rho0 nu / r_v) for this fluid, or alpha = 3.37 for the "
            "fluid this wall holds");
}

// How many viscosity_match diagnostics of a severity the channel example gets with wall friction t.
std::size_t viscosity_match_count(const std::string& t, Severity severity) {
  return of(physics_checks(build_scene(kChannel, {{"LIGGGHTS_SPH_parameters.SPH_wall_visc", t}})),
            "viscosity_match", severity)
      .size();
}

// A factor 2 either way passes; beyond it a sticky wall warns and a slipping one informs.
TEST(ViscosityMatch, FactorTwoIsTheLimit) {
  const std::string rule = "SPHdensity*viscosity/SPH_wall_cutoff_visc";
  for (const Severity severity : {Severity::Warning, Severity::Info}) {
    EXPECT_EQ(viscosity_match_count("1.9*" + rule, severity), 0u);
    EXPECT_EQ(viscosity_match_count(rule + "/1.9", severity), 0u);
  }
  EXPECT_EQ(viscosity_match_count("2.1*" + rule, Severity::Warning), 1u);
  EXPECT_EQ(viscosity_match_count("2.1*" + rule, Severity::Info), 0u);
  EXPECT_EQ(viscosity_match_count(rule + "/2.1", Severity::Warning), 0u);
  EXPECT_EQ(viscosity_match_count(rule + "/2.1", Severity::Info), 1u);
}

// The moment rule t = 6 rho0 nu d^2 / r_v^3 (2D; 0.42 rho0 nu / r_v at h = 1.9 d) is the other
// no-slip wall for the fluid (docs/theory.md, "Viscosity"; examples/cylinder uses it): matched,
// not reported as slipping; 10 % below it is a wall that slips again.
TEST(ViscosityMatch, TheMomentRuleIsANoSlipWall) {
  const std::string moment = "6*SPHdensity*viscosity*particlespacing^2/SPH_wall_cutoff_visc^3";
  EXPECT_EQ(viscosity_match_count(moment, Severity::Info), 0u);
  EXPECT_EQ(viscosity_match_count(moment, Severity::Warning), 0u);
  EXPECT_EQ(viscosity_match_count("0.9*" + moment, Severity::Info), 1u);
  EXPECT_EQ(viscosity_match_count("1.1*" + moment, Severity::Info), 1u);
}

// The equal-style variables of the scripts are evaluated as LIGGGHTS would (v_name, ${name},
// arithmetic), and the last artViscAlpha in force counts (script 2 replaces script 1's).
TEST_F(SmallScene, ViscosityMatchReadsTheScriptsVariables) {
  set_up_script(kSetUp +
                "variable nu_fluid equal 5e-3\n"
                "variable a equal 16*v_nu_fluid/(${cAB}*0.001)\n");
  std::ofstream(folder_ / "after.in")
      << kAfter << "fix m3 all property/global artViscAlpha peratomtype ${a}\n";
  const auto diagnostics = physics_checks(build(kGoodSph, kGoodFluid));
  EXPECT_TRUE(of(diagnostics, "viscosity_match").empty()) << listing(diagnostics);
  const auto found = of(diagnostics, "viscosity_match", Severity::Info);  // the wall slips
  ASSERT_EQ(found.size(), 1u);
  EXPECT_CONTAINS(found[0].message,
                  "alpha = 4 (after.in:6:1) gives nu = alpha c h / 16 = "
                  "0.005 m^2/s");
  EXPECT_CONTAINS(found[0].message, "0.4x");
  EXPECT_CONTAINS(found[0].message, "the wall slips, fine where alpha is numerical damping");
}

}  // namespace
}  // namespace fsi::scene
