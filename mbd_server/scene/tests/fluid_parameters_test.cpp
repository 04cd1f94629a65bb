// The Fluid block (docs/user-guide.md, "The Fluid block"): the rules of
// fsi/scene/fluid_parameters.hpp on known inputs, a value the user sets winning over its rule (and
// feeding the rules after it), the values reaching the LIGGGHTS variables under the examples'
// names, and each bad input's problem at its scene line.
#include "fsi/scene/fluid_parameters.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/scene/physics_checks.hpp"
#include "fsi/scene/scene.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

// Water 0.1 m deep at d = 2 mm under |g| = 9.81.
FluidValues tank() {
  return {
      {"density", 1000.0}, {"spacing", 0.002}, {"viscosity", 1e-6}, {"height", 0.1}, {"g", 9.81}};
}

const FluidValue& of(const FluidDerivation& derivation, std::string_view symbol) {
  for (const FluidValue& value : derivation.values) {
    if (value.quantity->symbol == symbol) return value;
  }
  ADD_FAILURE() << "no " << symbol;
  return derivation.values.front();
}

TEST(FluidRules, KnownInputsGiveKnownValues2D) {
  const FluidDerivation fluid = derive_fluid(tank(), 2);
  EXPECT_DOUBLE_EQ(fluid.value("h"), 0.0038);                     // 1.9 d
  EXPECT_DOUBLE_EQ(fluid.value("m"), 4e-3);                       // rho0 d^2
  EXPECT_DOUBLE_EQ(fluid.value("z_half"), 0.0019);                // h/2
  EXPECT_NEAR(fluid.value("c"), 10.0 * std::sqrt(1.962), 1e-12);  // 10 sqrt(2 g H) = 14.007
  EXPECT_DOUBLE_EQ(fluid.value("alpha"), 0.02);
  EXPECT_DOUBLE_EQ(fluid.value("alpha_eq"), 0.5);
  EXPECT_DOUBLE_EQ(fluid.value("p_ref"), 490.5);                 // rho0 g H / 2
  EXPECT_DOUBLE_EQ(fluid.value("r_v"), 0.0076);                  // 2h
  EXPECT_NEAR(fluid.value("t"), 1000.0 * 1e-6 / 0.0076, 1e-15);  // rho0 nu / r_v
  EXPECT_DOUBLE_EQ(fluid.value("r_c"), 0.0076);                  // 2h
  EXPECT_DOUBLE_EQ(fluid.value("r0"), 0.0076);                   // r_c
  EXPECT_DOUBLE_EQ(fluid.value("k"), 9810.0);                    // 10 rho0 g H
  EXPECT_DOUBLE_EQ(fluid.value("U"), 0.0);                       // its default
  for (const FluidValue& value : fluid.values)
    EXPECT_FALSE(value.given && !value.quantity->is_input());
}

TEST(FluidRules, ThreeDimensionsTakeTheirKernelRatioAndMass) {
  const FluidDerivation fluid = derive_fluid(tank(), 3);
  EXPECT_DOUBLE_EQ(fluid.value("h"), 1.2 * 0.002);
  EXPECT_DOUBLE_EQ(fluid.value("m"), 1000.0 * 8e-9);
}

TEST(FluidRules, AFasterFlowThanFreeFallSetsTheSpeedOfSound) {
  FluidValues given = tank();
  given["speed"] = 3.0;  // above sqrt(2 g H) = 1.4 m/s
  EXPECT_DOUBLE_EQ(derive_fluid(given, 2).value("c"), 30.0);
}

TEST(FluidRules, AValueTheUserSetsWinsAndFeedsTheRulesAfterIt) {
  FluidValues given = tank();
  given["smoothing_length"] = 0.004;
  given["speed_of_sound"] = 20.0;
  const FluidDerivation fluid = derive_fluid(given, 2);
  EXPECT_DOUBLE_EQ(fluid.value("h"), 0.004);
  EXPECT_TRUE(of(fluid, "h").given);
  EXPECT_DOUBLE_EQ(*of(fluid, "h").by_rule, 0.0038);  // what the rule would have given
  EXPECT_DOUBLE_EQ(fluid.value("c"), 20.0);
  EXPECT_DOUBLE_EQ(fluid.value("r_v"), 0.008);       // 2h of the user's h
  EXPECT_DOUBLE_EQ(fluid.value("t"), 1e-3 / 0.008);  // rho0 nu / r_v of that r_v
  EXPECT_CONTAINS(explain(fluid, of(fluid, "c")),
                  "c (${cAB}) = 20 m/s: set by Fluid.speed_of_sound, which wins over the rule 10 "
                  "max(sqrt(2 g H), U) = 14.01 m/s");
}

