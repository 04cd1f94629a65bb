#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <utility>

#include "fsi/common/error.hpp"
#include "fsi/scene/parameter_file.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

using testing::message_thrown;

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class TempFolder {
 public:
  TempFolder() {
    static int counter = 0;
    path_ = fs::temp_directory_path() /
            ("fsi_scene_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempFolder() { fs::remove_all(path_); }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  std::string write(const std::string& name, const std::string& text) const {
    const fs::path file = path_ / name;
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
    return file.string();
  }

 private:
  fs::path path_;
};

Block parse(const std::string& text, const std::vector<Override>& overrides = {}) {
  return parse_parameter_text(text, "t.scene", overrides);
}

// The message of the fsi::Error that parsing throws ("" if it does not throw).
std::string error_of(const std::string& text, const std::vector<Override>& overrides = {}) {
  return message_thrown([&] { parse(text, overrides); });
}

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

double number_at(const Block& root, const std::string& path) {
  const Parameter* parameter = root.lookup(path);
  EXPECT_NE(parameter, nullptr) << path;
  if (!parameter) return std::nan("");
  EXPECT_EQ(parameter->value.kind, ValueKind::Number) << path;
  return parameter->value.number;
}

// The structure of the thesis §5.6 parameter file, spread over three files.
const char* kMainFile = R"(% model data for the static consistency test
include "parts/common.scene"
SolverOptions
{
  end_time = 0.7      % total simulated time
  Timeint { step_size = 0.5*1e-5; tableau = "RadauIIA" }
}
Newton.max_iterations = 40   // a dotted key creates block Newton
Geometry
{
  width = 0.05; height = 0.1
  piston_thickness = 0.005
  offset_x = 0.002
  piston_y = 0.75*height - 0.5*piston_thickness
}
LIGGGHTS_SPH_parameters {
  xmin = 0. + Geometry.offset_x - 0.01
  name = "piston"
  gravity = [0, -9.81]
  points = [[0, 0], [Geometry.width, 0],   % bottom edge
            [Geometry.width, Geometry.height*Material.scale]]
  copy = gravity
}
Body { name = "a"; mass = 1 }  Body { name = "b"; mass = 2*pi }
heavier = Body[1].mass - Body[0].mass
)";

TEST(ParameterFile, ReadsTheStructureOfThesisSection56) {
  TempFolder folder;
  folder.write(
      "parts/common.scene",
      "% shared material data\nMaterial { density = 1000\n  include \"more/scale.scene\"\n}\n");
  folder.write("parts/more/scale.scene", "scale = 2  // relative to parts/\n");
  const Block root = load_parameter_file(folder.write("main.scene", kMainFile));

  EXPECT_DOUBLE_EQ(number_at(root, "SolverOptions.end_time"), 0.7);
  EXPECT_DOUBLE_EQ(number_at(root, "SolverOptions.Timeint.step_size"), 0.5e-5);
  EXPECT_EQ(root.lookup("SolverOptions.Timeint.tableau")->value.text, "RadauIIA");
  EXPECT_EQ(number_at(root, "Newton.max_iterations"), 40.0);
  EXPECT_DOUBLE_EQ(number_at(root, "Geometry.piston_y"), 0.75 * 0.1 - 0.5 * 0.005);
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.xmin"), 0.002 - 0.01);
  EXPECT_EQ(root.lookup("LIGGGHTS_SPH_parameters.name")->value.text, "piston");
  const Value& points = root.lookup("LIGGGHTS_SPH_parameters.points")->value;
  ASSERT_EQ(points.kind, ValueKind::Matrix);
  EXPECT_EQ(points.matrix, (NumberMatrix{{0, 0}, {0.05, 0}, {0.05, 0.2}}));
  EXPECT_EQ(root.lookup("LIGGGHTS_SPH_parameters.copy")->value, vector_value({0, -9.81}));
  ASSERT_EQ(root.children("Body").size(), 2u);
  EXPECT_EQ(root.lookup("Body[1].name")->value.text, "b");
  EXPECT_DOUBLE_EQ(number_at(root, "heavier"), 2 * std::numbers::pi - 1);
  EXPECT_EQ(number_at(root, "Material.density"), 1000.0);
  EXPECT_EQ(number_at(root, "Material.scale"), 2.0);

  // Locations: line:column of the key, in the file that holds it.
  const Parameter* end_time = root.lookup("SolverOptions.end_time");
  EXPECT_EQ(end_time->location.line, 5);
  EXPECT_EQ(end_time->location.column, 3);
  EXPECT_EQ(end_time->expression, "0.7");
  const Parameter* height = root.lookup("Geometry.height");
  EXPECT_EQ(height->location.line, 11);
  EXPECT_EQ(height->location.column, 17);
  const Parameter* density = root.lookup("Material.density");
  EXPECT_EQ(fs::path(density->location.file).filename(), "common.scene");
  EXPECT_EQ(density->location.line, 2);
  EXPECT_EQ(density->location.column, 12);
  EXPECT_EQ(fs::path(root.lookup("Material.scale")->location.file).filename(), "scale.scene");
  // A matrix over two lines keeps its expression on one line, without the comment.
  EXPECT_EQ(root.lookup("LIGGGHTS_SPH_parameters.points")->expression,
            "[[0, 0], [Geometry.width, 0], [Geometry.width, Geometry.height*Material.scale]]");
  // The included block comes first in textual order.
  ASSERT_FALSE(root.entries.empty());
  EXPECT_EQ(root.entries.front().type, BlockEntry::Type::Block);
  EXPECT_EQ(root.blocks[root.entries.front().index].name, "Material");
}

