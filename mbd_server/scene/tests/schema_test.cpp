#include <gtest/gtest.h>

#include <functional>

#include "fsi/common/error.hpp"
#include "fsi/scene/schema.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

using testing::listing;

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

BlockSpec test_spec() {
  const BlockSpec timeint =
      block_spec("Timeint", "time integration",
                 {number("step_size", "s", "fixed time step").positive(),
                  integer("stages", "Radau IIA stages").between(1, 3).with_default(3),
                  text("tableau", "integration scheme")
                      .one_of({"RadauIIA", "LobattoIIIA"})
                      .with_default("RadauIIA")})
          .as_required();
  const BlockSpec solver =
      block_spec("SolverOptions", "solver settings",
                 {number("end_time", "s", "simulated time").positive()}, {timeint})
          .as_required();
  const BlockSpec mesh =
      block_spec("Mesh", "surface polyline",
                 {matrix("points", 2, "m", "vertices, one [x, y] per row").at_least(-10),
                  integer("closed", "1: join the last point to the first | or not")
                      .between(0, 1)
                      .with_default(0)})
          .as_list();
  const BlockSpec body =
      block_spec("RigidBody2D", "a planar rigid body",
                 {text("name", "unique name"), number("mass", "kg", "mass").positive(),
                  vector("position", 2, "m", "centre of mass").with_default({0.0, 0.0}),
                  number("angle", "rad", "initial angle").optional()},
                 {mesh})
          .as_list();
  const BlockSpec sph =
      block_spec("LIGGGHTS_SPH_parameters", "LIGGGHTS variables",
                 {number("smoothinglength", "m", "smoothing length h").positive()})
          .as_open();
  const BlockSpec gravity =
      block_spec("Gravity", "uniform gravity",
                 {vector("acceleration", 2, "m/s^2", "acceleration").with_default({0.0, -9.81})});
  BlockSpec root = block_spec("", "a scene", {}, {solver, body, sph, gravity});
  root.user_blocks_allowed = true;
  return root;
}

std::vector<Problem> problems_of(const std::string& text) {
  return validate(parse_parameter_text(text, "s.scene"), test_spec());
}

TEST(Schema, ReportsEveryProblemAtOnce) {
  const std::vector<Problem> problems = problems_of(
      "SolverOptions { end_time = -1\n"
      "  Timeint { step_size = 0; stages = 2.5; tableau = \"Euler\"; stepsize = 1 }\n"
      "}\n"
      "RigidBody2D { mass = \"heavy\"; position = [1, 2, 3] }\n"
      "RigidBody2D { name = \"b\"; mass = 1; Mesh { points = [[0, 0, 0]] } }\n"
      "SolverOptoins { end_time = 1 }\n"
      "Geometry { anything = 1 }\n"
      "LIGGGHTS_SPH_parameters { smoothinglength = 0; cAB = 20; smoothinglenght = 1 }\n"
      "Gravity { acceleration = [0, -9.81] }\n"
      "Gravity { acceleration = 5 }\n"
      "loose = 1\n");
  const std::string all = listing(problems);
  EXPECT_EQ(problems.size(), 15u) << all;
  EXPECT_CONTAINS(all, "s.scene:1:17: 'SolverOptions.end_time' = -1 s is out of range (> 0 s)");
  EXPECT_CONTAINS(all,
                  "s.scene:2:13: 'SolverOptions.Timeint.step_size' = 0 s is out of range (> 0 s); "
                  "choose a value > 0 s");
  EXPECT_CONTAINS(all,
                  "s.scene:2:28: 'SolverOptions.Timeint.stages' must be a whole number, not 2.5");
  EXPECT_CONTAINS(all,
                  "s.scene:2:42: 'SolverOptions.Timeint.tableau' = \"Euler\" is not one of "
                  "\"RadauIIA\", \"LobattoIIIA\"");
  EXPECT_CONTAINS(all,
                  "s.scene:2:61: unknown parameter 'SolverOptions.Timeint.stepsize'; did you mean "
                  "'step_size'?");
  EXPECT_CONTAINS(all, "s.scene:4:15: 'RigidBody2D[0].mass' must be a number, not a string");
  EXPECT_CONTAINS(all, "s.scene:4:31: 'RigidBody2D[0].position' has 3 components, it needs 2");
  EXPECT_CONTAINS(all,
                  "s.scene:4:1: required parameter 'RigidBody2D[0].name' is missing (unique name)");
  EXPECT_CONTAINS(all,
                  "s.scene:5:44: 'RigidBody2D[1].Mesh.points' row 1 has 3 values, it needs 2");
  EXPECT_CONTAINS(all,
                  "s.scene:6:1: unknown block 'SolverOptoins'; did you mean 'SolverOptions'? If "
                  "this is your own parameter block, rename it");
  EXPECT_CONTAINS(all,
                  "s.scene:8:27: 'LIGGGHTS_SPH_parameters.smoothinglength' = 0 m is out of range");
  EXPECT_CONTAINS(all,
                  "s.scene:8:58: unknown parameter 'LIGGGHTS_SPH_parameters.smoothinglenght'; did "
                  "you mean 'smoothinglength'? If this is a key of your own, rename it");
  EXPECT_CONTAINS(all, "s.scene:10:1: block 'Gravity' is given twice (first at s.scene:9:1)");
  EXPECT_CONTAINS(all,
                  "s.scene:10:11: 'Gravity[1].acceleration' must be a vector, not a number (5)");
  EXPECT_CONTAINS(all,
                  "s.scene:11:1: unknown parameter 'loose'; put parameters of your own into a "
                  "block of your own");
  // User blocks and the user's own keys in open blocks are accepted.
  EXPECT_EQ(all.find("'Geometry"), std::string::npos) << all;
  EXPECT_EQ(all.find("cAB"), std::string::npos) << all;
}

