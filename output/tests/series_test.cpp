#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/output/series.hpp"
#include "fsi/test_support/folder_per_test.hpp"

namespace fsi::output {
namespace {

namespace fs = std::filesystem;

using test_support::file_text;

using SeriesTest = test_support::FolderPerTest;

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
  Series series(folder_, "fluid", "vtu");
  const fs::path first = series.write(250, 0.0025, "first");
  EXPECT_EQ(first, folder_ / "fluid_000000250.vtu");
  EXPECT_EQ(file_text(first), "first");
  EXPECT_EQ(file_text(series.index_path()), encode_collection({{0.0025, "fluid_000000250.vtu"}}));

  series.write(500, 0.005, "second");
  EXPECT_EQ(file_text(folder_ / "fluid_000000500.vtu"), "second");
  EXPECT_EQ(file_text(folder_ / "fluid.pvd"),
            encode_collection({{0.0025, "fluid_000000250.vtu"}, {0.005, "fluid_000000500.vtu"}}));
  EXPECT_EQ(series.entries().size(), 2u);
  // No temporary file is left behind.
  for (const auto& entry : fs::directory_iterator(folder_))
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
}

TEST_F(SeriesTest, UnwritableFolderSaysWhatWhereAndHowToFix) {
  Series series(folder_ / "missing", "boundary", "vtu");
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
