#include "fsi/contact/fix_arguments.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace fsi::contact {
namespace {

std::string error_of(const std::vector<std::string>& words) {
  try {
    parse_fix_fsi_sph_arguments(words);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(FixArguments, ParsesAllKeywords) {
  const std::vector<std::string> words{"k",     "17500", "t", "0.8",    "r0",    "0.002", "cutoff",
                                       "0.003", "gauss", "4", "kernel", "spiky", "law",   "thesis"};
  const auto parsed = parse_fix_fsi_sph_arguments(words);
  EXPECT_EQ(parsed.law.repulsion_scale, 17500.0);
  EXPECT_EQ(parsed.law.viscous_scale, 0.8);
  EXPECT_EQ(parsed.law.equilibrium_distance, 0.002);
  EXPECT_EQ(parsed.law.cutoff, 0.003);
  EXPECT_EQ(parsed.gauss_points, 4);
}

TEST(FixArguments, DefaultsToThreeGaussPoints) {
  const auto parsed = parse_fix_fsi_sph_arguments(
      std::vector<std::string>{"k", "1", "t", "0", "r0", "1", "cutoff", "1"});
  EXPECT_EQ(parsed.gauss_points, 3);
}

TEST(FixArguments, ErrorsNameTheProblem) {
  EXPECT_NE(error_of({"k", "1", "t", "0", "r0", "1"}).find("missing keyword 'cutoff'"),
            std::string::npos);
  EXPECT_NE(error_of({"kk", "1"}).find("unknown keyword 'kk'"), std::string::npos);
  EXPECT_NE(
      error_of({"k", "abc", "t", "0", "r0", "1", "cutoff", "1"}).find("'k' needs a finite number"),
      std::string::npos);
  EXPECT_NE(error_of({"k", "1", "t", "0", "r0", "1", "cutoff", "1", "gauss", "7"}).find("gauss"),
            std::string::npos);
  EXPECT_NE(error_of({"k", "1", "t", "0", "r0", "2", "cutoff", "1"}).find("r0"), std::string::npos);
  EXPECT_NE(error_of({"k", "1", "t"}).find("has no value"), std::string::npos);
  EXPECT_NE(error_of({"k", "1", "t", "0", "r0", "1", "cutoff", "1", "kernel", "cubic"})
                .find("kernel 'cubic'"),
            std::string::npos);
}

}  // namespace
}  // namespace fsi::contact