TEST(ParameterFile, ReferencesResolveInnermostBlockFirst) {
  const Block root = parse(R"(width = 1
top = 5
Outer {
  width = 2
  Inner {
    a = width            % Outer.width: the nearest enclosing definition
    b = top              % found at the root
    width = width * 10   % the right side sees Outer.width
    c = width            % Inner's own width now
  }
  d = Inner.c
}
name = "tank"
v = [1, 2]
m = [[1, 2], [3, 4]]
copied_name = name
copied_v = v
copied_m = m
Body { mass = 1 }
Body { mass = 2 }
twice = 2*Body[1].mass + Outer.Inner.c
)");
  EXPECT_EQ(number_at(root, "Outer.Inner.a"), 2.0);
  EXPECT_EQ(number_at(root, "Outer.Inner.b"), 5.0);
  EXPECT_EQ(number_at(root, "Outer.Inner.width"), 20.0);
  EXPECT_EQ(number_at(root, "Outer.Inner.c"), 20.0);
  EXPECT_EQ(number_at(root, "Outer.d"), 20.0);
  EXPECT_EQ(root.lookup("copied_name")->value, text_value("tank"));
  EXPECT_EQ(root.lookup("copied_v")->value, vector_value({1, 2}));
  EXPECT_EQ(root.lookup("copied_m")->value, matrix_value({{1, 2}, {3, 4}}));
  EXPECT_EQ(number_at(root, "twice"), 24.0);
}

TEST(ParameterFile, LaterDefinitionInInnerBlockFallsBackToEarlierOuterOne) {
  const Block root = parse("width = 1\nG {\n  half = width/2\n  width = 4\n}\n");
  EXPECT_EQ(number_at(root, "G.half"), 0.5);
  EXPECT_EQ(number_at(root, "G.width"), 4.0);
}

TEST(ParameterFile, DottedKeysAssignInsideBlocks) {
  const Block root = parse(R"(Newton.max_iterations = 40
Newton { tolerance = 1e-8 }
SolverOptions { end_time = 1 }
SolverOptions.Timeint.step_size = 1e-5
Body { mass = 1 }
Body { mass = 2 }
Body[1].mass = 3
)");
  // The dotted key and the later block are one block, not a list of two.
  ASSERT_EQ(root.children("Newton").size(), 1u);
  EXPECT_EQ(number_at(root, "Newton.max_iterations"), 40.0);
  EXPECT_EQ(number_at(root, "Newton.tolerance"), 1e-8);
  EXPECT_EQ(root.children("SolverOptions").size(), 1u);
  EXPECT_EQ(number_at(root, "SolverOptions.Timeint.step_size"), 1e-5);
  EXPECT_EQ(number_at(root, "Body[1].mass"), 3.0);  // the last assignment counts
  EXPECT_EQ(root.lookup_block("Body[1]")->parameters.size(), 2u);
}

TEST(ParameterFile, ReferenceToALaterParameterNamesBothPlaces) {
  const std::string message = error_of("a = b + 1\nb = 2\n");
  EXPECT_CONTAINS(
      message, "t.scene:1:5: in 'a': 'b' is defined later, at t.scene:2:1; move it above line 1");
}

