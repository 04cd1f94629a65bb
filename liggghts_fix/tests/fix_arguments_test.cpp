#include "fsi/contact/fix_arguments.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fsi::contact {
namespace {

std::string error_of(const std::vector<std::string>& words) {
  try {
    parse_fix_fsi_sph_arguments(words, 2);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(FixArguments, ParsesAllKeywords) {
  const std::vector<std::string> words{"k",     "17500", "t", "0.8",    "r0",    "0.002", "cutoff",
                                       "0.003", "gauss", "4", "kernel", "spiky", "law",   "thesis"};
  const auto parsed = parse_fix_fsi_sph_arguments(words, 2);
  EXPECT_EQ(parsed.law.repulsion_scale, 17500.0);
  EXPECT_EQ(parsed.law.viscous_scale, 0.8);
  EXPECT_EQ(parsed.law.equilibrium_distance, 0.002);
  EXPECT_EQ(parsed.law.cutoff, 0.003);
  EXPECT_EQ(parsed.gauss_points, 4);
}

TEST(FixArguments, DefaultsToThreeGaussPoints) {
  const auto parsed = parse_fix_fsi_sph_arguments(
      std::vector<std::string>{"k", "1", "t", "0", "r0", "1", "cutoff", "1"}, 2);
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
  EXPECT_NE(error_of({"k", "1", "t", "0", "r0", "1", "cutoff", "1", "kernel", "gauss"})
                .find("'kernel' needs 'spiky' or 'cubic', got 'gauss'"),
            std::string::npos);
  EXPECT_NE(
      error_of({"k", "1", "t", "0", "r0", "1", "cutoff", "1", "law", "lj", "p1", "2", "p2", "3"})
          .find("p2 < p1"),
      std::string::npos);
  EXPECT_NE(error_of({"k", "1", "t", "0", "r0", "1", "cutoff", "1", "p1", "12"}).find("law lj"),
            std::string::npos);
  EXPECT_NE(error_of({"k", "1", "t", "0", "r0", "1", "cutoff", "1", "triangle", "4"})
                .find("'triangle' needs one of 1, 3, 7"),
            std::string::npos);
  EXPECT_NE(error_of({"k", "1", "t", "0", "r0", "1", "cutoff", "1", "k", "2"}).find("twice"),
            std::string::npos);
  EXPECT_NE(error_of({"k", "1", "t", "0", "r0", "1", "cutoff", "1", "cutoff_visc", "-1"})
                .find("'cutoff_visc' needs a positive length"),
            std::string::npos);
  EXPECT_NE(error_of({"k", "1", "t", "0", "r0", "1", "cutoff", "1", "warn", "1"}).find("'warn'"),
            std::string::npos);
}

TEST(FixArguments, ParsesLawKernelAndCutoffs) {
  const auto parsed = parse_fix_fsi_sph_arguments(
      std::vector<std::string>{"k",        "1", "t",      "2",     "r0",          "0.5",
                               "cutoff",   "1", "law",    "lj",    "p1",          "12",
                               "p2",       "6", "kernel", "cubic", "cutoff_visc", "1.5",
                               "triangle", "3", "warn",   "0.25"},
      2);
  EXPECT_EQ(parsed.law.repulsion_law, RepulsionLaw::LennardJones);
  EXPECT_EQ(parsed.law.lj_p1, 12);
  EXPECT_EQ(parsed.law.lj_p2, 6);
  EXPECT_EQ(parsed.law.viscous_kernel, ViscousKernel::CubicSpline);
  EXPECT_EQ(parsed.law.effective_viscous_cutoff(), 1.5);
  EXPECT_EQ(parsed.law.range(), 1.5);
  EXPECT_EQ(parsed.triangle_points, 3);
  EXPECT_EQ(parsed.warn_fraction, 0.25);
}

TEST(FixArguments, DocumentationListsEveryKeyword) {
  // docs/fix_fsi_sph.md embeds this table; the keyword list and the usage agree with the parser.
  const std::string table = fix_fsi_sph_keyword_table_markdown();
  const std::string usage = fix_fsi_sph_usage();
  for (const char* keyword : {"k", "t", "r0", "cutoff", "cutoff_visc", "law", "p1", "p2", "kernel",
                              "gauss", "triangle", "warn"}) {
    EXPECT_NE(table.find(std::string("| `") + keyword + "` |"), std::string::npos) << keyword;
    EXPECT_NE(usage.find(std::string("  ") + keyword + " "), std::string::npos) << keyword;
  }
}

TEST(FixArguments, DocumentationEmbedsTheGeneratedKeywordTable) {
  std::ifstream in(FSI_SOURCE_DIR "/docs/fix_fsi_sph.md");
  ASSERT_TRUE(in) << "docs/fix_fsi_sph.md not found";
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find(fix_fsi_sph_keyword_table_markdown()), std::string::npos)
      << "docs/fix_fsi_sph.md is out of date; paste this table into its Syntax section:\n"
      << fix_fsi_sph_keyword_table_markdown();
}

}  // namespace
}  // namespace fsi::contact

namespace fsi::contact {
namespace {

TEST(FixArguments, TrueShapeDerivesTheRepulsionFromSpacingAndPressure) {
  const auto parsed = parse_fix_fsi_sph_arguments(
      std::vector<std::string>{"t", "0.5", "spacing", "0.002", "pressure", "490"}, 2);
  EXPECT_TRUE(parsed.uses_true_shape);
  EXPECT_DOUBLE_EQ(parsed.law.cutoff, kTrueShapeCutoffFraction * 0.002);
  EXPECT_NEAR(rest_distance(parsed.law, 490.0, 0.002, 2), kTrueShapeRestFraction * 0.002, 1e-12);
  const auto parsed3d = parse_fix_fsi_sph_arguments(
      std::vector<std::string>{"t", "0.5", "spacing", "0.002", "pressure", "490"}, 3);
  EXPECT_NE(parsed3d.law.repulsion_scale, parsed.law.repulsion_scale);
}

TEST(FixArguments, TrueShapeRefusesMixingWithExplicitRepulsion) {
  auto error = [](std::vector<std::string> words) {
    try {
      parse_fix_fsi_sph_arguments(words, 2);
    } catch (const std::invalid_argument& bad) {
      return std::string(bad.what());
    }
    return std::string();
  };
  EXPECT_NE(error({"t", "1", "spacing", "0.002", "pressure", "490", "k", "100"})
                .find("'k' is derived from 'spacing' and 'pressure'"),
            std::string::npos);
  EXPECT_NE(error({"t", "1", "spacing", "0.002"}).find("needs both 'spacing'"), std::string::npos);
  EXPECT_NE(error({"t", "1", "pressure", "490"}).find("needs both 'spacing'"), std::string::npos);
  EXPECT_NE(error({"t", "1", "spacing", "0", "pressure", "490"}).find("'spacing' needs a positive"),
            std::string::npos);
  EXPECT_NE(error({"t", "1", "k", "1", "r0", "1"}).find("missing keyword 'cutoff'"),
            std::string::npos);
}

}  // namespace
}  // namespace fsi::contact
