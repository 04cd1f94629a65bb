#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/output/series.hpp"

namespace fsi::output {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class SeriesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ =
        fs::temp_directory_path() /
        ("fsi_output_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }
  fs::path directory_;
};

TEST(Collection, OneDataSetPerEntryWithItsTime) {
  const std::string text =
      encode_collection({{0.0, "fluid_000000000.vtu"}, {0.0025, "fluid_000000250.vtu"}});
  EXPECT_EQ(text,
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0\" part=\"0\" file=\"fluid_000000000.vtu\"/>\n"
            "    <DataSet timestep=\"0.0025000000000000001\" part=\"0\" "
            "file=\"fluid_000000250.vtu\"/>\n"
            "  </Collection>\n"
            "</VTKFile>\n");
}

TEST_F(SeriesTest, IndexIsRewrittenAfterEveryFile) {
  Series series(directory_, "fluid", "vtu");
  const fs::path first = series.write(250, 0.0025, "first");
  EXPECT_EQ(first, directory_ / "fluid_000000250.vtu");
  EXPECT_EQ(read(first), "first");
  EXPECT_EQ(read(series.index_path()), encode_collection({{0.0025, "fluid_000000250.vtu"}}));

  series.write(500, 0.005, "second");
  EXPECT_EQ(read(directory_ / "fluid_000000500.vtu"), "second");
  EXPECT_EQ(read(directory_ / "fluid.pvd"),
            encode_collection({{0.0025, "fluid_000000250.vtu"}, {0.005, "fluid_000000500.vtu"}}));
  EXPECT_EQ(series.entries().size(), 2u);
  // No temporary file is left behind.
  for (const auto& entry : fs::directory_iterator(directory_))
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
}

TEST_F(SeriesTest, UnwritableFolderSaysWhatWhereAndHowToFix) {
  Series series(directory_ / "missing", "boundary", "vtu");
  try {
    series.write(1, 0.0, "x");
    FAIL() << "writing into a missing folder did not throw";
  } catch (const fsi::Error& error) {
    EXPECT_NE(error.fault().find("missing/boundary_000000001.vtu.tmp"), std::string::npos)
        << error.what();
    EXPECT_NE(error.remedy().find("missing"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace fsi::output
