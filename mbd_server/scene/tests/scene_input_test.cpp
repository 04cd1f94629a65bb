// Scene input mistakes users hit (issue 18, items 7 and 9): `--set` of a key the file lacks,
// file names in included files, and an end time the step does not divide.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/scene/physics_checks.hpp"
#include "fsi/scene/scene.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

class SceneInput : public testing::FolderPerTest {
 protected:
  // A coupled scene with neither a Newton nor an Output block.
  std::string minimal_scene(const std::string& solver =
                                "end_time = 1; Timeint { step_size = "
                                "1e-5 }") const {
    return write_coupled_scene("m.scene", "SolverOptions { " + solver +
                                              " }\n"
                                              "Ground { Mesh { points = [[0, 0], [1, 0]] } }\n")
        .string();
  }

  static std::string error_of(const std::string& file, const std::vector<Override>& overrides) {
    return testing::message_thrown([&] { build_scene(file, overrides); });
  }
};

TEST_F(SceneInput, SetAddsAKeyTheSchemaDeclaresAndTheFileLacks) {
  // constraint_form: absent from an existing block; Newton and Output: blocks the file lacks.
  const Scene scene =
      build_scene(minimal_scene(), {{"SolverOptions.Timeint.constraint_form", "\"index2\""},
                                    {"SolverOptions.Newton.max_iterations", "40"},
                                    {"Output.sensor_every_steps", "5"},
                                    {"dimension", "2"}});
  EXPECT_EQ(scene.solver.constraint_form, mbd::ConstraintForm::Index2);
  EXPECT_EQ(scene.solver.newton.max_iterations, 40);
  EXPECT_EQ(scene.output.sensor_every_steps, 5);
  const Parameter* added = scene.parameters.lookup("SolverOptions.Newton.max_iterations");
  ASSERT_NE(added, nullptr);
  EXPECT_EQ(added->location.text(), "--set SolverOptions.Newton.max_iterations=40");
  // An added key sees every parameter of the file, as an override at the end would.
  const Scene derived =
      build_scene(minimal_scene(), {{"Output.sensor_every_steps", "2*SolverOptions.end_time"}});
  EXPECT_EQ(derived.output.sensor_every_steps, 2);
}

TEST_F(SceneInput, SetOfAnAddedKeyIsValidatedLikeTheFile) {
  const std::string text =
      error_of(minimal_scene(), {{"SolverOptions.Newton.max_iterations", "0"}});
  EXPECT_CONTAINS(text,
                  "--set SolverOptions.Newton.max_iterations=0: "
                  "'SolverOptions.Newton.max_iterations' = 0 is out of range");
}

TEST_F(SceneInput, SetRefusesWhatTheSchemaDoesNotDeclare) {
  const std::string scene = minimal_scene();
  // A typo of a declared key, with the nearest one.
  const std::string typo = error_of(scene, {{"SolverOptions.Timeint.step_sise", "1e-4"}});
  EXPECT_CONTAINS(typo,
                  "--set SolverOptions.Timeint.step_sise=1e-4: the scene file has no "
                  "parameter 'SolverOptions.Timeint.step_sise'");
  EXPECT_CONTAINS(typo, "did you mean 'SolverOptions.Timeint.step_size'?");
  // A block of the user's own holds only what the file gives it.
  EXPECT_CONTAINS(error_of(scene, {{"Geometry.width", "1"}}),
                  "the scene file has no parameter 'Geometry.width'");
  // An element of a list is not made by --set: which body would it be?
  const std::string body = error_of(scene, {{"RigidBody2D.mass", "1"}});
  EXPECT_CONTAINS(body, "the scene file has no parameter 'RigidBody2D.mass'");
  EXPECT_CONTAINS(body, "'RigidBody2D' blocks form a list");
}