TEST(ParameterFile, AValueAssignedAgainAfterAUseIsAnError) {
  // As a variant scene does below an include: the beam's mass took rho = 1100, the scene would
  // record rho = 4400. Named at the use, with both assignments and the way to change it.
  const std::string text =
      "Geometry { rho = 1100; h = 0.005 }\nBeam { mass = Geometry.rho*Geometry.h }\n"
      "Geometry.rho = 4400\n";
  const std::string message = error_of(text);
  EXPECT_CONTAINS(message, "1 problem(s)");
  EXPECT_CONTAINS(message,
                  "t.scene:2:8: in 'Beam.mass': 'Geometry.rho' is assigned again at t.scene:3:1, "
                  "after this use: the use takes the value of t.scene:1:12");
  EXPECT_CONTAINS(message, "give it with --set Geometry.rho=...");
  // --set replaces the value everywhere: no problem, and the use sees it.
  EXPECT_EQ(
      number_at(
          parse("Geometry { rho = 1100; h = 0.005 }\nBeam { mass = Geometry.rho*Geometry.h }\n",
                {{"Geometry.rho", "4400"}}),
          "Beam.mass"),
      22.0);
  // Assigned again before any use, or again with the same value: nothing to report.
  EXPECT_EQ(error_of("a = 1\na = 2\nb = a\n"), "");
  EXPECT_EQ(error_of("a = 1\nb = a\na = 1\n"), "");
  EXPECT_EQ(number_at(parse("a = 1\nb = a\na = 1\n"), "b"), 1.0);
}

TEST(ParameterFile, ACycleIsNamedAsOneWithItsWholeChain) {
  // a -> Geometry.b -> c -> a, across blocks; reported once, where the cycle is entered.
  const std::string message =
      error_of("a = Geometry.b + 1\nGeometry { b = sqrt(c) }\nc = 2*a\nd = 1\n");
  EXPECT_CONTAINS(message, "1 problem(s)");
  EXPECT_CONTAINS(message, "t.scene:1:5: in 'a': 'Geometry.b' is defined later (t.scene:2:12)");
  EXPECT_CONTAINS(message, "a cycle a -> Geometry.b -> c -> a; break the cycle");
  // A parameter referring to itself is a plain undefined name (nothing earlier has its name).
  EXPECT_CONTAINS(error_of("x = x + 1\n"), "'x' is not defined");
}

TEST(ParameterFile, AnUnknownFunctionIsNamedAsOneWithTheFunctionsThereAre) {
  // A user's round(x): it was "not defined; define it above this line".
  const std::string message = error_of("n = round(2.6)\nm = rint (2.6)\n");
  EXPECT_CONTAINS(message, "2 problem(s)");
  EXPECT_CONTAINS(message,
                  "t.scene:2:5: in 'm': 'rint' is followed by a blank before its '('; "
                  "write rint(...) without the blank");
  EXPECT_CONTAINS(message,
                  "t.scene:1:5: in 'n': 'round' is not a function of the scene language; "
                  "use one of sin cos tan");
  EXPECT_CONTAINS(message, "rint (to the nearest integer) min max sum avg; round(x) is rint(x)");
  EXPECT_EQ(number_at(parse("m = rint(2.6)\n"), "m"), 3.0);
}

TEST(ParameterFile, UndefinedNameSuggestsTheNearestOne) {
  const std::string message = error_of("Geometry {\n  width = 0.05\n  height = 2*widht\n}\n");
  EXPECT_CONTAINS(message,
                  "t.scene:3:14: in 'Geometry.height': 'widht' is not defined; did you mean "
                  "'width'?");
  const std::string dotted = error_of("G { width = 1 }\nx = 1 + G.widht\n");
  EXPECT_CONTAINS(dotted, "t.scene:2:9: in 'x': block 'G' has no parameter 'widht'");
  EXPECT_CONTAINS(dotted, "did you mean 'G.width'?");
  // Only the dotted path exists: suggest it.
  EXPECT_CONTAINS(error_of("Geometry { offset_x = 1 }\nx = offset_x\n"),
                  "t.scene:2:5: in 'x': 'offset_x' is not defined; did you mean "
                  "'Geometry.offset_x'?");
}

// Rows may differ in length (a Mesh's [x, y] and [x, y, r] points): the schema judges each row
// of a declared key (SchemaTest: "row 2 has 3 values, it needs 2").
TEST(ParameterFile, MatrixRowsMayDifferInLength) {
  const Block root = parse("m = [[1, 2],\n     [3], [4, 5, 6]]\n");
  EXPECT_EQ(root.lookup("m")->value.matrix, (NumberMatrix{{1, 2}, {3}, {4, 5, 6}}));
}