TEST(FluidRules, EachDerivedValueIsExplainedWithItsRuleAndInputs) {
  // Units for the scene's dimension: a user's 3D log read "m = 0.125 kg/m (3D: kg)".
  const FluidDerivation spatial = derive_fluid(tank(), 3);
  EXPECT_CONTAINS(explain(spatial, of(spatial, "m")), " kg: rho0 d^2 (3D: rho0 d^3)");
  EXPECT_CONTAINS(explain(spatial, of(spatial, "t")), " N s/m^4: rho0 nu / r_v");
  const FluidDerivation fluid = derive_fluid(tank(), 2);
  EXPECT_CONTAINS(explain(fluid, of(fluid, "m")), " kg/m: rho0 d^2 (3D: rho0 d^3)");
  EXPECT_CONTAINS(explain(fluid, of(fluid, "c")),
                  "c (${cAB}) = 14.01 m/s: 10 max(sqrt(2 g H), U) with g = 9.81 m/s^2, H = 0.1 "
                  "m, U = 0 m/s (thesis §6.2");
  EXPECT_CONTAINS(explain(fluid, of(fluid, "t")),
                  "t (${SPH_wall_visc}) = 0.1316 N s/m^3: rho0 nu / r_v (rule "
                  "\"thesis\", the default) with rho0 = 1000 kg/m^3, nu = 1e-06 m^2/s, r_v = "
                  "0.0076 m");
  EXPECT_CONTAINS(explain(fluid, of(fluid, "g")), "g (${gravity}) = 9.81 m/s^2: from the Gravity");
  EXPECT_CONTAINS(explain(fluid, of(fluid, "d")), "d (${particlespacing}) = 0.002 m: given");
}

// The wall friction has two rules (docs/theory.md, "Viscosity"): the thesis' rho0 nu / r_v by
// default, the moment rule by name. Water 0.1 m deep, nu = 1e-3 (the cylinder's fluid).
TEST(FluidRules, TheMomentRuleIsChosenByNameAndExplained) {
  FluidValues given = tank();
  given["viscosity"] = 1e-3;
  const FluidDerivation thesis = derive_fluid(given, 2);
  EXPECT_EQ(of(thesis, "t").rule->name, "thesis");
  EXPECT_DOUBLE_EQ(thesis.value("t"), 1000.0 * 1e-3 / 0.0076);
  const FluidDerivation moment = derive_fluid(given, 2, {{"wall_friction", "moment"}});
  EXPECT_EQ(of(moment, "t").rule->name, "moment");
  // 2D: t = 6 rho0 nu d^2 / r_v^3, r_v = 2h = 3.8 d: 6 / 3.8^3 = 0.1094 of rho0 nu / d.
  EXPECT_NEAR(moment.value("t"), 6.0 * 1000.0 * 1e-3 * 0.002 * 0.002 / std::pow(0.0076, 3), 1e-12);
  EXPECT_NEAR(moment.value("t") / thesis.value("t"), 6.0 / (3.8 * 3.8), 1e-12);
  // 3D: t = 20 rho0 nu d^3 / (pi r_v^4), r_v = 2.4 d.
  const FluidDerivation moment3 = derive_fluid(given, 3, {{"wall_friction", "moment"}});
  EXPECT_NEAR(moment3.value("t"),
              20.0 * 1000.0 * 1e-3 * std::pow(0.002, 3) / (std::numbers::pi * std::pow(0.0048, 4)),
              1e-12);
  // The values before it and after it do not change.
  EXPECT_DOUBLE_EQ(moment.value("r_v"), thesis.value("r_v"));
  EXPECT_DOUBLE_EQ(moment.value("k"), thesis.value("k"));
  EXPECT_CONTAINS(explain(moment, of(moment, "t")),
                  "t (${SPH_wall_visc}) = 54.67 N s/m^3: 6 rho0 nu d^2 / r_v^3 (3D: "
                  "20 rho0 nu d^3 / (pi r_v^4)) (rule \"moment\", Fluid.wall_friction_rule) with "
                  "rho0 = 1000 kg/m^3, nu = 0.001 m^2/s, d = 0.002 m, r_v = 0.0076 m");
  EXPECT_CONTAINS(explain(thesis, of(thesis, "t")), "rho0 nu / r_v (rule \"thesis\", the default)");
  // The markdown table lists both, the default first.
  EXPECT_CONTAINS(fluid_rules_markdown(),
                  "`wall_friction_rule = \"thesis\"` (default): rho0 nu / r_v; "
                  "`wall_friction_rule = \"moment\"`: 6 rho0 nu d^2 / r_v^3");
}

