#include <gtest/gtest.h>

#include "fsi/common/error.hpp"
#include "fsi/scene/schema.hpp"

namespace fsi::scene {
namespace {

BlockSpec test_spec() {
  ParameterSpec step = number("step_size", "s", "fixed time step");
  step.minimum = 0.0;
  step.minimum_exclusive = true;
  ParameterSpec stages = integer("stages", "Radau IIA stages");
  stages.default_value = number_value(3);
  stages.minimum = 1;
  stages.maximum = 3;
  ParameterSpec tableau = text("tableau", "integration scheme");
  tableau.default_value = text_value("RadauIIA");
  tableau.choices = {"RadauIIA"};
  BlockSpec timeint{"Timeint", "time integration",      false, true,
                    false,     {step, stages, tableau}, {},    false};
  ParameterSpec name_spec = text("name", "body name");
  ParameterSpec position = vector("position", 2, "m", "centre of mass");
  position.default_value = vector_value({0, 0});
  BlockSpec body{"RigidBody2D", "a planar rigid body", true, false,
                 false,         {name_spec, position}, {},   false};
  BlockSpec root;
  root.blocks = {timeint, body};
  root.user_blocks_allowed = true;
  return root;
}

std::vector<Problem> problems_of(const std::string& text) {
  return validate(parse_parameter_text(text, "s.scene"), test_spec());
}

TEST(Schema, ReportsEveryProblemAtOnce) {
  const auto problems = problems_of(
      "Timeint { step_size = -1; stages = 2.5; tableau = \"Euler\"; stepsize = 1 }\n"
      "RigidBody2D { position = [1, 2, 3] }\n"
      "Timent { end_time = 1 }\n"
      "Geometry { anything = 1 }\n");
  std::string all;
  for (const auto& p : problems)
    all += p.text() + "\n";
  EXPECT_EQ(problems.size(), 7u) << all;
  EXPECT_NE(all.find("'Timeint.step_size' = -1 s is out of range (> 0)"), std::string::npos) << all;
  EXPECT_NE(all.find("'Timeint.stages' must be an integer"), std::string::npos) << all;
  EXPECT_NE(all.find("\"Euler\" is not one of \"RadauIIA\""), std::string::npos) << all;
  EXPECT_NE(all.find("unknown parameter 'Timeint.stepsize'"), std::string::npos) << all;
  EXPECT_NE(all.find("did you mean 'step_size'?"), std::string::npos) << all;
  EXPECT_NE(all.find("'RigidBody2D.position' needs 2 components"), std::string::npos) << all;
  EXPECT_NE(all.find("'RigidBody2D.name' is missing"), std::string::npos) << all;
  EXPECT_NE(all.find("unknown block 'Timent'"), std::string::npos) << all;
  EXPECT_EQ(all.find("Geometry"), std::string::npos) << "user blocks are allowed: " << all;
  EXPECT_NE(all.find("s.scene:1:11"), std::string::npos) << all;
}

TEST(Schema, MissingRequiredBlockAndDuplicateBlock) {
  auto problems = problems_of("RigidBody2D { name = \"a\" }\n");
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].message.find("block 'Timeint' is missing"), std::string::npos);
  problems = problems_of("Timeint { step_size = 1 }\nTimeint { step_size = 2 }\n");
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].message.find("given twice"), std::string::npos);
  EXPECT_THROW(throw_if_any(problems, "s.scene"), fsi::Error);
}

TEST(Schema, ViewAppliesDefaults) {
  const Block root = parse_parameter_text(
      "Timeint { step_size = 1e-5 }\nRigidBody2D { name = \"a\" }\nRigidBody2D { name = \"b\"; "
      "position = [1, 2] }\n",
      "s.scene");
  const BlockSpec spec = test_spec();
  ASSERT_TRUE(validate(root, spec).empty());
  const View view(root, spec);
  EXPECT_EQ(view.block("Timeint").number("step_size"), 1e-5);
  EXPECT_EQ(view.block("Timeint").integer("stages"), 3);
  EXPECT_EQ(view.block("Timeint").string("tableau"), "RadauIIA");
  const auto bodies = view.blocks("RigidBody2D");
  ASSERT_EQ(bodies.size(), 2u);
  EXPECT_EQ(bodies[0].vector("position"), (std::vector<double>{0, 0}));
  EXPECT_EQ(bodies[1].vector("position"), (std::vector<double>{1, 2}));
  EXPECT_FALSE(bodies[0].has("position"));
  EXPECT_EQ(bodies[1].location("position").line, 3);
}

TEST(Schema, RenderersListEveryParameter) {
  const BlockSpec spec = test_spec();
  const std::string help = render_help(spec);
  const std::string markdown = render_markdown(spec);
  for (const char* key : {"Timeint.step_size", "Timeint.stages", "Timeint.tableau",
                          "RigidBody2D.name", "RigidBody2D.position"}) {
    EXPECT_NE(help.find(key), std::string::npos) << key;
  }
  for (const char* key :
       {"`step_size`", "`stages`", "`tableau`", "`name`", "`position`", "## `Timeint`"}) {
    EXPECT_NE(markdown.find(key), std::string::npos) << key;
  }
}

}  // namespace
}  // namespace fsi::scene
