#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "fsi/common/error.hpp"
#include "fsi/scene/parameter_file.hpp"

namespace fsi::scene {
namespace {

namespace fs = std::filesystem;

// Structure of the thesis §5.6 parameter file.
const char* kThesisLike = R"(% model data for static consistency test
SolverOptions
{
  end_time = 0.7 % total simulation time
  Timeint
  {
    max_step_size = 0.5*1e-5
    min_step_size = max_step_size
    tableau_name = "LobattoIIIA"
  }
}
Newton.max_modified_newton_steps= 40
Geometry { width = 0.05; height = 0.1 // the box
  fill_level = 0.4*height
  piston_thickness = 0.005
  piston_y = 0.75*height-0.5*piston_thickness
  offset_x = 0.0
}
LIGGGHTS_SPH_parameters
{
  smoothinglength = 0.0015
  particlespacing = smoothinglength/1.9
  xmin = 0. + Geometry.offset_x -0.01
  gravity = [0, -9.81]
  corners = [[0, 0], [Geometry.width, 0],
             [Geometry.width, Geometry.height]]
  name = "tank"
  copy = gravity
}
Body { name = "a"; mass = 1 }
Body { name = "b"; mass = 2*pi }
)";

Block parse(const std::string& text, const std::vector<Override>& overrides = {}) {
  return parse_parameter_text(text, "test.scene", overrides);
}

std::string error_text(const std::string& text, const std::vector<Override>& overrides = {}) {
  try {
    parse(text, overrides);
  } catch (const fsi::Error& error) {
    return error.what();
  }
  return "";
}

TEST(ParameterFile, ReadsTheThesisStructure) {
  const Block root = parse(kThesisLike);
  EXPECT_DOUBLE_EQ(root.lookup("SolverOptions.Timeint.min_step_size")->value.number, 0.5e-5);
  EXPECT_EQ(root.lookup("SolverOptions.Timeint.tableau_name")->value.text, "LobattoIIIA");
  EXPECT_EQ(root.lookup("Newton.max_modified_newton_steps")->value.number, 40.0);
  EXPECT_DOUBLE_EQ(root.lookup("Geometry.fill_level")->value.number, 0.04);
  EXPECT_DOUBLE_EQ(root.lookup("Geometry.piston_y")->value.number, 0.0725);
  EXPECT_DOUBLE_EQ(root.lookup("LIGGGHTS_SPH_parameters.particlespacing")->value.number,
                   0.0015 / 1.9);
  EXPECT_DOUBLE_EQ(root.lookup("LIGGGHTS_SPH_parameters.xmin")->value.number, -0.01);
  const auto& corners = root.lookup("LIGGGHTS_SPH_parameters.corners")->value;
  ASSERT_EQ(corners.kind, ValueKind::Matrix);
  ASSERT_EQ(corners.matrix.size(), 3u);
  EXPECT_DOUBLE_EQ(corners.matrix[2][1], 0.1);
  EXPECT_EQ(root.lookup("LIGGGHTS_SPH_parameters.copy")->value.vector,
            (std::vector<double>{0, -9.81}));
  ASSERT_EQ(root.children("Body").size(), 2u);
  EXPECT_DOUBLE_EQ(root.lookup("Body[1].mass")->value.number, 2 * M_PI);
  const Parameter* end_time = root.lookup("SolverOptions.end_time");
  EXPECT_EQ(end_time->location.line, 4);
  EXPECT_EQ(end_time->location.column, 3);
}

TEST(ParameterFile, OverridesPropagateToLaterParameters) {
  const Block root = parse(kThesisLike, {{"Geometry.height", "0.2"}, {"Body[0].mass", "3"}});
  EXPECT_DOUBLE_EQ(root.lookup("Geometry.fill_level")->value.number, 0.08);
  EXPECT_DOUBLE_EQ(root.lookup("Geometry.piston_y")->value.number, 0.75 * 0.2 - 0.0025);
  EXPECT_DOUBLE_EQ(root.lookup("LIGGGHTS_SPH_parameters.corners")->value.matrix[2][1], 0.2);
  EXPECT_EQ(root.lookup("Body[0].mass")->value.number, 3.0);
  EXPECT_EQ(root.lookup("Geometry.height")->location.file, "--set Geometry.height=0.2");
}

TEST(ParameterFile, OverrideErrorsSuggest) {
  const std::string unknown = error_text(kThesisLike, {{"Geometry.widht", "1"}});
  EXPECT_NE(unknown.find("no parameter 'Geometry.widht'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("did you mean 'Geometry.width'"), std::string::npos) << unknown;
  const std::string ambiguous = error_text(kThesisLike, {{"Body.mass", "1"}});
  EXPECT_NE(ambiguous.find("list of 2 blocks"), std::string::npos) << ambiguous;
  const std::string bad = error_text(kThesisLike, {{"Geometry.width", "1+"}});
  EXPECT_NE(bad.find("--set Geometry.width=1+"), std::string::npos) << bad;
  EXPECT_THROW(parse_override("no_equals"), fsi::Error);
  const Override ok = parse_override("SolverOptions.end_time = 0.05");
  EXPECT_EQ(ok.path, "SolverOptions.end_time");
  EXPECT_EQ(ok.expression, "0.05");
}

TEST(ParameterFile, UndefinedAndLaterReferencesAreLocated) {
  const std::string undefined = error_text("Geometry {\n  width = 0.05\n  height = 2*widht\n}\n");
  EXPECT_NE(undefined.find("test.scene:3:12"), std::string::npos) << undefined;
  EXPECT_NE(undefined.find("'widht' is not defined; did you mean 'width'?"), std::string::npos)
      << undefined;
  const std::string later = error_text("a = b + 1\nb = 2\n");
  EXPECT_NE(later.find("test.scene:1:5"), std::string::npos) << later;
  EXPECT_NE(later.find("is defined later at test.scene:2:1; move it above line 1"),
            std::string::npos)
      << later;
}

TEST(ParameterFile, AllEvaluationErrorsAreReportedTogether) {
  const std::string text =
      error_text("a = 1 +\nb = undefined_thing\nc = \"text\"\nd = c * 2\ne = [1, 2\n");
  // e is a syntax error ([ not closed) and stops at once; drop it to see the evaluation errors.
  EXPECT_NE(text.find("'[' is not closed"), std::string::npos) << text;
  const std::string many = error_text("a = 1 +\nb = undefined_thing\nc = \"text\"\nd = c * 2\n");
  EXPECT_NE(many.find("3 problem(s)"), std::string::npos) << many;
  EXPECT_NE(many.find("test.scene:1:5"), std::string::npos) << many;
  EXPECT_NE(many.find("test.scene:2:5"), std::string::npos) << many;
  EXPECT_NE(many.find("'c' is a string, arithmetic needs numbers"), std::string::npos) << many;
}

TEST(ParameterFile, SyntaxErrorsAreLocated) {
  EXPECT_NE(error_text("Block {\n  a = 1\n")
                .find("test.scene:1:1: block 'Block' opened here is not closed"),
            std::string::npos);
  EXPECT_NE(error_text("a = 1\n}\n").find("test.scene:2:1: '}' without an open block"),
            std::string::npos);
  EXPECT_NE(error_text("a 1\n").find("expected '=' or '{' after 'a'"), std::string::npos);
  EXPECT_NE(error_text("a =\n").find("'a' has no value"), std::string::npos);
  EXPECT_NE(error_text("s = \"open\n").find("string not closed"), std::string::npos);
  EXPECT_NE(error_text("3 = 4\n").find("unexpected '3'"), std::string::npos);
}

TEST(ParameterFile, IncludesAreTextualAndRelative) {
  const fs::path folder = fs::temp_directory_path() / "fsi_scene_include_test";
  fs::create_directories(folder / "sub");
  std::ofstream(folder / "sub" / "common.scene") << "Geometry { width = base * 2 }\n";
  std::ofstream(folder / "main.scene")
      << "base = 0.5\ninclude \"sub/common.scene\"\nafter = Geometry.width + 1\n";
  const Block root = load_parameter_file((folder / "main.scene").string());
  EXPECT_DOUBLE_EQ(root.lookup("Geometry.width")->value.number, 1.0);
  EXPECT_DOUBLE_EQ(root.lookup("after")->value.number, 2.0);
  EXPECT_NE(root.lookup("Geometry.width")->location.file.find("common.scene"), std::string::npos);
  std::ofstream(folder / "loop.scene") << "include \"loop.scene\"\n";
  try {
    load_parameter_file((folder / "loop.scene").string());
    FAIL();
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find("include cycle"), std::string::npos);
  }
  std::ofstream(folder / "missing.scene") << "include \"nothere.scene\"\n";
  EXPECT_THROW(load_parameter_file((folder / "missing.scene").string()), fsi::Error);
  fs::remove_all(folder);
}

TEST(ParameterFile, TextRoundTripKeepsEveryValue) {
  const Block first = parse(kThesisLike);
  const Block second = parse(to_text(first));
  EXPECT_EQ(flatten_numbers(first), flatten_numbers(second));
  EXPECT_EQ(to_json(first), to_json(second));
}

TEST(ParameterFile, LoadsTheStaticTankExample) {
  const Block root = load_parameter_file(FSI_EXAMPLES_DIR "/static_tank/static_tank_coarse.scene");
  EXPECT_DOUBLE_EQ(root.lookup("Geometry.width")->value.number, 0.05);
  EXPECT_DOUBLE_EQ(root.lookup("LIGGGHTS_SPH_parameters.particlespacing")->value.number,
                   0.0016 / 1.9);
  EXPECT_EQ(root.children("RigidBody2D").size(), 2u);
}

TEST(EditDistance, SuggestsTheNearestName) {
  EXPECT_EQ(edit_distance("width", "widht"), 2u);
  EXPECT_EQ(nearest("SolverOption", {"SolverOptions", "Output"}), "SolverOptions");
  EXPECT_EQ(nearest("zzz", {"SolverOptions", "Output"}), "");
}

}  // namespace
}  // namespace fsi::scene