// The error derive_fluid throws for these values and choices (a failure when it throws none).
Error refusal(const FluidValues& given, const FluidRuleChoices& choices) {
  try {
    derive_fluid(given, 2, choices);
  } catch (const Error& error) {
    return error;
  }
  ADD_FAILURE() << "accepted";
  return Error("");
}

TEST(FluidRules, AnUnknownRuleOrARuleForAGivenValueIsRefused) {
  const Error unknown = refusal(tank(), {{"wall_friction", "momnet"}});
  EXPECT_EQ(unknown.location(), "wall_friction_rule");
  EXPECT_CONTAINS(unknown.fault(), "no rule \"momnet\" for wall_friction");
  EXPECT_CONTAINS(unknown.remedy(), "choose one of \"thesis\", \"moment\"");
  FluidValues given = tank();
  given["wall_friction"] = 0.5;
  const Error both = refusal(given, {{"wall_friction", "moment"}});
  EXPECT_EQ(both.location(), "wall_friction_rule");
  EXPECT_CONTAINS(both.fault(), "wall_friction is given and its rule is chosen too");
  EXPECT_CONTAINS(both.remedy(), "remove wall_friction_rule to keep the given value");
  const Error single = refusal(tank(), {{"smoothing_length", "thesis"}});
  EXPECT_EQ(single.location(), "smoothing_length_rule");
  EXPECT_CONTAINS(single.fault(), "has one rule");
}

TEST(FluidRules, TheTimeStepIsTheLeastOfItsLimits) {
  const FluidDerivation fluid = derive_fluid(tank(), 2);
  // Acoustic 0.125 h / c = 3.39e-5 s; viscous 0.125 h^2 / (alpha c h / 16) = 0.0271 s; body force
  // 0.25 sqrt(h/g) = 4.9e-3 s.
  EXPECT_NEAR(recommended_time_step(fluid), 0.125 * 0.0038 / (10.0 * std::sqrt(1.962)), 1e-15);
  EXPECT_CONTAINS(explain_time_step(fluid, 2e-5), "step_size = 2e-05 s (within)");
  EXPECT_CONTAINS(explain_time_step(fluid, 5e-5), "step_size = 5e-05 s (ABOVE it)");
  FluidValues syrup = tank();
  syrup["viscosity"] = 0.01;      // viscous limit 0.125 h^2 / nu = 1.8e-4 s: still above acoustic
  syrup["speed_of_sound"] = 1.0;  // acoustic 4.75e-4 s: now the viscous limit is the least
  EXPECT_NEAR(recommended_time_step(derive_fluid(syrup, 2)), 0.125 * 0.0038 * 0.0038 / 0.01, 1e-15);
}

TEST(FluidRules, ALeftOutStepIsTheLargestWithinTheLimitThatDividesTheEndTime) {
  const FluidDerivation fluid = derive_fluid(tank(), 2);
  // The acoustic limit of a step the run chooses is 0.09 h/c (a dam break is stable to 0.092 h/c,
  // docs/validation.md "Stability maps"): 2.4416e-5 s here, below the 0.125 h/c bound.
  const double limit = 0.09 * 0.0038 / (10.0 * std::sqrt(1.962));
  EXPECT_LT(limit, recommended_time_step(fluid));
  // 0.01 s / 2.4416e-5 s = 409.6: 410 steps.
  EXPECT_DOUBLE_EQ(derived_time_step(fluid, 0.01, 1), 0.01 / 410.0);
  EXPECT_LE(derived_time_step(fluid, 0.01, 1), limit);
  // 4 substeps: structure steps of at most 4 limits, 102.4 of them: 103, i.e. 412 fluid steps.
  EXPECT_DOUBLE_EQ(derived_time_step(fluid, 0.01, 4), 0.01 / 412.0);
  // An end time that is a whole number of limits keeps the limit itself.
  EXPECT_NEAR(derived_time_step(fluid, 100.0 * limit, 1), limit, 1e-18);
  // Shorter than one step: one step of end_time.
  EXPECT_DOUBLE_EQ(derived_time_step(fluid, 1e-6, 1), 1e-6);
  EXPECT_CONTAINS(explain_time_step(fluid, 0.01 / 410.0, true, 0.01),
                  "SolverOptions.Timeint.step_size is not given: the run steps at 2.439e-05 s, "
                  "end_time / 410 (the largest step within 0.09 h/c = 2.442e-05 s");
  EXPECT_THROW(derived_time_step(fluid, 0.0, 1), Error);
}