TEST(ParameterFile, EvaluationErrorsAreLocatedAtTheirToken) {
  EXPECT_CONTAINS(error_of("c = \"text\"\nd = 1 + c * 2\n"),
                  "t.scene:2:9: in 'd': 'c' is a string: arithmetic needs numbers");
  EXPECT_CONTAINS(error_of("v = [1, 2]\nx = v * 2\n"),
                  "t.scene:2:5: in 'x': 'v' is a vector: arithmetic needs numbers");
  EXPECT_CONTAINS(error_of("a = 1 +\n"), "t.scene:1:8: in 'a': cannot evaluate '1 +'");
  EXPECT_CONTAINS(error_of("a = 1\ny = sqrt(-a)\n"),
                  "t.scene:2:5: in 'y': 'sqrt(-a)' evaluates to nan");
  EXPECT_CONTAINS(error_of("v = [1, [2]]\n"),
                  "t.scene:1:9: in 'v': the list mixes numbers and bracketed rows");
  EXPECT_CONTAINS(error_of("v = [1, 2] + 1\n"),
                  "t.scene:1:11: in 'v': unexpected text after the closing ']'");
  EXPECT_CONTAINS(error_of("v = [1, , 2]\n"), "t.scene:1:9: in 'v': empty element");
  EXPECT_CONTAINS(error_of("s = \"a\" \"b\"\n"),
                  "t.scene:1:8: in 's': unexpected text after the string");
  EXPECT_CONTAINS(error_of("G { a = 1 }\nx = G\n"), "t.scene:2:5: in 'x': 'G' is a block");
  EXPECT_CONTAINS(error_of("e = 2\nx = 3*e\n"),
                  "t.scene:2:7: in 'x': 'e' is the built-in constant and also a parameter "
                  "(t.scene:1:1)");
  const std::string list = error_of("Body { m = 1 }\nBody { m = 2 }\nx = Body.m\ny = Body[2].m\n");
  EXPECT_CONTAINS(list,
                  "t.scene:3:5: in 'x': 'Body' is a list of 2 blocks; pick one: Body[0].m ... "
                  "Body[1].m");
  EXPECT_CONTAINS(list, "t.scene:4:5: in 'y': 'Body[2]' does not exist: there are 2 'Body' blocks");
}

TEST(ParameterFile, AllEvaluationErrorsComeInOneMessageOneLineEach) {
  const std::string message = error_of(
      "a = 1 +\n"
      "b = undefined_thing\n"
      "c = \"text\"\n"
      "d = c * 2\n"
      "e2 = a * 2     % depends on the broken a: no second message\n"
      "f = [1, widht]\n");
  EXPECT_CONTAINS(message, "4 problem(s)");
  EXPECT_CONTAINS(message, "\n  t.scene:1:8: in 'a'");
  EXPECT_CONTAINS(message, "\n  t.scene:2:5: in 'b'");
  EXPECT_CONTAINS(message, "\n  t.scene:4:5: in 'd'");
  EXPECT_CONTAINS(message, "\n  t.scene:6:9: in 'f'");
  EXPECT_EQ(message.find("'e2'"), std::string::npos) << message;
  EXPECT_CONTAINS(message, "how to fix:");
}

TEST(ParameterFile, SyntaxErrorsStopAtTheFirstWithItsLocation) {
  // Each: the text, and the message of its first syntax error.
  const std::pair<std::string, std::string> cases[] = {
      {"Block {\n  a = 1\n", "t.scene:1:1: block 'Block' is not closed"},
      {"a = 1\n}\n", "t.scene:2:1: '}' without an open block"},
      {"a 1\n", "t.scene:1:1: 'a' is followed by neither '=' nor '{'"},
      {"a = 1\ns = \"open\n", "t.scene:2:5: the string is not closed"},
      {"v = [1,\n  2\n", "t.scene:1:5: '[' is not closed"},
      {"a = (1 + 2]\n", "t.scene:1:11: ']' does not match the '(' opened at t.scene:1:5"},
      {"B { a = [1, 2 }\n", "t.scene:1:9: '[' is not closed before '}'"},
      {"x = 2]\n", "t.scene:1:6: ']' without a matching '['"},
      {"x = { 1 }\n", "t.scene:1:5: '{' inside an expression"},
      {"a =   % nothing\n", "t.scene:1:1: 'a' has no value after '='"},
      {"  3 = 4\n", "t.scene:1:3: unexpected '3'"},
      {"x.y. = 1\n", "t.scene:1:1: 'x.y.' is not a valid name"},
      {"a[1] = 2\n", "t.scene:1:1: only blocks take an index"},
      {"A.B { }\n", "t.scene:1:1: a block name cannot contain '.'"},
      {"include common.scene\n", "t.scene:1:9: include needs a file name in double quotes"},
      {"G = 1\nG { }\n", "t.scene:2:1: 'G' is already a parameter of this block (t.scene:1:1)"},
      {"Body { m = 1 }\nBody { m = 2 }\nBody.m = 3\n",
       "t.scene:3:1: 'Body' is a list of 2 blocks, so 'Body.m' is ambiguous"},
  };
  for (const auto& [text, expected] : cases)
    EXPECT_CONTAINS(error_of(text), expected);
  // A syntax error wins over evaluation errors before it: nothing is evaluated.
  const std::string message = error_of("a = undefined\nb = (\n");
  EXPECT_CONTAINS(message, "t.scene:2:5: '(' is not closed");
  EXPECT_EQ(message.find("undefined"), std::string::npos) << message;
}

