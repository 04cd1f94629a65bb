// Acceptance test of issue 6: the HOTINT parameter file of thesis §5.6, typed into
// tests/data/thesis_5_6.par with its geometry values, parses as written (deviations D1-D3 are
// listed in the file) and reproduces the thesis' derived values.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "fsi/scene/parameter_file.hpp"
#include "fsi/test_support/thrown.hpp"

namespace fsi::scene {
namespace {

const std::string kFile = std::string(FSI_SCENE_TEST_DATA) + "/thesis_5_6.par";

std::string read_fixture() {
  std::ifstream in(kFile);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

double number_at(const Block& root, const std::string& path) {
  const Parameter* parameter = root.lookup(path);
  if (!parameter || parameter->value.kind != ValueKind::Number) {
    ADD_FAILURE() << path << " is not a number parameter";
    return -1.0;
  }
  return parameter->value.number;
}

std::string error_of(const std::string& text) {
  return test_support::message_thrown([&] { parse_parameter_text(text, "thesis.par"); });
}

// Replaces the one occurrence of `from` in `text` (fails the test if it is not there once).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(ThesisParameterFile, ParsesAndReproducesTheDerivedValues) {
  const Block root = load_parameter_file(kFile);

  // SolverOptions, Solution, Linalg, dotted keys at the top level.
  EXPECT_EQ(number_at(root, "SolverOptions.end_time"), 0.7);
  EXPECT_EQ(number_at(root, "SolverOptions.Timeint.max_step_size"), 0.5 * 1e-5);
  EXPECT_EQ(number_at(root, "SolverOptions.Timeint.min_step_size"), 0.5 * 1e-5);
  EXPECT_EQ(root.lookup("SolverOptions.Timeint.tableau_name")->value.text, "LobattoIIIA");
  EXPECT_EQ(number_at(root, "SolverOptions.Timeint.max_stages"), 2.0);
  EXPECT_EQ(number_at(root, "SolverOptions.Timeint.do_implicit_integration"), 1.0);
  EXPECT_EQ(number_at(root, "Solution.write_solution_every_x_step"), 10.0);
  EXPECT_EQ(number_at(root, "Solution.store_data_every"), 0.001);
  EXPECT_EQ(number_at(root, "Linalg.use_sparse_solver"), 0.0);
  EXPECT_EQ(number_at(root, "Newton.max_modified_newton_steps"), 40.0);
  EXPECT_EQ(number_at(root, "LoggingOptions.output_level"), 6.0);

  // Geometry of thesis §6.3.
  EXPECT_EQ(number_at(root, "Geometry.width"), 0.05);
  EXPECT_EQ(number_at(root, "Geometry.height"), 0.1);
  EXPECT_DOUBLE_EQ(number_at(root, "Geometry.fill_level"), 0.04);
  EXPECT_DOUBLE_EQ(number_at(root, "Geometry.piston_y"), 0.0725);
  EXPECT_DOUBLE_EQ(number_at(root, "Geometry.piston_v0"), 0.05);

  // LIGGGHTS_SPH_parameters and the values derived from them.
  const double h = 0.0015;
  const double d = h / 1.9;
  EXPECT_EQ(number_at(root, "LIGGGHTS_SPH_parameters.SPHdensity"), 1000.0);
  EXPECT_EQ(number_at(root, "LIGGGHTS_SPH_parameters.smoothinglength"), h);
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.particlespacing"), d);
  // SPHparticlemass = SPHdensity*particlespacing^2 = 6.2327e-4 kg/m.
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.SPHparticlemass"), 1000.0 * d * d);
  EXPECT_NEAR(number_at(root, "LIGGGHTS_SPH_parameters.SPHparticlemass"), 6.2327e-4, 1e-8);
  EXPECT_EQ(number_at(root, "LIGGGHTS_SPH_parameters.cAB"), 20.0);
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.highviscosity"), 0.1);
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.xmin"), -0.01);
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.xmax"), 0.05);
  EXPECT_EQ(number_at(root, "LIGGGHTS_SPH_parameters.ymax"), 0.1);
  EXPECT_EQ(number_at(root, "LIGGGHTS_SPH_parameters.zmin"), -10.0);
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.SPH_wall_cutoff"), 2 * h);
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.SPH_wall_equilibriumdist"), 2 * h);
  EXPECT_EQ(number_at(root, "LIGGGHTS_SPH_parameters.SPH_wall_rep"), 17500.0);
  // SPH_wall_visc = SPHdensity*viscosity/smoothinglength (thesis eq. 6.4) = 0.6667 kg/(m s).
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.SPH_wall_visc"), 1000.0 * 1e-3 / h);
  EXPECT_EQ(number_at(root, "LIGGGHTS_SPH_parameters.equilibration_steps"), 100000.0);
  EXPECT_EQ(number_at(root, "LIGGGHTS_SPH_parameters.refinement_option"), 2.0);
  EXPECT_DOUBLE_EQ(number_at(root, "LIGGGHTS_SPH_parameters.refinement_resolution"), 4 * h);
  EXPECT_EQ(number_at(root, "TCP_data.port"), 12345.0);
  EXPECT_EQ(number_at(root, "TCP_data.ip4"), 1.0);

  // Every block of the listing, in its order.
  std::vector<std::string> blocks;
  for (const Block& block : root.blocks)
    blocks.push_back(block.name);
  EXPECT_EQ(blocks, (std::vector<std::string>{"SolverOptions", "Solution", "Linalg", "Newton",
                                              "LoggingOptions", "Geometry",
                                              "LIGGGHTS_SPH_parameters", "TCP_data"}));
}

// D2: without the lost "Geometry {" line the closing brace of line 40 has no block.
TEST(ThesisParameterFile, DeviationD2TheLostBlockHeaderIsNeeded) {
  const std::string text = replaced(read_fixture(), "Geometry\n{\n", "");
  EXPECT_NE(error_of(text).find("'}' without an open block"), std::string::npos) << error_of(text);
}

// D3: the printed "Geometry.offset_x_" is an undefined reference, reported with the fix.
TEST(ThesisParameterFile, DeviationD3TheTypoIsReportedWithASuggestion) {
  const std::string text = replaced(read_fixture(), "xmax = 0.05 + Geometry.offset_x\n",
                                    "xmax = 0.05 + Geometry.offset_x_\n");
  const std::string error = error_of(text);
  EXPECT_NE(error.find("has no parameter 'offset_x_'"), std::string::npos) << error;
  EXPECT_NE(error.find("did you mean 'Geometry.offset_x'?"), std::string::npos) << error;
}

// D1: a wrapped comment line printed on its own is not an entry.
TEST(ThesisParameterFile, DeviationD1AWrappedCommentLineIsAnError) {
  const std::string text =
      replaced(read_fixture(), "full exchange of SPH data\n", "full\n    exchange of SPH data\n");
  EXPECT_NE(error_of(text).find("'exchange' is followed by neither '=' nor '{'"), std::string::npos)
      << error_of(text);
}

}  // namespace
}  // namespace fsi::scene