TEST(FluidRules, AMissingInputOrAZeroSpeedOfSoundIsRefusedWithItsFix) {
  FluidValues given = tank();
  given.erase("spacing");
  try {
    derive_fluid(given, 2);
    ADD_FAILURE() << "accepted without a spacing";
  } catch (const Error& error) {
    EXPECT_EQ(error.location(), "spacing");
    EXPECT_CONTAINS(error.fault(), "needs its input 'spacing'");
    EXPECT_CONTAINS(error.remedy(), "add spacing = ... [m] to the Fluid block");
  }
  given = tank();
  given["g"] = 0.0;  // no gravity, no speed: nothing sets c
  try {
    derive_fluid(given, 2);
    ADD_FAILURE() << "accepted c = 0";
  } catch (const Error& error) {
    EXPECT_EQ(error.location(), "speed_of_sound");
    EXPECT_CONTAINS(error.fault(),
                    "speed_of_sound (c) = 0 by its rule 10 max(sqrt(2 g H), U) "
                    "with g = 0, H = 0.1, U = 0: it must be positive");
    EXPECT_CONTAINS(error.remedy(), "set speed_of_sound = ... in the Fluid block");
  }
}

// Scenes with a Fluid block: a tank of water 0.1 m deep on a floor.
class FluidBlock : public testing::FolderPerTest {
 protected:
  std::filesystem::path scene(
      const std::string& fluid, const std::string& more = "",
      const std::string& region = "spacing = Fluid.spacing; density = Fluid.density",
      const std::string& solver =
          "SolverOptions { end_time = 0.01; Timeint { step_size = 2e-5 } }") {
    return write_coupled_scene(
        "f.scene", solver +
                       "\n"
                       "Gravity { acceleration = [0, -9.81] }\n"
                       "Ground { Mesh { points = [[0, 0.2], [0, 0], [0.05, 0], [0.05, 0.2]] } }\n"
                       "Fluid\n{\n" +
                       fluid + "\n}\n" +
                       "FluidRegion { shape = \"box\"; lower = [0, 0]; upper = [0.05, 0.1]; " +
                       region + " }\n" + more);
  }
  static std::string inputs() {
    return "  density = 1000\n  spacing = 0.002\n  viscosity = 1e-6\n  height = 0.1";
  }
  static std::string variable(const Scene& built, const std::string& name) {
    for (const auto& [key, value] : built.liggghts.variables) {
      if (key == name) return value;
    }
    return "(undefined)";
  }
};

TEST_F(FluidBlock, ItsValuesBecomeTheExamplesLiggghtsVariables) {
  const Scene built = build_scene(
      scene(inputs() + "\n  speed_of_sound = 20", "LIGGGHTS_SPH_parameters { xmin = -0.005 }\n")
          .string());
  EXPECT_EQ(variable(built, "SPHdensity"), "1000");
  EXPECT_EQ(variable(built, "particlespacing"), "0.002");
  EXPECT_EQ(variable(built, "smoothinglength"), "0.0038");
  EXPECT_EQ(variable(built, "cAB"), "20");  // the user's
  EXPECT_EQ(variable(built, "gravity"), "9.81");
  EXPECT_EQ(variable(built, "SPH_wall_pressure"), "490.5");
  EXPECT_EQ(variable(built, "SPH_wall_cutoff_visc"), "0.0076");
  EXPECT_EQ(variable(built, "zhalf"), "0.0019");
  EXPECT_EQ(variable(built, "xmin"), "-0.005");  // the block's own entries stay
  ASSERT_TRUE(built.fluid_parameters.has_value());
  // The physics checks find them under the examples' names, at the Fluid block's lines.
  EXPECT_EQ(smoothing_length(built), 0.0038);
  EXPECT_EQ(speed_of_sound(built), 20.0);
  const Parameter* c = sph_parameter(built, "cAB");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->location.line, 11);                                       // speed_of_sound = 20
  EXPECT_EQ(sph_parameter(built, "smoothinglength")->location.line, 5);  // the block: derived
}