TEST(ParameterFile, IncludeErrorsNameTheIncludingLine) {
  TempFolder folder;
  const std::string missing = folder.write("missing.scene", "a = 1\n  include \"nothere.scene\"\n");
  const std::string missing_include = message_thrown([&] { load_parameter_file(missing); });
  EXPECT_CONTAINS(missing_include, "missing.scene:2:3: cannot read the included file");
  EXPECT_CONTAINS(missing_include, "nothere.scene");
  folder.write("a.scene", "x = 1\ninclude \"b.scene\"\n");
  folder.write("b.scene", "include \"a.scene\"\n");
  const std::string include_cycle = message_thrown(
      [&] { load_parameter_file(folder.write("loop.scene", "include \"a.scene\"\n")); });
  EXPECT_CONTAINS(include_cycle, "b.scene:1:1");
  EXPECT_CONTAINS(include_cycle, "include cycle: a.scene -> b.scene -> a.scene");
  folder.write("broken.scene", "ok = 1\nbad = [1\n");
  const std::string broken_include = message_thrown(
      [&] { load_parameter_file(folder.write("top.scene", "\n\ninclude \"broken.scene\"\n")); });
  EXPECT_CONTAINS(broken_include, "broken.scene:2:7 (included from ");
  EXPECT_CONTAINS(broken_include, "top.scene:3:1)");
}

// Found by designing the scene fuzzer: a folder opened as a file read as empty, so
// `include "data"` (a folder) or a scene path naming a folder passed silently as an empty scene,
// and a device such as /dev/zero or a pipe would be read forever. Only regular files are read.
TEST(ParameterFile, IncludesAndScenesMustBeRegularFiles) {
  TempFolder folder;
  folder.write("data/x.scene", "x = 1\n");
  const std::string main = folder.write("main.scene", "a = 1\ninclude \"data\"\n");
  const std::string folder_include = message_thrown([&] { load_parameter_file(main); });
  EXPECT_CONTAINS(folder_include, "main.scene:2:1: cannot read the included file");
  EXPECT_CONTAINS(folder_include, "not a folder or a device");
  const std::string device_include =
      message_thrown([&] { parse_parameter_text("include \"/dev/null\"\n", "t.scene"); });
  EXPECT_CONTAINS(device_include, "t.scene:1:1: cannot read the included file '/dev/null'");
  const std::string data_folder = fs::path(main).parent_path() / "data";
  const std::string folder_scene = message_thrown([&] { load_parameter_file(data_folder); });
  EXPECT_CONTAINS(folder_scene, "cannot read the scene file '" + data_folder + "'");
}

// The fuzzer's reader: includes come from memory only, relative to the including file's folder,
// and a name outside the given files (absolute, or with ../ leaving the folder) is not found.
TEST(ParameterFile, InMemoryIncludesReadNothingElse) {
  const IncludeReader files =
      in_memory_files({{"/scenes/common.inc", "g = 9.81\n"},
                       {"/scenes/sub/nested.inc", "include \"../common.inc\"\n"},
                       {"/scenes/loop.inc", "include \"loop.inc\"\n"}});
  const Block root = parse_parameter_text("include \"sub/nested.inc\"\nw = 2*g\n",
                                          "/scenes/main.scene", {}, files);
  EXPECT_DOUBLE_EQ(number_at(root, "w"), 2 * 9.81);
  for (const std::string outside : {"/etc/hostname", "../etc/hostname", "sub/../../etc/hostname"}) {
    const std::string read_outside = message_thrown([&] {
      parse_parameter_text("include \"" + outside + "\"\n", "/scenes/main.scene", {}, files);
    });
    EXPECT_CONTAINS(read_outside, "/scenes/main.scene:1:1: cannot read the included file");
  }
  const std::string memory_cycle = message_thrown(
      [&] { parse_parameter_text("include \"loop.inc\"\n", "/scenes/main.scene", {}, files); });
  EXPECT_CONTAINS(memory_cycle, "include cycle: loop.inc -> loop.inc");
}