TEST(Schema, ABlockGivenTwiceIsOneProblemWithoutFollowOns) {
  // The second copy lacks end_time and Timeint.step_size: merged into the first it would not, so
  // the only mistake is the second copy itself. Its own values are still checked.
  const std::vector<Problem> problems = problems_of(
      "SolverOptions { end_time = 1; Timeint { step_size = 1e-3 } }\n"
      "SolverOptions { Timeint { stages = 7 } }\n");
  const std::string all = listing(problems);
  ASSERT_EQ(problems.size(), 2u) << all;
  EXPECT_EQ(problems[0].text(),
            "s.scene:2:1: block 'SolverOptions' is given twice (first at s.scene:1:1); merge the "
            "two blocks; only element lists may repeat");
  EXPECT_CONTAINS(all, "s.scene:2:27: 'SolverOptions[1].Timeint.stages' = 7 is out of range");
}

TEST(Schema, RangesMissingBlocksAndMixedUpEntries) {
  const std::vector<Problem> problems = problems_of(
      "SolverOptions { end_time { }\n"
      "  Timeint { step_size = 1; stages = 4 }\n"
      "}\n"
      "Gravity = 3\n"
      "RigidBody2D { name = \"a\"; mass = 1; Mesh { points = [[0, -11]]; closed = -1 } }\n");
  const std::string all = listing(problems);
  EXPECT_EQ(problems.size(), 6u) << all;
  EXPECT_CONTAINS(all, "s.scene:1:17: 'SolverOptions.end_time' is a parameter, not a block");
  EXPECT_CONTAINS(all, "s.scene:1:1: required parameter 'SolverOptions.end_time' is missing");
  EXPECT_CONTAINS(
      all, "s.scene:2:28: 'SolverOptions.Timeint.stages' = 4 is out of range (>= 1 and <= 3)");
  EXPECT_CONTAINS(all, "s.scene:4:1: 'Gravity' is a block, not a parameter");
  EXPECT_CONTAINS(all, "'RigidBody2D.Mesh.points[0][1]' = -11 m is out of range (>= -10 m)");
  EXPECT_CONTAINS(all, "'RigidBody2D.Mesh.closed' = -1 is out of range (>= 0 and <= 1)");

  const std::vector<Problem> empty = problems_of("Geometry { width = 1 }\n");
  ASSERT_EQ(empty.size(), 1u) << listing(empty);
  EXPECT_EQ(empty[0].location.text(), "s.scene");
  EXPECT_CONTAINS(
      empty[0].text(),
      "required block 'SolverOptions' is missing (solver settings); add SolverOptions { "
      "... } to the top level");
}