TEST_F(SceneInput, IncludedFilesNameScriptsAndMeshesRelativeToThemselves) {
  write("parts/s.in", "# script\n");
  write("parts/box.stl", testing::unit_box_stl());
  write("parts/fluid.inc",
        "LIGGGHTS { script1 = \"s.in\"; script2 = \"s.in\" }\n"
        "Ground { Mesh { stl = \"box.stl\"; scale = 2; offset = [-0.5, -0.5, -0.5] } }\n"
        "FluidRegion { shape = \"stl\"; stl = \"box.stl\"; spacing = 0.25; density = 1000 }\n");
  const std::string file = write("top.scene",
                                 "scene_language = 1\ndimension = 3\n"
                                 "SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }\n"
                                 "include \"parts/fluid.inc\"\n"
                                 "Coupling { refinement_resolution = 0.2 }\n");
  const Scene scene = build_scene(file);
  EXPECT_EQ(scene.liggghts.script1_text, "# script\n");
  EXPECT_EQ(scene.boundary.element_count(), 12u);
  EXPECT_EQ(scene.fluid.count(), 64u);
  // A name given on the command line is relative to the top-level scene, as before.
  write("other.in", "# other\n");
  const Scene overridden = build_scene(file, {{"LIGGGHTS.script2", "\"other.in\""}});
  EXPECT_EQ(overridden.liggghts.script2_text, "# other\n");
}

TEST_F(SceneInput, AMissingScriptInAnIncludedFileIsSoughtBesideIt) {
  write("parts/fluid.inc", "LIGGGHTS { script1 = \"s.in\"; script2 = \"s.in\" }\n");
  write("s.in", "# beside the top-level scene, not beside the include\n");
  const std::string file = write("top.scene",
                                 "scene_language = 1\n"
                                 "SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }\n"
                                 "Ground { Mesh { points = [[0, 0], [1, 0]] } }\n"
                                 "include \"parts/fluid.inc\"\n"
                                 "Coupling { refinement_resolution = 0.002 }\n");
  const std::string text = error_of(file, {});
  EXPECT_CONTAINS(text, "fluid.inc:1:12: LIGGGHTS script '" + (folder_ / "parts/s.in").string() +
                            "' cannot be read");
  EXPECT_CONTAINS(text, "relative to the scene file that names it");
}

TEST_F(SceneInput, AnEndTimeTheStepDoesNotDivideIsReported) {
  // 0.01 / 3e-4 = 33.33: the run takes 33 steps and ends at 0.0099 s.
  const Scene scene = build_scene(minimal_scene("end_time = 0.01; Timeint { step_size = 3e-4 }"));
  const std::vector<Diagnostic> found = end_time_check(scene);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].severity, Severity::Warning);
  EXPECT_EQ(found[0].location.text(), (folder_ / "m.scene").string() + ":2:17");
  EXPECT_CONTAINS(found[0].message,
                  "end_time / step_size = 0.01 s / 0.0003 s = 33.33 is not a whole number");
  EXPECT_CONTAINS(found[0].message, "the run takes 33 steps and ends at t = 0.0099 s");
  EXPECT_EQ(found[0].fix,
            "use step_size = 0.01/33 (33 steps) or 0.01/34 (34 steps), or end_time = 0.0099 s "
            "(33 steps) or 0.0102 s (34 steps)");
  // An end time below half a step: the run takes no step at all.
  const std::vector<Diagnostic> none =
      end_time_check(build_scene(minimal_scene("end_time = 0.001; Timeint { step_size = 0.003 }")));
  ASSERT_EQ(none.size(), 1u);
  EXPECT_CONTAINS(none[0].message,
                  "= 0.33 is not a whole number: the run takes 0 steps and ends "
                  "at t = 0 s");
  EXPECT_EQ(none[0].fix, "use step_size = 0.001/1 (1 step), or end_time = 0.003 s (1 step)");
  // Steps that divide, also where the quotient is not exact in binary (0.15 / 3e-5).
  for (const char* solver : {"end_time = 0.01; Timeint { step_size = 1e-4 }",
                             "end_time = 0.15; Timeint { step_size = 3e-5 }",
                             "end_time = 0.7; Timeint { step_size = 0.1 }"}) {
    EXPECT_TRUE(end_time_check(build_scene(minimal_scene(solver))).empty()) << solver;
  }
}

}  // namespace
}  // namespace fsi::scene