// Found by fuzz_scene_parser: a string value with bytes that are not UTF-8 made the run manifest's
// to_json(...).dump() throw nlohmann's type_error 316; invalid bytes now become U+FFFD.
TEST(ParameterFile, JsonOfAStringThatIsNotUtf8) {
  const Block root = parse(
      "name = \"a\xFF\xFE"
      "b\"\n");
  std::string dumped;
  EXPECT_NO_THROW(dumped = to_json(root).dump());
  EXPECT_EQ(dumped,
            "{\"name\":\"a\xEF\xBF\xBD\xEF\xBF\xBD"
            "b\"}");
}

TEST(ParameterFile, OverridesReplaceTheExpressionInPlace) {
  const std::string text = R"(Geometry { width = 0.05; height = 2*width }
points = [[0, 0], [Geometry.width, Geometry.height]]
Body { mass = 1 }
Body { mass = 2 }
name = "tank"
later = Body[1].mass + 1
)";
  const Block root = parse(
      text,
      {{"Geometry.width", "0.06"}, {"Body[1].mass", "3*Geometry.width"}, {"name", "\"other\""}});
  EXPECT_DOUBLE_EQ(number_at(root, "Geometry.height"), 0.12);
  EXPECT_DOUBLE_EQ(root.lookup("points")->value.matrix[1][1], 0.12);
  EXPECT_DOUBLE_EQ(number_at(root, "Body[1].mass"), 0.18);
  EXPECT_DOUBLE_EQ(number_at(root, "later"), 1.18);
  EXPECT_EQ(number_at(root, "Body[0].mass"), 1.0);
  EXPECT_EQ(root.lookup("name")->value.text, "other");
  const Parameter* width = root.lookup("Geometry.width");
  EXPECT_EQ(width->location.text(), "--set Geometry.width=0.06");
  EXPECT_EQ(width->expression, "0.06");
  // Still at its original place: first entry of Geometry.
  EXPECT_EQ(root.lookup_block("Geometry")->parameters.front().key, "width");
}

TEST(ParameterFile, OverrideErrorsNameTheOverride) {
  const std::string text =
      "Geometry { width = 0.05 }\nBody { mass = 1 }\nBody { mass = 2 }\nz = 1\n";
  const std::string unknown = error_of(text, {{"Geometry.widht", "1"}});
  EXPECT_CONTAINS(unknown,
                  "--set Geometry.widht=1: the scene file has no parameter 'Geometry.widht'");
  EXPECT_CONTAINS(unknown, "did you mean 'Geometry.width'?");
  EXPECT_CONTAINS(error_of(text, {{"Body.mass", "1"}}),
                  "--set Body.mass=1: 'Body' is a list of 2 blocks\n  how to fix: pick one: "
                  "Body[0].mass ... Body[1].mass");
  EXPECT_CONTAINS(error_of(text, {{"Body[2].mass", "1"}}),
                  "--set Body[2].mass=1: there are only 2 'Body' blocks");
  EXPECT_CONTAINS(error_of(text, {{"Geometry", "1"}}),
                  "--set Geometry=1: 'Geometry' is a block, not a parameter");
  EXPECT_CONTAINS(error_of(text, {{"Geometry.width", "1+"}}),
                  "--set Geometry.width=1+: in 'Geometry.width': cannot evaluate '1+'");
  EXPECT_CONTAINS(error_of(text, {{"Geometry.width", "[1, 2"}}),
                  "--set Geometry.width=[1, 2: in 'Geometry.width': '[' is not closed");
  EXPECT_CONTAINS(error_of(text, {{"Geometry.width", "z"}}),
                  "--set Geometry.width=z: in 'Geometry.width': 'z' is defined later, at "
                  "t.scene:4:1; an override sees only parameters defined above the overridden "
                  "one (t.scene:1:12)");
  EXPECT_CONTAINS(error_of(text, {{"Geometry.width", ""}}), "the override has no value");
  // A bare word: the shell took the quotes of a text value.
  const std::string bare = error_of("Fluid { wall_friction_rule = \"thesis\" }\n",
                                    {{"Fluid.wall_friction_rule", "moment"}});
  EXPECT_CONTAINS(bare, "'moment' is not defined");
  EXPECT_CONTAINS(bare,
                  "a text value keeps its quotes through the shell: --set "
                  "'Fluid.wall_friction_rule=\"moment\"'");
  EXPECT_EQ(error_of(text, {{"Geometry.width", "Body.mass"}}).find("keeps its quotes"),
            std::string::npos);  // a path: not a text value

  EXPECT_THROW(parse_override("no_equals_sign"), fsi::Error);
  EXPECT_THROW(parse_override("=3"), fsi::Error);
  const Override parsed = parse_override(" SolverOptions.end_time = 0.05 ");
  EXPECT_EQ(parsed.path, "SolverOptions.end_time");
  EXPECT_EQ(parsed.expression, "0.05");
  EXPECT_EQ(parse_override("name=\"a=b\"").expression, "\"a=b\"");
}