TEST(Schema, ThrowIfAnyListsEveryProblemInOneError) {
  EXPECT_NO_THROW(throw_if_any({}, "s.scene"));
  const std::vector<Problem> problems = problems_of("SolverOptions { end_time = -1 }\nloose = 1\n");
  ASSERT_EQ(problems.size(), 3u);
  try {
    throw_if_any(problems, "s.scene");
    FAIL() << "no error thrown";
  } catch (const fsi::Error& error) {
    const std::string text = error.what();
    EXPECT_CONTAINS(text, "s.scene: 3 problem(s)");
    EXPECT_CONTAINS(text, "\n  s.scene:1:17: 'SolverOptions.end_time'");
    EXPECT_CONTAINS(text, "\n  s.scene:1:1: required block 'SolverOptions.Timeint'");
    EXPECT_CONTAINS(text, "\n  s.scene:2:1: unknown parameter 'loose'");
  }
}

TEST(Schema, ViewAppliesDefaults) {
  const Block root = parse_parameter_text(
      "SolverOptions { end_time = 1; Timeint { step_size = 1e-5 } }\n"
      "RigidBody2D { name = \"a\"; mass = 1 }\n"
      "RigidBody2D { name = \"b\"; mass = 2; position = [1, 2]; angle = 0.5\n"
      "  Mesh { points = [[0, 0], [1, 0]] } }\n"
      "LIGGGHTS_SPH_parameters { smoothinglength = 0.001; cAB = 20; label = \"x\" }\n"
      "Geometry { width = 0.05 }\n",
      "s.scene");
  const BlockSpec spec = test_spec();
  ASSERT_TRUE(validate(root, spec).empty()) << listing(validate(root, spec));
  const View view(root, spec);
  const View timeint = view.block("SolverOptions").block("Timeint");
  EXPECT_EQ(timeint.number("step_size"), 1e-5);
  EXPECT_EQ(timeint.integer("stages"), 3);
  EXPECT_EQ(timeint.string("tableau"), "RadauIIA");
  EXPECT_FALSE(timeint.has("stages"));

  const std::vector<View> bodies = view.blocks("RigidBody2D");
  ASSERT_EQ(bodies.size(), 2u);
  EXPECT_EQ(bodies[0].vector("position"), (std::vector<double>{0, 0}));
  EXPECT_FALSE(bodies[0].has("position"));
  EXPECT_EQ(bodies[0].location("position").line, 2);  // absent: the block's place
  EXPECT_EQ(bodies[1].vector("position"), (std::vector<double>{1, 2}));
  EXPECT_EQ(bodies[1].location("position").line, 3);
  EXPECT_EQ(bodies[1].location("position").column, 37);
  EXPECT_FALSE(bodies[0].has("angle"));
  EXPECT_THROW((void)bodies[0].number("angle"), fsi::Error);  // optional, no default
  EXPECT_EQ(bodies[1].number("angle"), 0.5);
  ASSERT_EQ(bodies[1].blocks("Mesh").size(), 1u);
  EXPECT_EQ(bodies[1].blocks("Mesh")[0].matrix("points"), (NumberMatrix{{0, 0}, {1, 0}}));
  EXPECT_EQ(bodies[1].blocks("Mesh")[0].integer("closed"), 0);
  EXPECT_TRUE(bodies[0].blocks("Mesh").empty());

  // An absent block reads as its defaults.
  EXPECT_FALSE(view.has_block("Gravity"));
  EXPECT_EQ(view.block("Gravity").vector("acceleration"), (std::vector<double>{0, -9.81}));
  // Open blocks and user blocks give access to the user's own keys.
  const View sph = view.block("LIGGGHTS_SPH_parameters");
  EXPECT_EQ(sph.number("cAB"), 20.0);
  EXPECT_EQ(sph.string("label"), "x");
  EXPECT_THROW((void)sph.number("label"), fsi::Error);
  EXPECT_THROW((void)sph.number("absent"), fsi::Error);
  EXPECT_EQ(view.block("Geometry").number("width"), 0.05);
}

