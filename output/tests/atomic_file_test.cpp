#include <gtest/gtest.h>

#include <cerrno>
#include <filesystem>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/output/atomic_file.hpp"
#include "fsi/test_support/folder_per_test.hpp"

namespace fsi::output {
namespace {

namespace fs = std::filesystem;

using test_support::file_text;

using AtomicFileTest = test_support::FolderPerTest;

TEST_F(AtomicFileTest, ReplacesTheFileAndLeavesNoTemporary) {
  const fs::path path = folder_ / "run.json";
  write_file_atomically(path, "first");
  write_file_atomically(path, "second, longer", Durability::MachineCrash);
  EXPECT_EQ(file_text(path), "second, longer");
  EXPECT_FALSE(fs::exists(folder_ / "run.json.tmp"));
}

// A full disk while writing: the old file stays whole, the temporary goes, the message names the
// file, the system's reason and the fix. /dev/full fails every write with ENOSPC; the temporary
// name pointing there stands in for a disk that fills up during the write.
TEST_F(AtomicFileTest, FullDiskKeepsTheOldFileAndSaysSo) {
  const fs::path path = folder_ / "run.json";
  write_file_atomically(path, "the old manifest");
  fs::create_symlink("/dev/full", folder_ / "run.json.tmp");
  try {
    write_file_atomically(path, "the new manifest");
    FAIL() << "a write to a full disk did not throw";
  } catch (const fsi::Error& error) {
    EXPECT_NE(error.fault().find(path.string()), std::string::npos) << error.what();
    EXPECT_NE(error.fault().find("No space left on device"), std::string::npos) << error.what();
    EXPECT_NE(error.remedy().find("free space"), std::string::npos) << error.what();
  }
  EXPECT_EQ(file_text(path), "the old manifest");
  EXPECT_FALSE(fs::exists(fs::symlink_status(folder_ / "run.json.tmp")));
}

TEST_F(AtomicFileTest, MissingFolderNamesTheFile) {
  try {
    write_file_atomically(folder_ / "gone" / "sensors.csv", "x");
    FAIL() << "writing into a missing folder did not throw";
  } catch (const fsi::Error& error) {
    EXPECT_NE(error.fault().find("gone/sensors.csv.tmp"), std::string::npos) << error.what();
    EXPECT_NE(error.remedy().find("missing"), std::string::npos) << error.what();
  }
}

TEST(FileError, TheFixFollowsTheReason) {
  EXPECT_NE(file_error("cannot write", "/d/f", ENOSPC, "x").remedy().find("df -h /d"),
            std::string::npos);
  EXPECT_NE(file_error("cannot write", "/d/f", EROFS, "x").remedy().find("writable"),
            std::string::npos);
  EXPECT_NE(file_error("cannot write", "/d/f", EACCES, "x").remedy().find("writable"),
            std::string::npos);
}

}  // namespace
}  // namespace fsi::output
