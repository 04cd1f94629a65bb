#include "fsi/contact/script_text.hpp"

#include <gtest/gtest.h>

namespace fsi::contact {
namespace {

using Words = std::vector<std::string>;

TEST(ScriptText, CommandsKeepTheirFirstLineAndJoinContinuations) {
  const auto commands = script_commands(
      "# a comment line\n"
      "\n"
      "fix fsi all fsi/sph k 2000 &\n"
      "    t 50   # the wall friction\n"
      "variable name string \"a # b\"  # comment after a quoted '#'\r\n"
      "run 10");
  ASSERT_EQ(commands.size(), 3u);
  EXPECT_EQ(commands[0].line, 3);
  EXPECT_EQ(commands[0].words, (Words{"fix", "fsi", "all", "fsi/sph", "k", "2000", "t", "50"}));
  EXPECT_EQ(commands[1].line, 5);
  EXPECT_EQ(commands[1].words, (Words{"variable", "name", "string", "a # b"}));
  EXPECT_EQ(commands[2].line, 6);
  EXPECT_EQ(commands[2].words, (Words{"run", "10"}));
}

TEST(ScriptText, AnAmpersandBeforeACommentDoesNotContinue) {
  // LAMMPS looks at the last character of the line as read, comment included.
  const auto commands = script_commands("fix a all gravity 9.81 & # no continuation\nrun 1\n");
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_EQ(commands[0].words.back(), "&");
  EXPECT_EQ(commands[1].line, 2);
}

TEST(ScriptText, ReferencedVariablesOutsideQuotes) {
  EXPECT_EQ(referenced_variables("pair_style sph ${h} $c v_x $(1+2) '${quoted}' \"$q\""),
            (Words{"h", "c"}));
  EXPECT_TRUE(referenced_variables("variable a equal 2*v_b").empty());
  EXPECT_EQ(referenced_variables("print ${unterminated"), Words{});
}

TEST(ScriptText, SubstituteVariablesReplacesBracedAndOneCharacterNames) {
  const VariableLookup value_of = [](const std::string& name) -> std::optional<std::string> {
    if (name == "h") return "0.0038";
    if (name == "c") return "20";
    if (name == "rho0") return "1000.";
    return std::nullopt;
  };
  EXPECT_EQ(substitute_variables("${rho0}*${h}", value_of), "1000.*0.0038");
  EXPECT_EQ(substitute_variables("$c/2", value_of), "20/2");
  EXPECT_EQ(substitute_variables("plain", value_of), "plain");
  EXPECT_EQ(substitute_variables("", value_of), "");
  // A '$' at the end of a word stays (LIGGGHTS has nothing to substitute there).
  EXPECT_EQ(substitute_variables("cost$", value_of), "cost$");
}

TEST(ScriptText, SubstituteVariablesRefusesUnknownNamesAndOpenBraces) {
  const VariableLookup value_of = [](const std::string& name) -> std::optional<std::string> {
    if (name == "h") return "0.0038";
    return std::nullopt;
  };
  EXPECT_EQ(substitute_variables("${undefined}", value_of), std::nullopt);
  EXPECT_EQ(substitute_variables("2*$x", value_of), std::nullopt);  // $x: the variable "x"
  EXPECT_EQ(substitute_variables("${h", value_of), std::nullopt);
  EXPECT_EQ(substitute_variables("${h}${h}", value_of), "0.00380.0038");
}

}  // namespace
}  // namespace fsi::contact
