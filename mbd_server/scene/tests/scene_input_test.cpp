// Scene input mistakes users hit (issue 18, items 7 and 9): `--set` of a key the file lacks,
// file names in included files, and an end time the step does not divide.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/scene/scene.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

namespace fs = std::filesystem;

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

// A folder of its own per test, removed afterwards.
class SceneInput : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("fsi_scene_input_" +
               std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  std::string write(const std::string& name, const std::string& text) const {
    const fs::path file = folder_ / name;
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
    return file.string();
  }

  // A coupled scene with neither a Newton nor an Output block.
  std::string minimal_scene(const std::string& solver =
                                "end_time = 1; Timeint { step_size = "
                                "1e-5 }") const {
    write("s.in", "# script\n");
    return write("m.scene", "scene_language = 1\nSolverOptions { " + solver +
                                " }\n"
                                "Ground { Mesh { points = [[0, 0], [1, 0]] } }\n"
                                "LIGGGHTS { script1 = \"s.in\"; script2 = \"s.in\" }\n"
                                "Coupling { refinement_resolution = 0.002 }\n");
  }

  std::string error_of(const std::string& file, const std::vector<Override>& overrides) const {
    try {
      build_scene(file, overrides);
    } catch (const fsi::Error& error) {
      return error.what();
    }
    return "(accepted)";
  }

  fs::path folder_;
};

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

}  // namespace
}  // namespace fsi::scene