TEST_F(FluidBlock, AHydrostaticRegionTakesTheFluidsSpeedOfSound) {
  const Scene built = build_scene(
      scene(inputs(), "", "spacing = Fluid.spacing; density = Fluid.density; hydrostatic = 1")
          .string());
  // Bottom row (y = d/2): rho = rho0 (1 + rho0 g (H - d/2) / B)^(1/7), B = rho0 c^2 / 7.
  const double c = 10.0 * std::sqrt(2.0 * 9.81 * 0.1);
  const double expected =
      1000.0 * std::pow(1.0 + 1000.0 * 9.81 * 0.099 * 7.0 / (1000.0 * c * c), 1.0 / 7.0);
  ASSERT_FALSE(built.fluid.densities.empty());
  EXPECT_NEAR(built.fluid.densities.front(), expected, 1e-9);
}

TEST_F(FluidBlock, AValueGivenTwiceIsAProblemAtTheScriptVariable) {
  const std::string problems = testing::build_error(
      scene(inputs(), "LIGGGHTS_SPH_parameters\n{\n  cAB = 20\n  gravity = 9.81\n}\n"));
  EXPECT_CONTAINS(problems, "f.scene:15:3: 'cAB' is given both here and by the Fluid block at ");
  EXPECT_CONTAINS(problems, "f.scene:5:1 (Fluid.speed_of_sound, c = 10 max(sqrt(2 g H), U))");
  EXPECT_CONTAINS(problems, "write speed_of_sound = ... in the Fluid block");
  EXPECT_CONTAINS(problems, "f.scene:16:3: 'gravity' is given both here");
  EXPECT_CONTAINS(problems, "the Fluid block defines ${gravity} as |g| of the Gravity block");
}

TEST_F(FluidBlock, BadInputsAreProblemsAtTheirLines) {
  EXPECT_CONTAINS(
      testing::build_error(
          scene("  density = -1000\n  spacing = 0.002\n  viscosity = 1e-6\n  height = 0.1", "",
                "spacing = 0.002; density = 1000")),
      "f.scene:7:3: 'Fluid.density' = -1000 kg/m^3 is out of range");  // density, refused by its
                                                                       // declaration (positive)
  const std::string missing =
      testing::build_error(scene("  density = 1000\n  viscosity = 1e-6\n  height = 0.1", "",
                                 "spacing = 0.002; density = 1000"));
  EXPECT_CONTAINS(missing, "f.scene:5:1: required parameter 'Fluid.spacing' is missing");
  EXPECT_CONTAINS(missing, "1 problem(s)");  // reported once
  const std::string different =
      testing::build_error(scene(inputs(), "", "spacing = 0.001; density = Fluid.density"));
  EXPECT_CONTAINS(different,
                  "FluidRegion.spacing = 0.001 differs from the Fluid block's "
                  "spacing = 0.002");
  EXPECT_CONTAINS(different, "write spacing = Fluid.spacing here");
}

TEST_F(FluidBlock, TheWallFrictionRuleIsChosenInTheBlock) {
  const Scene built = build_scene(scene(inputs() + "\n  wall_friction_rule = \"moment\"").string());
  // 6 rho0 nu d^2 / r_v^3 with nu = 1e-6, d = 0.002, r_v = 0.0076: 0.05466 (thesis: 0.1316).
  EXPECT_NEAR(std::stod(variable(built, "SPH_wall_visc")),
              6.0 * 1000.0 * 1e-6 * 4e-6 / std::pow(0.0076, 3), 1e-12);
  const std::string typo =
      testing::build_error(scene(inputs() + "\n  wall_friction_rule = \"momnet\""));
  EXPECT_CONTAINS(typo, "f.scene:11:3: 'Fluid.wall_friction_rule' = \"momnet\" is not one of");
  EXPECT_CONTAINS(typo, "did you mean \"moment\"?");
  const std::string both = testing::build_error(
      scene(inputs() + "\n  wall_friction = 0.1\n  wall_friction_rule = \"moment\""));
  EXPECT_CONTAINS(both, "f.scene:12:3: wall_friction is given and its rule is chosen too");
}