void expect_same_values(const Block& a, const Block& b) {
  ASSERT_EQ(a.name, b.name);
  ASSERT_EQ(a.entries.size(), b.entries.size()) << a.name;
  for (std::size_t i = 0; i < a.entries.size(); ++i) {
    ASSERT_EQ(a.entries[i].type, b.entries[i].type) << a.name;
    if (a.entries[i].type == BlockEntry::Type::Block) {
      expect_same_values(a.blocks[a.entries[i].index], b.blocks[b.entries[i].index]);
    } else {
      const Parameter& left = a.parameters[a.entries[i].index];
      const Parameter& right = b.parameters[b.entries[i].index];
      EXPECT_EQ(left.key, right.key);
      EXPECT_EQ(left.value, right.value) << left.key;  // bit-exact doubles
    }
  }
}

TEST(ParameterFile, PrintedTextParsesBackToTheSameValues) {
  TempFolder folder;
  folder.write("parts/common.scene", "Material { density = 1000; scale = 2 }\n");
  const Block first = load_parameter_file(folder.write("main.scene", std::string(kMainFile) + R"(
Tricky {
  third = 1/3
  sum = 0.1 + 0.2
  tiny = 1e-300
  huge = 2^70 + 1
  negative = -0.0
  text = "50% full; {x} // not a comment"
  empty = []
  twice = 1
  twice = twice + 1
}
)"));
  const std::string printed = to_text(first);
  const Block second = parse_parameter_text(printed, "printed.scene");
  expect_same_values(first, second);
  // Evaluated values carry their expression as a comment.
  EXPECT_CONTAINS(printed, "step_size = 5e-06  % 0.5*1e-5");
  EXPECT_CONTAINS(printed, "third = 0.3333333333333333  % 1/3");
  // Printing the reparsed tree gives the same values again (a fixed point up to comments).
  expect_same_values(second, parse_parameter_text(to_text(second), "again.scene"));
}

TEST(ParameterFile, JsonMirrorsTheTree) {
  const Block root = parse(
      "S { end_time = 0.5; T { tableau = \"RadauIIA\" } }\nBody { m = 1 }\nBody { m = 2 }\n"
      "One { v = [1, 2] }\nm = [[1, 2], [3, 4]]\n");
  const nlohmann::json json = to_json(root);
  EXPECT_EQ(json["S"]["end_time"], 0.5);
  EXPECT_EQ(json["S"]["T"]["tableau"], "RadauIIA");
  ASSERT_TRUE(json["Body"].is_array());
  EXPECT_EQ(json["Body"][1]["m"], 2.0);
  EXPECT_TRUE(json["One"].is_object());
  EXPECT_EQ(json["One"]["v"], nlohmann::json({1.0, 2.0}));
  EXPECT_EQ(json["m"][1][0], 3.0);
  const auto flat = flatten_numbers(root);
  EXPECT_EQ(flat.at("Body[1].m"), 2.0);
  EXPECT_EQ(flat.at("S.end_time"), 0.5);
}

TEST(ParameterFile, TheLanguageVersionIsReadFirst) {
  const Block root = parse("% a scene\n\nscene_language = 1   % the version\na = 2\n");
  EXPECT_EQ(root.language_version, 1L);
  EXPECT_EQ(root.language_version_location.line, 3);
  EXPECT_EQ(root.find("scene_language"), nullptr);  // a statement, not a parameter
  EXPECT_EQ(parse("a = 1\n").language_version, std::nullopt);
  // Printed back and recorded in the manifest.
  EXPECT_EQ(to_text(root).rfind("scene_language = 1\na = 2", 0), 0u) << to_text(root);
  EXPECT_EQ(parse(to_text(root)).language_version, 1L);
  EXPECT_EQ(to_json(root)["scene_language"], 1);

  // A newer version is refused before its (perhaps new) syntax is read.
  const std::string newer = error_of("scene_language = 2\nBody < mass := 1 >\n");
  EXPECT_CONTAINS(newer,
                  "the file is written for scene language version 2, this program reads version 1");
  EXPECT_CONTAINS(newer, "t.scene:1:18");
  EXPECT_CONTAINS(newer, "use an fsi-server that reads version 2");
  // Only as the first entry, only a whole number written out.
  EXPECT_CONTAINS(error_of("a = 1\nscene_language = 1\n"),
                  "t.scene:2:1: scene_language must be the first entry of its file");
  EXPECT_CONTAINS(error_of("A { scene_language = 1 }\n"), "must be the first entry");
  EXPECT_CONTAINS(error_of("scene_language = 1.5\n"), "takes a whole number written out");
  EXPECT_CONTAINS(error_of("scene_language = 2-1\n"), "takes a whole number written out");
  EXPECT_CONTAINS(error_of("scene_language = 0\n"), "versions start at 1");
}

TEST(ParameterFile, AnIncludedFileMayStateItsVersionToo) {
  TempFolder folder;
  folder.write("ok.inc", "% fragment\nscene_language = 1\nb = 2\n");
  folder.write("new.inc", "scene_language = 3\nb = 2\n");
  const Block root = load_parameter_file(
      folder.write("main.scene", "scene_language = 1\na = 1\ninclude \"ok.inc\"\nc = a + b\n"));
  EXPECT_EQ(root.language_version, 1L);
  EXPECT_EQ(root.language_version_location.line, 1);
  EXPECT_EQ(number_at(root, "c"), 3.0);
  const std::string newer_include = message_thrown([&] {
    load_parameter_file(folder.write("bad.scene", "scene_language = 1\ninclude \"new.inc\"\n"));
  });
  EXPECT_CONTAINS(newer_include, "new.inc:1:18");
  EXPECT_CONTAINS(newer_include, "written for scene language version 3");
}

TEST(ParameterFile, LookupHelpers) {
  const Block root = parse("A { B { c = 1 } }\nBody { m = 1 }\nBody { m = 2 }\nk = 1\nk = 2\n");
  EXPECT_EQ(root.lookup("A.B.c")->value.number, 1.0);
  EXPECT_EQ(root.lookup("Body[1].m")->value.number, 2.0);
  EXPECT_EQ(root.lookup("Body.m")->value.number, 1.0);  // no index: the first
  EXPECT_EQ(root.lookup("Body[2].m"), nullptr);
  EXPECT_EQ(root.lookup("A.X.c"), nullptr);
  EXPECT_EQ(root.lookup("not a path"), nullptr);
  EXPECT_EQ(root.lookup_block("A.B")->name, "B");
  EXPECT_EQ(root.find("k")->value.number, 2.0);  // the last assignment
  EXPECT_EQ(root.children("Body").size(), 2u);
  EXPECT_EQ(root.child("Missing"), nullptr);

  Block built;
  built.add_parameter({"x", number_value(1), "1", {}});
  Block child;
  child.name = "Child";
  built.add_block(child);
  ASSERT_EQ(built.entries.size(), 2u);
  EXPECT_EQ(built.entries[1].type, BlockEntry::Type::Block);
  EXPECT_EQ(to_text(built), "x = 1\nChild\n{\n}\n");
}

TEST(ParameterFile, LoadsTheStaticTankExample) {
  const Block root = load_parameter_file(FSI_EXAMPLES_DIR "/static_tank/static_tank_coarse.scene");
  EXPECT_DOUBLE_EQ(number_at(root, "Geometry.width"), 0.05);
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.particlespacing"), 0.0016 / 1.9);
  EXPECT_EQ(root.children("RigidBody2D").size(), 2u);
  EXPECT_EQ(root.language_version, 1L);
}

TEST(EditDistance, SuggestsTheNearestName) {
  EXPECT_EQ(edit_distance("width", "widht"), 2u);
  EXPECT_EQ(edit_distance("Solveroptions", "SolverOptions"), 0u);  // case does not count
  EXPECT_EQ(nearest("SolverOption", {"SolverOptions", "Output"}), "SolverOptions");
  EXPECT_EQ(nearest("zzz", {"SolverOptions", "Output"}), "");
}

}  // namespace
}  // namespace fsi::scene
