#include "command_policy.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fsi::client {
namespace {

std::optional<std::string> check(std::vector<std::string> words) {
  return refused_command(words);
}

TEST(CommandPolicy, RefusesProgramsAndFilesOutsideTheRunDirectory) {
  EXPECT_TRUE(check({"shell", "rm", "-rf", "x"}));
  EXPECT_TRUE(check({"run", "1000", "every", "100", "\"shell touch x\""}));
  EXPECT_TRUE(check({"log", "/tmp/liggghts.log"}));
  EXPECT_TRUE(check({"include", "../../secret.in"}));
  EXPECT_TRUE(check({"write_data", "out/../../x.data"}));
  EXPECT_TRUE(check({"dump", "d", "all", "custom", "100", "~/dump.txt", "id"}));
  EXPECT_TRUE(check({"read_data", "\"/etc/passwd\""}));
  const auto why = check({"log", "/tmp/liggghts.log"});
  ASSERT_TRUE(why);
  EXPECT_NE(why->find("/tmp/liggghts.log"), std::string::npos) << *why;
}

TEST(CommandPolicy, AcceptsTheExampleScriptsKindOfCommands) {
  EXPECT_FALSE(check({"fix", "pressure", "all", "sph/pressure", "Tait", "57142.857", "1000", "7"}));
  EXPECT_FALSE(check({"variable", "alpha", "equal", "0.001/(20*0.000614)"}));
  EXPECT_FALSE(check({"dump", "d", "all", "custom", "100", "dump/particles.*.txt", "id"}));
  EXPECT_FALSE(check({"log", "liggghts.log"}));
  EXPECT_FALSE(check({"pair_style", "sph/artVisc/tensCorr", "spiky2d", "0.000614", "artVisc"}));
  EXPECT_FALSE(check({"fix", "w", "all", "wall/region/sph", "box", "17500", "0.001"}));
  EXPECT_FALSE(check({"thermo_style", "custom", "step", "atoms", "ke", "cpu"}));
}

}  // namespace
}  // namespace fsi::client