TEST_F(FluidBlock, ASceneWithoutAStepTakesTheLargestItsRulesAllow) {
  const std::string region = "spacing = Fluid.spacing; density = Fluid.density";
  const Scene built = build_scene(scene(inputs(), "", region,
                                        "SolverOptions { end_time = 0.01; Timeint { substeps = 4 } "
                                        "}\nOutput { sensor_every_steps = 4 }")
                                      .string());
  ASSERT_TRUE(built.fluid_parameters.has_value());
  EXPECT_TRUE(built.solver.step_size_derived);
  EXPECT_DOUBLE_EQ(built.solver.step_size, 0.01 / 412.0);  // 103 structure steps of 4
  EXPECT_EQ(built.solver.step_count(), 412u);
  EXPECT_EQ(built.solver.step_size_location.line, 6);  // the Fluid block, after Output
  // Without a Timeint block at all (a user was told to add an empty one): the same rule.
  const Scene bare =
      build_scene(scene(inputs(), "", region, "SolverOptions { end_time = 0.01 }").string());
  EXPECT_TRUE(bare.solver.step_size_derived);
  EXPECT_EQ(bare.solver.stages, 3);
  EXPECT_GT(bare.solver.step_size, 0.0);
  // Given, the scene's step stands, whatever the rule says.
  const Scene given = build_scene(scene(inputs()).string());
  EXPECT_FALSE(given.solver.step_size_derived);
  EXPECT_EQ(given.solver.step_size, 2e-5);
}

// The structure dry (--mbd-only) of a coupled scene that leaves its step out: the coupled run's
// step, so both write their rows at the same times (a Liao trial user had to copy it by hand).
TEST_F(FluidBlock, ADryRunOfASceneWithoutAStepTakesTheCoupledRunsStep) {
  const std::string region = "spacing = Fluid.spacing; density = Fluid.density";
  const std::string solver =
      "SolverOptions { end_time = 0.01; Timeint { substeps = 4 } }\nOutput { sensor_every_steps "
      "= 4 }\nRigidBody2D { name = \"p\"; mass = 1; inertia = 1; position = [0.02, 0.15] }";
  const auto path = scene(inputs(), "", region, solver);
  const Scene coupled = build_scene(path.string());
  const Scene dry = build_scene(path.string(), {}, SceneMode::MbdOnly);
  ASSERT_TRUE(coupled.solver.step_size_derived);
  EXPECT_TRUE(dry.solver.step_size_derived);
  EXPECT_DOUBLE_EQ(dry.solver.step_size, coupled.solver.step_size);
  EXPECT_DOUBLE_EQ(dry.solver.step_size, 0.01 / 412.0);
  EXPECT_FALSE(dry.fluid_parameters.has_value());  // the dry run has no fluid
  EXPECT_CONTAINS(blocks_needed(dry, SceneMode::MbdOnly),
                  "given but not read by an --mbd-only run: Fluid (but for the step it derives)");
  // A Fluid block whose rules fail (here: no gravity and no velocity scale for c) gives no
  // step: the problem says to write one, and where to find the block's own problem.
  const std::string no_rule = mbd_only_outcome(
      "g.scene",
      "scene_language = 1\nSolverOptions { end_time = 0.01 }\n"
      "RigidBody2D { name = \"p\"; mass = 1; inertia = 1; position = [0, 0] }\n"
      "Fluid { density = 1000; spacing = 0.002; viscosity = 1e-6; height = 0.1 }\n");
  EXPECT_CONTAINS(no_rule,
                  "SolverOptions.Timeint.step_size is missing, and the Fluid block "
                  "cannot derive it (check the scene without --mbd-only");
}