TEST(Schema, DeclarationBuilders) {
  const ParameterSpec step = number("step", "s", "doc").positive().at_most(1).with_default(0.5);
  EXPECT_EQ(step.minimum, 0.0);
  EXPECT_TRUE(step.minimum_exclusive);
  EXPECT_EQ(step.maximum, 1.0);
  EXPECT_EQ(step.default_value, number_value(0.5));
  EXPECT_FALSE(step.is_required());
  EXPECT_TRUE(number("x", "m", "doc").is_required());
  EXPECT_FALSE(number("x", "m", "doc").optional().is_required());
  EXPECT_EQ(text("t", "doc").with_default("a").default_value, text_value("a"));
  EXPECT_EQ(vector("v", 2, "m", "doc").with_default({1.0, 2.0}).default_value,
            vector_value({1, 2}));
  EXPECT_EQ(matrix("m", 2, "m", "doc").with_default(NumberMatrix{{1, 2}}).default_value,
            matrix_value({{1, 2}}));
  const ParameterSpec bounded = integer("n", "doc").between(1, 3).above(0);
  EXPECT_EQ(bounded.minimum, 0.0);
  EXPECT_TRUE(bounded.minimum_exclusive);
  EXPECT_EQ(bounded.maximum, 3.0);
  EXPECT_EQ(text("t", "doc").one_of({"a", "b"}).choices, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(vector("v", 2, "m", "doc").with_length(3).length, 3u);
  const BlockSpec list = block_spec("B", "doc", {step}).as_list().as_required().as_open();
  EXPECT_TRUE(list.repeated && list.required && list.open);
  EXPECT_NE(list.parameter("step"), nullptr);
  EXPECT_EQ(list.parameter("other"), nullptr);
}

TEST(Schema, RenderersListEveryParameter) {
  const BlockSpec spec = test_spec();
  const std::string help = render_help(spec);
  const std::string markdown = render_markdown(spec);
  std::size_t parameters = 0;
  std::function<void(const BlockSpec&, const std::string&)> check = [&](const BlockSpec& block,
                                                                        const std::string& path) {
    if (!path.empty()) {
      EXPECT_CONTAINS(markdown, "## `" + path + "`");
    }
    for (const ParameterSpec& parameter : block.parameters) {
      ++parameters;
      const std::string full = path.empty() ? parameter.key : path + "." + parameter.key;
      EXPECT_CONTAINS(help, "  " + full + "  " + std::string(name(parameter.kind)));
      EXPECT_CONTAINS(help, parameter.doc);
      EXPECT_CONTAINS(markdown, "| `" + parameter.key + "` | " + std::string(name(parameter.kind)));
      if (!parameter.unit.empty()) {
        EXPECT_CONTAINS(help, "[" + parameter.unit + "]");
      }
    }
    for (const BlockSpec& child : block.blocks)
      check(child, path.empty() ? child.name : path + "." + child.name);
  };
  check(spec, "");
  EXPECT_EQ(parameters, 12u);
  EXPECT_CONTAINS(help, "SolverOptions.Timeint.stages  integer  default 3  allowed: >= 1 and <= 3");
  EXPECT_CONTAINS(help, "SolverOptions.end_time  number [s]  (required)  allowed: > 0");
  EXPECT_CONTAINS(help, "RigidBody2D.angle  number [rad]  (optional)");
  EXPECT_CONTAINS(markdown,
                  "| `tableau` | string | – | \"RadauIIA\" | \"RadauIIA\", \"LobattoIIIA\" | "
                  "integration scheme |");
  EXPECT_CONTAINS(markdown, "## `RigidBody2D` (element list: may appear several times)");
  EXPECT_CONTAINS(markdown, "Also takes keys and blocks of your own.");
  // Every table row has exactly six cells, even with '|' in a doc string.
  std::size_t rows = 0;
  std::size_t start = 0;
  while ((start = markdown.find("\n| `", start)) != std::string::npos) {
    const std::size_t end = markdown.find('\n', start + 1);
    const std::string row = markdown.substr(start + 1, end - start - 1);
    std::size_t separators = 0;
    for (std::size_t i = 0; i < row.size(); ++i)
      separators += row[i] == '|' && (i == 0 || row[i - 1] != '\\');
    EXPECT_EQ(separators, 7u) << row;
    ++rows;
    start = end;
  }
  EXPECT_EQ(rows, parameters);
}

}  // namespace
}  // namespace fsi::scene