TEST_F(FluidBlock, WithoutAFluidBlockALeftOutStepIsAProblem) {
  write("s.in", "# script\n");
  const std::string no_fluid = testing::build_error(
      write("n.scene",
            "scene_language = 1\nSolverOptions { end_time = 0.01; Timeint { stages = 3 } }\n"
            "Gravity { acceleration = [0, -9.81] }\n"
            "Ground { Mesh { points = [[0, 0.2], [0, 0], [0.05, 0]] } }\n"
            "LIGGGHTS { script1 = \"s.in\"; script2 = \"s.in\" }\n"
            "Coupling { refinement_resolution = 0.002 }\n"));
  EXPECT_CONTAINS(no_fluid,
                  "n.scene:2:34: SolverOptions.Timeint.step_size is missing, and there "
                  "is no Fluid block to derive it from");
  EXPECT_CONTAINS(no_fluid, "give the fluid's physical inputs in a Fluid block");
  const std::string mbd_only = mbd_only_outcome(
      "m.scene",
      "scene_language = 1\nSolverOptions { end_time = 0.01; Timeint { stages = 3 } }\n"
      "RigidBody2D { name = \"p\"; mass = 1; inertia = 1; position = [0, 0] }\n");
  EXPECT_CONTAINS(mbd_only,
                  "SolverOptions.Timeint.step_size is missing, and there is no Fluid block to "
                  "derive it from");
}

// examples/hydrostatic_pressure uses the Fluid block: its variables are those of its former
// hand-written LIGGGHTS_SPH_parameters (the values below, coarse: d = 2 mm), except the wall
// friction, which follows the documented no-slip rule rho0 nu / r_v (docs/theory.md,
// "Viscosity"): half the former rho0 nu / h, on water at rest.
TEST(FluidExample, TheHydrostaticTankKeepsItsHandWrittenVariables) {
  const Scene built =
      build_scene(FSI_EXAMPLES_DIR "/hydrostatic_pressure/hydrostatic_pressure_coarse.scene");
  std::map<std::string, double> variables;
  for (const auto& [name, value] : built.liggghts.variables)
    variables[name] = std::stod(value);
  const std::map<std::string, double> by_hand = {{"SPHdensity", 1000.0},
                                                 {"particlespacing", 0.002},
                                                 {"smoothinglength", 1.9 * 0.002},
                                                 {"cAB", 20.0},
                                                 {"viscosity", 1e-3},
                                                 {"highviscosity", 1e-3},
                                                 {"SPHparticlemass", 1000.0 * 0.002 * 0.002},
                                                 {"gravity", 9.81},
                                                 {"rest_drag", 2.0 * M_PI * std::sqrt(9.81 / 0.1)},
                                                 {"xmin", -0.005},
                                                 {"xmax", 0.055},
                                                 {"ymin", -0.005},
                                                 {"ymax", 0.155},
                                                 {"zhalf", 0.5 * 1.9 * 0.002},
                                                 {"SPH_wall_pressure", 0.5 * 1000.0 * 9.81 * 0.1},
                                                 {"SPH_wall_cutoff_visc", 2.0 * 1.9 * 0.002}};
  for (const auto& [name, value] : by_hand) {
    ASSERT_EQ(variables.count(name), 1u) << name;
    EXPECT_NEAR(variables[name], value, 1e-12 * std::abs(value)) << name;
  }
  EXPECT_NEAR(variables["SPH_wall_visc"], 1000.0 * 1e-3 / (2.0 * 1.9 * 0.002), 1e-9);
  EXPECT_NEAR(variables["SPH_wall_visc"] / (1000.0 * 1e-3 / (1.9 * 0.002)), 0.5, 1e-12);
  // The lattice starts at the Tait density of the Fluid block's c (20 m/s, set there).
  EXPECT_EQ(built.fluid.spacing, 0.002);
  ASSERT_FALSE(built.fluid.densities.empty());
  EXPECT_GT(built.fluid.densities.front(), 1000.0);
}

// The user guide's table is the declarations' (regenerate it from the failure message).
TEST(FluidExample, TheUserGuidesTableIsTheDeclarations) {
  std::ifstream in(FSI_EXAMPLES_DIR "/../docs/user-guide.md");
  ASSERT_TRUE(in) << "docs/user-guide.md";
  std::stringstream guide;
  guide << in.rdbuf();
  EXPECT_NE(guide.str().find(fluid_rules_markdown()), std::string::npos)
      << "docs/user-guide.md, \"The Fluid block\", should hold this table:\n"
      << fluid_rules_markdown();
}

}  // namespace
}  // namespace fsi::scene
